"""``calibrate``, ``uq`` and ``sweep`` before their first run: the wall-time estimate printed, a study beyond
24 h refused without --force, the SPEC checked whole (result keys against what a run reports, parameters,
distributions and bounds, the shape of every value), a folder of another SPEC refused naming what differs, and
--resume with the same SPEC going on. Each refusal: one line, exit status 2, no folder left."""
from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest

from rotorcosim.master.cli import main

TOY = Path(__file__).resolve().parents[1] / "helpers" / "two_masses.toml"

UQ = '''[uq]
scenario = "toy.toml"
samples = 4
seed = 1
results = ["final_outputs.m1.x"]
[[uq.parameter]]
name = "m1.x0"
distribution = "normal"
mean = 0.1
std = 0.02
'''
CAL = '''[calibrate]
scenario = "toy.toml"
targets = "t.csv"
max_evaluations = 2
[[calibrate.parameter]]
name = "m1.x0"
lower = 0.05
upper = 0.2
'''

#: the paper's engine, a film spring stiffness uncertain / updated over a range reaching below zero
BL_UQ = '''[uq]
scenario = "blade_loss_2850"
duration = 0.02
samples = 8
seed = 1
results = ["bearings.0.whirl_amplitude_mm"]
[[uq.parameter]]
name = "damper0.k_spring"
distribution = "normal"
mean = 5.254e6
std = 5e6
'''
BL_CAL = '''[calibrate]
scenario = "blade_loss_2850"
duration = 0.02
targets = "t.csv"
[[calibrate.parameter]]
name = "damper0.k_spring"
lower = -1.0
upper = 1e7
start = 5e6
'''


def call(capsys, *argv):
    rc = main([str(a) for a in argv])
    out, err = capsys.readouterr()
    return rc, out, err


def error_line(err: str) -> str:
    """The one error line (the estimate's line, printed before it, is not an error)."""
    assert "Traceback" not in err and "may be a bug" not in err, err
    lines = [x for x in err.splitlines() if x.strip() and not x.startswith(("uq: ", "calibrate: ", "sweep: "))]
    assert len(lines) == 1, err
    return lines[0]


def spec(folder: Path, text: str, name: str = "s.toml", targets: str = ",final_outputs.m1.x,0.05\n") -> Path:
    """The SPEC ``text`` as ``folder/name``, beside the toy scenario and a targets file holding ``targets``."""
    shutil.copy(TOY, folder / "toy.toml")
    (folder / "t.csv").write_text("case,result,value\n" + targets)
    p = folder / name
    p.write_text(text)
    return p


# -- item: wall time estimated, printed, and refused beyond 24 h ---------------------------------------------
def test_uq_prints_its_estimate_before_the_first_sample(tmp_path, capsys):
    rc, _, err = call(capsys, "uq", spec(tmp_path, UQ), "--out", tmp_path / "o", "--serial", "--quiet")
    assert rc == 0
    first = err.splitlines()[0]
    assert first.startswith("uq: 4 runs of about ") and "1 at a time" in first and "of wall time (estimated)" in first
    assert json.loads((tmp_path / "o" / "uq.json").read_text())["estimate"]["runs"] == 4


@pytest.mark.parametrize("command, text, shorten", [
    ("uq", UQ.replace("samples = 4", "samples = 1000000"), "fewer samples"),
    ("calibrate", CAL.replace("max_evaluations = 2", "max_evaluations = 1000000"), "a smaller max_evaluations"),
])
def test_a_study_beyond_24_h_is_refused_without_force(tmp_path, capsys, command, text, shorten):
    rc, _, err = call(capsys, command, spec(tmp_path, text), "--out", tmp_path / "o", "--serial")
    line = error_line(err)
    assert rc == 2
    assert "above the 24.0 h limit: give --force to run it anyway" in line and shorten in line, line
    assert not (tmp_path / "o").exists()


