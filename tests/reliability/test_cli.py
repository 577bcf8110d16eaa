"""The command line: no traceback for a user's mistake or an environment fault; exit 2 (input), 1 (run)."""

import pytest

from rotorcosim.master.cli import main


def call(capsys, *argv):
    rc = main(list(argv))
    out, err = capsys.readouterr()
    return rc, out, err


def one_line_error(err: str) -> str:
    lines = [l for l in err.splitlines() if l.strip()]
    assert "Traceback" not in err
    assert len(lines) == 1, err
    return lines[0]


@pytest.mark.parametrize("args, status, message", [
    (["--out", "{file}"], 2, "is a file, not a folder"),
    (["--out", ""], 2, "--out is empty"),
    (["--out", "{file}/sub"], 2, "cannot create the folder (Not a directory)"),
    (["--out", "/proc/rotorcosim_test/x"], 2, "cannot create the folder"),
    (["--out", "{dir}/o", "--duration", "1e9"], 2, "above the 24.0 h limit: give --force"),
    (["--out", "{dir}/o", "--duration", "1e-13"], 2, "too short"),
    (["--out", "{dir}/o", "--duration", "1e-4"], 2, "shorter than one step of the schedule (0.001 s)"),
    (["--out", "{dir}/o", "--duration", "-1"], 2, "--duration must be a positive"),
    (["--out", "{dir}/o", "--checkpoint-every", "0"], 2, "--checkpoint-every must be a positive"),
    (["--out", "{dir}/o", "--step-timeout", "-1"], 2, "--step-timeout must be a number of seconds >= 0"),
    (["--out", "{dir}/o", "--overwrite", "--resume"], 2, "exclude each other"),
    (["--out", "{dir}/o", "--unbalance", "nan"], 2, "--unbalance must be a finite level >= 0"),
    # was "unexpected OverflowError: cannot convert float infinity to integer" (exit 1)
    (["--out", "{dir}/o", "--duration", "1e308"], 2, "the schedule asks for inf steps, beyond the 9.01e+15"),
    (["--out", "{dir}/o", "--schedule", "monolithic", "--duration", "1e14", "--force"], 2, "asks for 1e+17 steps"),
    # a tolerance above 100 % accepts anything (1e308 was taken)
    (["--out", "{dir}/o", "--schedule", "auto", "--tolerance", "1e308"], 2, "tolerance 1e+308 % accepts results"),
])
def test_run_mistakes(tmp_path, capsys, args, status, message):
    f = tmp_path / "afile"
    f.write_text("x")
    args = [a.replace("{file}", str(f)).replace("{dir}", str(tmp_path)) for a in args]
    rc, out, err = call(capsys, "run", "toy_thermomechanical", "--quiet", "--no-figures", *args)
    assert rc == status
    line = one_line_error(err)
    assert line.startswith("rotorcosim run: error: ") and message in line
    assert not (tmp_path / "o" / "summary.json").exists()


def test_unknown_scenario_file(tmp_path, capsys):
    rc, _, err = call(capsys, "run", str(tmp_path / "nope.toml"), "--out", str(tmp_path / "o"))
    assert rc == 2 and "not found" in one_line_error(err)


def test_debug_shows_the_traceback(tmp_path, capsys):
    rc, _, err = call(capsys, "--debug", "run", "toy_thermomechanical", "--out", "")
    assert rc == 2 and "Traceback" in err and "OutputFolderError" in err
    rc, _, err = call(capsys, "run", "toy_thermomechanical", "--out", "", "--debug")
    assert rc == 2 and "Traceback" in err


def test_run_failure_is_status_1(tmp_path, capsys, monkeypatch):
    """An environment fault during the run (here: the disk fills while the time series is written)."""
    import errno

    from rotorcosim.master.observer.recorder import Recorder

    def full(self):
        raise OSError(errno.ENOSPC, "No space left on device", str(self.path))

    monkeypatch.setattr(Recorder, "flush", full)
    rc, _, err = call(capsys, "run", "toy_thermomechanical", "--quiet", "--duration", "1", "--out", str(tmp_path / "o"))
    assert rc == 1
    assert "No space left on device" in one_line_error(err)


@pytest.mark.parametrize("workers", ["0", "-1"])
def test_sweep_workers(tmp_path, capsys, workers):
    rc, _, err = call(capsys, "sweep", "--scenario", "toy_thermomechanical", "--unbalance", "1,2",
                      "--workers", workers, "--out", str(tmp_path / "s"))
    assert rc == 2 and "--workers must be at least 1" in one_line_error(err)