def test_a_sweep_beyond_24_h_is_refused_without_force(tmp_path, capsys):
    rc, _, err = call(capsys, "sweep", "--scenario", "toy_thermomechanical", "--unbalance", ",".join(map(str, range(1, 31))),
                      "--duration", "1e8", "--serial", "--out", tmp_path / "o")
    line = error_line(err)
    assert rc == 2 and "sweep: 30 runs of about" in line and "above the 24.0 h limit: give --force" in line
    assert "fewer levels or --set values, a shorter --duration" in line
    assert not (tmp_path / "o").exists()


def test_a_sweep_prints_its_estimate_and_keeps_it(tmp_path, capsys):
    rc, _, err = call(capsys, "sweep", "--scenario", "toy_thermomechanical", "--unbalance", "1,2", "--duration",
                      "0.05", "--serial", "--quiet", "--out", tmp_path / "o")
    assert rc == 0 and err.splitlines()[0].startswith("sweep: 2 runs of about ")
    state = json.loads((tmp_path / "o" / "sweep.json").read_text())
    assert state["estimate"]["runs"] == 2 and state["retries"] == {}


# -- item: the SPEC checked whole before the first run ------------------------------------------------------------
@pytest.mark.parametrize("command, text, targets, message", [
    # a misspelt result: was "6 of 6 samples failed" after running every sample
    ("uq", UQ.replace('"final_outputs.m1.x"]', '"final_outputs.m1.xx"]'), None,
     "result 'final_outputs.m1.xx' is not one a run of scenario 'two_masses' reports (did you mean "
     "'final_outputs.m1.x'?)"),
    ("uq", UQ.replace('"final_outputs.m1.x"]', '"bearings.0.whirl_amplitude_mm"]'), None,
     "result 'bearings.0.whirl_amplitude_mm' is not one a run of scenario 'two_masses' reports"),
    ("calibrate", CAL, ",final_outputs.m1.v_typo,0.05\n", "result 'final_outputs.m1.v_typo' is not one a run"),
    ("uq", UQ.replace('name = "m1.x0"', 'name = "m1.nope"'), None, "m1.nope"),
    ("uq", UQ.replace('name = "m1.x0"', 'name = "m9.x0"'), None, "m9"),
    # a distribution reaching past what the parameter takes: a film's spring stiffness drawn negative fails its
    # run (its component refuses it at set-up); was "2 of 8 samples failed"
    ("uq", BL_UQ, None, "got -7251034.591191405 (the engine's damper.0.k_spring) (a sample of its normal "
     "distribution, mean 5.254e+06, std 5e+06: narrow it or truncate it, truncnormal)"),
    ("uq", UQ.replace("std = 0.02", "std = -1"), None, "std must be > 0"),
    # a mean outside the bounds was drawn from the normal's far tail (or NaN), probed at a value never drawn
    ("uq", UQ.replace('"normal"', '"truncnormal"').replace("std = 0.02", "std = 0.02\nlower = 0.2\nupper = 0.3"),
     None, "parameter m1.x0: a truncnormal distribution's mean 0.1 lies outside its bounds [0.2, 0.3]: give a mean "
     "between lower and upper"),
    ("calibrate", CAL.replace("lower = 0.05", "lower = 0.3"), None, "lower 0.3 must be below upper 0.2"),
    ("calibrate", BL_CAL, ",bearings.0.whirl_amplitude_mm,0.1\n",
     "parameter damper0.k_spring: set damper0.k_spring: damper0.k_spring must be >= 0 (N/m), got -1"),
    # a misspelt table beside the SPEC's own: was ignored, the study run without what it said
    ("uq", UQ + "[uq_set]\nx = 1\n", None, "unknown table(s) or key(s) uq_set (a uq SPEC holds [uq] only)"),
    ("calibrate", "seed = 3\n" + CAL, None, "unknown table(s) or key(s) seed (a calibrate SPEC holds [calibrate]"),
    # a design too large to draw: was "error: out of memory" (exit 1) before the study was priced
    ("uq", UQ.replace("samples = 4", "samples = 1000000000000"), None,
     "samples = 1000000000000: a design of 1000000000000 runs x 1 parameters (7629395 MiB) is above the 512 MiB"),
])
def test_spec_mistakes_refused_before_the_first_run(tmp_path, capsys, command, text, targets, message):
    rc, _, err = call(capsys, command, spec(tmp_path, text, targets=targets or ",final_outputs.m1.x,0.05\n"),
                      "--out", tmp_path / "o", "--serial")
    line = error_line(err)
    assert rc == 2 and message in line, line
    assert not (tmp_path / "o").exists()