def test_bearing_static_absurd_loads(capsys):
    rc, out, err = call(capsys, "bearing-static", "--bearing", "0", "--radial-load", "1e6")
    assert rc == 0 and "warning: contact stress" in err and "above 4200 MPa" in err
    rc, out, err = call(capsys, "bearing-static", "--bearing", "0", "--radial-load", "1000")
    assert rc == 0 and "warning" not in err
    rc, out, err = call(capsys, "bearing-static", "--bearing", "0", "--radial-load", "1e9")
    assert rc == 2 and "no static equilibrium found" in one_line_error(err)
    # a speed in another unit (rad/s x 1e6...): the message names the speed, not only the loads
    rc, out, err = call(capsys, "bearing-static", "--bearing", "0", "--radial-load", "5000", "--speed-rpm=1e9")
    line = one_line_error(err)
    assert rc == 2 and "at 1e+09 rev/min (ball centrifugal force" in line and "another unit than rev/min" in line


def test_bearing_static_json_flags_validity(capsys):
    import json

    rc, out, _ = call(capsys, "bearing-static", "--bearing", "5", "--radial-load", "1e6", "--json")
    d = json.loads(out)
    assert d["within_elastic_range"] is False and d["max_contact_stress_MPa"] > d["elastic_limit_MPa"]