# -- item: wrong TOML shapes in a SPEC ------------------------------------------------------------------------------
@pytest.mark.parametrize("command, old, new, message", [
    ("uq", "[uq]\nscenario", "uq = 5\n[x]\nscenario", None),
    ("uq", "samples = 4", "samples = [4]", "samples must be an integer >= 2, got [4]"),
    ("uq", "seed = 1", "seed = {a = 1}", "seed must be an integer >= 0, got {'a': 1}"),
    ("uq", 'results = ["final_outputs.m1.x"]', 'results = "final_outputs.m1.x"', "results must be a list"),
    ("uq", 'results = ["final_outputs.m1.x"]', "results = [1]", "results must be a list"),
    ("uq", "mean = 0.1", "mean = [0.1]", "parameter m1.x0 mean: must be a number, got a list ([0.1])"),
    ("uq", "std = 0.02", "std = {a = 1}", "parameter m1.x0 std: must be a number, got a table"),
    ("uq", 'distribution = "normal"', 'distribution = ["normal"]', "distribution ['normal'] not in"),
    ("uq", 'name = "m1.x0"', "name = 5", "name must be written 'component.parameter'"),
    ("uq", "seed = 1", "seed = 1\nset = 5", "set must be a table"),
    ("uq", "seed = 1", "seed = 1\nsampler = [1]", "sampler [1] not in"),
    ("uq", "seed = 1", "seed = 1\nduration = [1]", "duration: must be a number, got a list"),
    ("calibrate", "[calibrate]\nscenario", "calibrate = [1]\n[x]\nscenario", None),
    ("calibrate", "lower = 0.05", "lower = [0.05]", "lower: must be a number, got a list ([0.05])"),
    ("calibrate", "upper = 0.2", "upper = {a = 1}", "upper: must be a number, got a table"),
    ("calibrate", 'targets = "t.csv"', "targets = 5", "targets must name a CSV file"),
    ("calibrate", "max_evaluations = 2", "max_evaluations = [2]", "max_evaluations must be an integer >= 1"),
    ("calibrate", "max_evaluations = 2", "max_evaluations = 2\ncases = 5", "cases must be tables of overrides"),
    ("calibrate", "max_evaluations = 2", "max_evaluations = 2\ncases = {a = 5}", "cases must be tables"),
    ("calibrate", "upper = 0.2", "upper = 0.2\nscale = ['log']", "scale ['log'] not in"),
    ("calibrate", "max_evaluations = 2", "max_evaluations = 2\nresidual = 5", "residual 5 not in"),
])
def test_wrong_shapes_in_a_spec_are_one_line(tmp_path, capsys, command, old, new, message):
    base = UQ if command == "uq" else CAL
    assert old in base
    text = base.replace(old, new, 1)
    if message is None:   # the whole table of another shape: the top of the file
        text, message = f"{command} = {new.split('=')[1].split(chr(10))[0].strip()}\n", f"[{command}] must be a table"
    rc, _, err = call(capsys, command, spec(tmp_path, text), "--out", tmp_path / "o", "--serial")
    line = error_line(err)
    assert rc == 2 and message in line, line
    assert not (tmp_path / "o").exists()