def test_command_process_collects_less_and_freezes_at_exit():
    """The program's own process (main() without argv): the collector's first threshold raised, and every object
    frozen at exit, after the other exit handlers (the interpreter's final collections then skip them);
    main(argv) from another program leaves its collector alone."""
    import subprocess
    import sys

    code = ("import atexit, gc, sys\n"
            "atexit.register(lambda: print('frozen at exit:', gc.get_freeze_count() > 0))\n"
            "from rotorcosim.master.cli.program import GC_THRESHOLD0, main\n"
            "before = gc.get_threshold()\n"
            "main(['scenarios'])\n"
            "print('left alone:', gc.get_threshold() == before)\n"
            "sys.argv = ['rotorcosim', 'scenarios']\n"
            "main()\n"
            "print('raised:', gc.get_threshold()[0] == GC_THRESHOLD0 != before[0])\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    for line in ("left alone: True", "raised: True", "frozen at exit: True"):
        assert line in out.stdout, out.stdout


@pytest.mark.parametrize("command, args, message", [
    ("sweep", ["--unbalance", "50", "--serial", "--duration", "0.01", "--scenario", "toy_thermomechanical",
               "--out", "{file}"], "--out {file} is a file, not a folder"),
    ("sweep", ["--unbalance", "50", "--serial", "--duration", "0.01", "--scenario", "toy_thermomechanical",
               "--out", "{file}/sub"], "cannot create the folder (Not a directory)"),
    ("export-fmus", ["{file}", "--scenario", "toy_thermomechanical"], "output folder {file} is a file, not a folder"),
    ("export-fmus", ["{file}/sub", "--scenario", "toy_thermomechanical"], "cannot create the folder (Not a directory)"),
    ("export-ssp", ["{dir}/folder.ssp", "toy_thermomechanical"], "is a folder, not an archive's name"),
    # compare: rundir.ensure_folder's checks and lines, as every other command (it had its own, and made the
    # folder before checking the rest of its input)
    ("compare", ["--out", "{file}", "--quiet"], "--out {file} is a file, not a folder"),
    ("compare", ["--out", "{file}/sub", "--quiet"], "--out {file}/sub: cannot create the folder (Not a directory)"),
    ("compare", ["--out", "/proc/rotorcosim_test/x", "--quiet"], "cannot create the folder"),
    ("export-ssp", ["/proc/rotorcosim_test.ssp", "toy_thermomechanical"], "/proc/rotorcosim_test.ssp: cannot write"),
])
def test_output_places_that_cannot_be_written(tmp_path, capsys, command, args, message):
    """Every command writing results names the output it cannot use, in one line (was: a bare OSError)."""
    f = tmp_path / "afile"
    f.write_text("x")
    (tmp_path / "folder.ssp").mkdir()
    args = [a.replace("{file}", str(f)).replace("{dir}", str(tmp_path)) for a in args]
    rc, _, err = call(capsys, command, *args)
    line = one_line_error(err)
    assert rc == 2 and message.replace("{file}", str(f)) in line, line
    assert "Errno" not in line
    assert f.read_text() == "x"


def test_sweep_checks_every_case_like_a_run_before_any_runs(tmp_path, capsys):
    """A duration no run takes failed every case (exit 1, tables of failures written, no line on stderr)."""
    for duration, message in (("nan", "duration must be a positive number"), ("1e308", "asks for inf steps")):
        out = tmp_path / f"s{duration}"
        rc, _, err = call(capsys, "sweep", "--scenario", "toy_thermomechanical", "--serial", "--quiet",
                          "--unbalance", "10,20", "--duration", duration, "--out", str(out))
        assert rc == 2 and message in one_line_error(err)
        assert not out.exists()


@pytest.mark.parametrize("args, message", [
    (["--tolerance", "5"], "applies to --schedule auto only"),
    (["--scenario", "toy_thermomechanical"], "has no bearing results"),
    (["--duration", "nan"], "--duration must be a positive"),
    (["--timing-runs", "0"], "--timing-runs must be a whole number of timings >= 1, got 0"),
    (["--timing-runs", "3", "--schedule", "auto"], "--timing-runs applies to the paper schedule"),
    (["--timing-runs", "3", "--monolithic", "elsewhere"], "--timing-runs applies to the paper schedule"),
    # both runs' own checks before the warm-up (was: the folder made, the warm-up run, then the overflow)
    (["--duration", "1e308"], "the schedule asks for inf steps"),
    (["--schedule", "auto", "--tolerance", "500"], "tolerance 500 % accepts results off by more than they are"),
])
def test_compare_makes_no_folder_before_its_input_is_checked(tmp_path, capsys, args, message):
    rc, _, err = call(capsys, "compare", "--out", str(tmp_path / "new"), "--quiet", *args)
    assert rc == 2 and message in one_line_error(err), err
    assert not (tmp_path / "new").exists()


@pytest.mark.parametrize("text, message", [
    ("", "missing table or key 'spool'"),
    ('[spool.pt]\nz_mm = "abc"\n[spool.gg]\nz_mm = [1]\n[casing]\n', "spool.pt.z_mm: must be a list of numbers, got the string 'abc'"),
    ("[spool.pt]\nz_mm = [1, 2]\n", "spool.pt names material 'rotor', which [material] does not define"),
])
def test_rotor_model_file_missing_or_wrong_keys(tmp_path, capsys, text, message):
    """A model file (critical-speeds --model-file, rotor.model_file) lacking a table or holding a wrong value:
    one line naming the file and the key (was: "error: 'power_turbine'", a bare KeyError)."""
    f = tmp_path / "model.toml"
    f.write_text(text)
    rc, _, err = call(capsys, "critical-speeds", "--model-file", str(f))
    line = one_line_error(err)
    assert rc == 2 and f"rotor model file {f}: " in line and message in line, line


def test_a_folder_given_as_the_scenario_file(tmp_path, capsys):
    rc, _, err = call(capsys, "run", str(tmp_path), "--out", str(tmp_path / "o"))
    assert rc == 2 and "is a folder, not a TOML file" in one_line_error(err)


@pytest.mark.parametrize("target, message", [
    ("{dir}", "is a folder; give a file name"),           # was: written to {dir}.png beside it, silently
    ("{dir}/nope/c.png", "the folder {dir}/nope does not exist"),
    ("{dir}/c.txt", "'.txt' is not an image format matplotlib writes"),   # was: after the scan
])
def test_campbell_target_checked_before_the_scan(tmp_path, capsys, target, message):
    target = target.replace("{dir}", str(tmp_path))
    rc, out, err = call(capsys, "critical-speeds", "--campbell", target)
    assert rc == 2 and message.replace("{dir}", str(tmp_path)) in one_line_error(err)
    assert out == "" and not (tmp_path.parent / (tmp_path.name + ".png")).exists()


def test_a_run_refused_before_it_starts_leaves_no_folder(tmp_path, capsys):
    """The blade-loss consistency check runs once the run folder is claimed: refused there, the folder and its lock
    file are taken back (was: a new folder holding only .rotorcosim.lock). A scenario file that writes a value into
    a thermal network alone (its bearing keeps the engine's) is such a refusal."""
    out = tmp_path / "new" / "run"
    sc = tmp_path / "s.toml"
    sc.write_text('[scenario]\nextends = "blade_loss_2850"\n[components.thermal0]\nparameters = { balls = 19 }\n')
    rc, _, err = call(capsys, "run", str(sc), "--duration", "0.002", "--no-figures", "--quiet", "--out", str(out))
    assert rc == 2 and "thermal0.balls = 19 but bearing0.balls = 21" in one_line_error(err)
    assert not (tmp_path / "new").exists()
    # a folder that was there keeps what it held, and gets no lock file
    out.mkdir(parents=True)
    (out / "notes.txt").write_text("mine")
    rc, _, err = call(capsys, "run", str(sc), "--duration", "0.002", "--no-figures", "--quiet", "--out", str(out))
    assert rc == 2 and sorted(p.name for p in out.iterdir()) == ["notes.txt"]


@pytest.mark.parametrize("param, message", [
    # absurd values that made the set-up itself fail: "unexpected RuntimeError ... it may be a bug" (exit 1)
    ("bearing0.preload=1e300", "bearing0: the preloaded rest state did not solve at omega = 16000 rev/min with "
     "preload = 1e+300 N: ball equilibrium did not converge (residual nan N"),
    ("bearing0.f0=1e300", "bearing0 could not be set up with its parameters"),
    # counts that hung the run (1e12 sub-steps in one step): bounded where declared
    ("bearing0.substeps=1000000000000", "bearing0.substeps: 1000000000000 is outside the range [0, 10000]"),
    ("bearing0.cfl=1e-9", "bearing0.cfl: 1e-09 is outside the declared range [0.001, 2]"),
])
def test_parameters_the_components_cannot_start_from(tmp_path, capsys, param, message):
    out = tmp_path / "o"
    rc, _, err = call(capsys, "run", "blade_loss_2850", "--duration", "0.002", "--no-figures", "--quiet",
                      "--set", param, "--out", str(out))
    assert rc == 2 and message in one_line_error(err), err
    if out.exists():  # failed at set-up: the summary says so, nothing else is there
        assert sorted(p.name for p in out.iterdir()) in (["summary.json"], [".rotorcosim.lock", "summary.json"])
        assert '"status": "failed"' in (out / "summary.json").read_text()


@pytest.mark.parametrize("argv, message", [
    (["run", "--duration", "abc", "--out", "x"], "rotorcosim run: error: argument --duration: invalid float value: "
                                                  "'abc' (see: rotorcosim run --help)"),
    (["run"], "the following arguments are required: --out"),
    (["bogus"], "rotorcosim: error: argument COMMAND: invalid choice: 'bogus'"),
])
def test_option_mistakes_are_one_line(capsys, argv, message):
    """argparse printed its whole usage (up to 9 lines) before the error."""
    with pytest.raises(SystemExit) as info:
        main(argv)
    assert info.value.code == 2
    assert message in one_line_error(capsys.readouterr().err)


def _engine(old: str, new: str) -> str:
    from rotorcosim.components.rotor import model

    text = model.DEFAULT_FILE.read_text()
    assert old in text
    return text.replace(old, new, 1)


@pytest.mark.parametrize("old, new, message", [
    # each was a traceback-free but wrong outcome: warnings and "array must not contain infs or NaNs" (no key),
    # or "unexpected ZeroDivisionError"
    ("nu = 0.3\n", "nu = 1e300\n", "material.rotor.nu must be a Poisson's ratio within (-1, 0.5), got 1e+300"),
    ("speed_rpm = 16000.0", "speed_rpm = 0", "spool.pt.speed_rpm must be a finite, non-zero speed in rev/min"),
    ("speed_rpm = 16000.0", "speed_rpm = nan", "spool.pt.speed_rpm must be a finite, non-zero speed"),
    ("radius_mm = 300.0", "radius_mm = 1e300", "the assembled mass matrix is not finite"),
    ("E = 208e9", "E = 0", "material.rotor.E must be a finite number > 0, got 0"),
])
def test_rotor_model_file_values_outside_the_model(tmp_path, capsys, old, new, message):
    import warnings

    f = tmp_path / "model.toml"
    f.write_text(_engine(old, new))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        rc, _, err = call(capsys, "critical-speeds", "--model-file", str(f))
    line = one_line_error(err)
    assert rc == 2 and f"rotor model file {f}: {message}" in line, line


def test_negative_numbers_in_any_notation_are_values(capsys):
    """argparse took -1e-5 and -inf for options ("expected 2 arguments"): a journal position in scientific
    notation could not be given."""
    rc, out, err = call(capsys, "damper-force", "--damper", "0", "--position", "-1e-5", "0", "--velocity", "0",
                        "-2e-3", "--temperature", "70", "--json")
    assert rc == 0 and '"eccentricity_ratio"' in out, err
    rc, _, err = call(capsys, "run", "toy_thermomechanical", "--duration", "-inf", "--out", "x")
    assert rc == 2 and "--duration must be a positive number of seconds, got -inf" in one_line_error(err)
    rc, _, err = call(capsys, "run", "toy_thermomechanical", "--unbalance", "-1E3", "--out", "x")
    assert rc == 2 and "--unbalance must be a finite level >= 0, got -1000.0" in one_line_error(err)   # the toy's


# -- one convention: SCENARIO positional (--scenario its alias), output --out (the export commands' older
#    positional output kept) --------------------------------------------------------------------------------------

def parsed(monkeypatch, *argv):
    """The namespace the program gives the command ``argv`` (parsed and finished, not run)."""
    import sys

    from rotorcosim.master.cli import options, program

    monkeypatch.setattr(sys, "argv", ["rotorcosim", *argv])
    return options.finish(program.build_parser().parse_args(list(argv)))


#: the scenario each command runs when none is given: compare, sweep and export-ssp keep blade_loss (their results
#: carry its name), run and export-fmus the API's default (None here; the FMUs are the same bytes for both)
DEFAULTS = {"run": None, "sweep": "blade_loss", "compare": "blade_loss", "export-fmus": None,
            "export-ssp": "blade_loss"}
OUT = {"run": ["--out", "o"], "sweep": ["--out", "o"], "compare": ["--out", "o"], "export-fmus": ["--out", "o"],
       "export-ssp": ["--out", "o.ssp"]}


@pytest.mark.parametrize("command", sorted(DEFAULTS))
def test_every_command_takes_the_scenario_as_positional_or_option(monkeypatch, command):
    toy = "toy_thermomechanical"
    for argv in ([toy], ["--scenario", toy], [toy, "--scenario", toy]):
        args = parsed(monkeypatch, command, *argv, *OUT[command])
        assert args.scenario == toy, argv
        assert args.out == OUT[command][1]
    assert parsed(monkeypatch, command, *OUT[command]).scenario == DEFAULTS[command]


@pytest.mark.parametrize("command", sorted(DEFAULTS))
def test_two_different_scenarios_are_refused(tmp_path, capsys, command):
    out = tmp_path / ("o.ssp" if command == "export-ssp" else "o")
    rc, _, err = call(capsys, command, "toy_thermomechanical", "--scenario", "blade_loss", "--out", str(out))
    assert rc == 2
    assert "two scenarios, 'toy_thermomechanical' and --scenario 'blade_loss': give one" in one_line_error(err)
    assert not out.exists()


@pytest.mark.parametrize("command, out", [("export-fmus", "fmus_out"), ("export-ssp", "engine.ssp")])
def test_the_export_commands_older_positional_output_still_works(monkeypatch, command, out):
    args = parsed(monkeypatch, command, out)
    assert (args.out, args.scenario) == (out, DEFAULTS[command])
    args = parsed(monkeypatch, command, out, "toy_thermomechanical")
    assert (args.out, args.scenario) == (out, "toy_thermomechanical")
    args = parsed(monkeypatch, command, out, "--scenario", "toy_thermomechanical")
    assert (args.out, args.scenario) == (out, "toy_thermomechanical")


@pytest.mark.parametrize("command, argv, message", [
    ("export-fmus", ["{dir}/a", "--out", "{dir}/b"], "the output is given twice"),
    ("export-fmus", ["{dir}/a", "toy_thermomechanical", "--out", "{dir}/b"], "the output is given twice"),
    ("export-ssp", ["{dir}/a.ssp", "toy_thermomechanical", "--out", "{dir}/b.ssp"], "the output is given twice"),
    ("export-fmus", [], "give the output: --out DIR"),
    ("export-ssp", ["--scenario", "toy_thermomechanical"], "give the output: --out FILE.ssp"),
    # the current form without its --out: the scenario is not taken for the output's name
    ("export-fmus", ["toy_thermomechanical"], "'toy_thermomechanical' is a scenario; give the output with --out DIR"),
    ("export-ssp", ["blade_loss_2850"], "'blade_loss_2850' is a scenario; give the output with --out FILE.ssp"),
])
def test_the_export_commands_refuse_an_output_given_twice_or_not_at_all(tmp_path, capsys, command, argv, message):
    argv = [a.replace("{dir}", str(tmp_path)) for a in argv]
    rc, _, err = call(capsys, command, *argv)
    assert rc == 2 and message in one_line_error(err)
    assert list(tmp_path.iterdir()) == []


def test_export_ssp_writes_to_out_in_either_form(tmp_path, capsys):
    assert call(capsys, "export-ssp", "toy_thermomechanical", "--out", str(tmp_path / "new.ssp"))[0] == 0
    assert call(capsys, "export-ssp", str(tmp_path / "old.ssp"), "toy_thermomechanical")[0] == 0
    assert (tmp_path / "new.ssp").read_bytes() == (tmp_path / "old.ssp").read_bytes()


def test_run_takes_the_scenario_either_way(tmp_path, capsys):
    import json

    quick = ["--duration", "0.05", "--no-figures", "--quiet"]
    assert call(capsys, "run", "toy_thermomechanical", *quick, "--out", str(tmp_path / "a"))[0] == 0
    assert call(capsys, "run", "--scenario", "toy_thermomechanical", *quick, "--out", str(tmp_path / "b"))[0] == 0
    a, b = (json.loads((tmp_path / d / "summary.json").read_text()) for d in "ab")
    assert a["scenario"] == b["scenario"] == "toy_thermomechanical"
    assert a["final_outputs"] == b["final_outputs"] and a["t_end_s"] == b["t_end_s"]


def test_sweep_takes_the_scenario_as_positional(tmp_path, capsys):
    rc, out, err = call(capsys, "sweep", "toy_thermomechanical", "--unbalance", "1", "--serial", "--quiet",
                        "--duration", "0.01", "--out", str(tmp_path / "s"))
    assert rc == 0, err
    import json

    summary = json.loads((tmp_path / "s" / "level_1" / "summary.json").read_text())
    assert summary["scenario"] == "toy_thermomechanical_1"   # the toy at the level 1 N, not the default


def _help(capsys, *argv) -> str:
    with pytest.raises(SystemExit) as info:
        main([*argv, "--help"])
    assert info.value.code == 0
    return " ".join(capsys.readouterr().out.split())


def test_schedule_has_the_same_help_on_run_and_sweep(capsys):
    from rotorcosim.master.cli.options import SCHEDULE_HELP

    for command in ("run", "sweep"):
        assert SCHEDULE_HELP in _help(capsys, command), command


@pytest.mark.parametrize("command", sorted(DEFAULTS))
def test_every_command_documents_scenario_and_out(capsys, command):
    text = _help(capsys, command)
    assert "[SCENARIO]" in text and "--scenario SCENARIO" in text and "--out" in text
    assert "`" not in text


def test_top_level_help_says_what_the_tool_does_in_plain_text(capsys):
    text = _help(capsys)
    assert "Co-simulation of a dual-rotor gas turbine engine" in text
    assert "docs/" in text and "rotorcosim COMMAND --help" in text
    assert "``" not in text and ":mod:" not in text


@pytest.mark.parametrize("value, message", [
    # was "unexpected ZeroDivisionError: float division by zero" (exit 1): the schedule's cycle follows the spool
    ("rotor.omega_pt=0", "rotor.omega_pt must be a finite non-zero number (the spool's operating speed, rad/s), got 0"),
    ("rotor.omega_gg=0", "rotor.omega_gg must be a finite non-zero number"),
    # a first spool set turning the other way: the cycle's speed, not "cycle period must be a positive number"
    ("rotor.omega_pt=-1675.5", "[schedule] speed_rpm: the cycle's speed must be a positive number of rev/min"),
])
def test_a_spool_speed_set_to_zero_or_backwards_is_one_line(tmp_path, capsys, value, message):
    out = tmp_path / "o"
    rc, _, err = call(capsys, "run", "blade_loss_2850", "--set", value, "--duration", "0.003", "--quiet",
                      "--no-figures", "--out", str(out))
    assert rc == 2 and message in one_line_error(err), err
    assert not out.exists()