# -- item: a folder of another SPEC refused by both, naming the keys; --resume goes on --------------------------
@pytest.mark.parametrize("command, old, new, named", [
    ("uq", "samples = 4\nseed = 1", "samples = 5\nseed = 2", "samples 4 there, 5 here; seed 1 there, 2 here"),
    ("uq", "seed = 1", "seed = 3", "seed 1 there, 3 here"),
    ("uq", "std = 0.02", "std = 0.03", "parameters"),
    ("calibrate", "upper = 0.2", "upper = 0.3", "parameters"),
    ("calibrate", "max_evaluations = 2", "max_evaluations = 3", "max_evaluations 2 there, 3 here"),
])
def test_a_folder_of_another_spec_is_refused_naming_what_differs(tmp_path, capsys, command, old, new, named):
    base = UQ if command == "uq" else CAL
    first = spec(tmp_path, base)
    rc, _, _ = call(capsys, command, first, "--out", tmp_path / "o", "--serial", "--quiet")
    assert rc == 0
    report = tmp_path / "o" / ("uq.json" if command == "uq" else "calibration.json")
    before = report.read_bytes()
    other = spec(tmp_path, base.replace(old, new), name="other.toml")
    rc, _, err = call(capsys, command, other, "--out", tmp_path / "o", "--serial", "--quiet")
    line = error_line(err)
    assert rc == 2 and "holds a study of another SPEC (differs in" in line and named in line, line
    assert report.read_bytes() == before          # not replaced
    rc, _, err = call(capsys, command, first, "--out", tmp_path / "o", "--serial", "--resume")
    assert rc == 0, err
    assert "resuming:" in err


def test_resume_into_a_folder_without_a_study_is_refused(tmp_path, capsys):
    rc, _, err = call(capsys, "uq", spec(tmp_path, UQ), "--out", tmp_path / "o", "--serial", "--resume")
    assert rc == 2 and "holds no study to resume" in error_line(err)
    assert not (tmp_path / "o").exists()


def test_a_targets_table_from_a_spreadsheet_is_read_and_a_binary_one_named(tmp_path, capsys):
    """A targets file saved as "CSV UTF-8" begins with a byte-order mark: it was refused as having no column
    'case' (the first column read as '\\ufeffcase'); bytes that are not UTF-8 gave the codec's message alone."""
    from rotorcosim.master.study.targets import read_targets

    f = tmp_path / "t.csv"
    f.write_text("\ufeffcase,result,value\n,final_outputs.m1.x,0.05\n", encoding="utf-8")
    (target,) = read_targets(f, {})
    assert (target.case, target.result, target.value) == ("", "final_outputs.m1.x", 0.05)
    p = spec(tmp_path, CAL)
    (tmp_path / "t.csv").write_bytes(b"case,result,value\n,final_outputs.m1.x,0.05\xff\n")
    rc, _, err = call(capsys, "calibrate", p, "--out", tmp_path / "o", "--serial")
    assert rc == 2 and error_line(err) == (f"rotorcosim calibrate: error: targets file {tmp_path / 't.csv'}: not "
                                           "UTF-8 text (byte 0xff at position 42): save it as CSV, UTF-8")
    assert not (tmp_path / "o").exists()


@pytest.mark.parametrize("command, text", [("uq", UQ), ("calibrate", CAL), ("sweep", None)])
@pytest.mark.parametrize("where, message", [
    # a study checked --workers after writing its report (uq.json / calibration.json left in --out)
    (["--workers", "0"], "--workers must be at least 1, got 0"),
    # the scheduler was ignored (sweep) or refused after the report was written (studies)
    (["--serial", "--scheduler", "tcp://127.0.0.1:1"],
     "--serial runs in this process, without Dask: give it or --scheduler, not both"),
    # the local cluster's size was ignored
    (["--serial", "--workers", "3"],
     "--serial runs in this process, one run after another: give it or --workers (3), not both"),
])
def test_where_the_runs_go_is_checked_before_anything_is_written(tmp_path, capsys, command, text, where, message):
    first = (["sweep", "toy_thermomechanical", "--unbalance", "1,2", "--duration", "0.05"] if text is None
             else [command, spec(tmp_path, text)])
    rc, _, err = call(capsys, *first, *where, "--quiet", "--out", tmp_path / "o")
    assert rc == 2 and error_line(err) == f"rotorcosim {command}: error: {message}", err
    assert not (tmp_path / "o").exists()
