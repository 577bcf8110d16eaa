"""Your own engine, from a blank folder: new-engine, check-engine, a blade-loss run of it; parameters listed and
set, the bearing's geometry among them."""
from __future__ import annotations

import json

import pytest

from rotorcosim.master.cli import main


def test_new_engine_check_and_run(tmp_path, capsys):
    """The walk-through: new-engine X, then a run of X/blade_loss.toml writes the usual results and
    figures. The run's whirl at bearing 0 is checked against the linear engine's (an independent harmonic
    solve of the same rotor with the bearings linearised): the film's nonlinearity and the thermal growth move
    it, by much less than a factor of 2 at this small orbit (the rub ring is not touched)."""
    folder = tmp_path / "X"
    assert main(["new-engine", str(folder)]) == 0
    assert main(["new-engine", str(folder)]) == 2                       # never overwrites
    assert "already there" in capsys.readouterr().err
    png = tmp_path / "campbell.png"
    assert main(["check-engine", str(folder / "engine.toml"), "--scenario", str(folder / "blade_loss.toml"),
                 "--campbell", str(png), "--json"]) == 0
    rep = json.loads(capsys.readouterr().out)
    assert rep["problems"] == [] and rep["spools"]["rotor"]["nodes"] == 10 and png.stat().st_size > 10_000
    fw = rep["critical_speeds"]["forward_synchronous_rpm"]
    assert all(abs(v / 16000.0 - 1) > 0.15 for v in fw)                # the running speed clear of them
    out = tmp_path / "out"
    assert main(["run", str(folder / "blade_loss.toml"), "--duration", "0.3", "--out", str(out)]) == 0
    s = json.loads((out / "summary.json").read_text())
    assert s["status"] == "complete", s["status"]
    assert (out / "fig09_response_bearing0.png").is_file() and (out / "timeseries.h5").is_file()
    whirl = s["bearings"]["0"]["whirl_amplitude_mm"]

    from rotorcosim.cases.blade_loss import linear_engine
    from rotorcosim.components.rotor import model as fem
    from rotorcosim.master.api import load_scenario

    sc = load_scenario(folder / "blade_loss.toml")
    full = fem.load(folder / "engine.toml")
    sup = linear_engine.supports(sc, data=full.data)
    lin = linear_engine.response(full, sup, sc.components["rotor"].parameters["F_unbalance"])
    assert 0.5 < whirl / lin["0"]["whirl_mm"] < 2.0, (whirl, lin)


def test_check_engine_lists_every_problem_and_writes_nothing(tmp_path, capsys):
    assert main(["new-engine", str(tmp_path / "X")]) == 0
    text = (tmp_path / "X" / "engine.toml").read_text()
    bad = text.replace("z_mm = [0, 40, 100", "z_mm = [0, 40, 40").replace('node = ["rotor", 8], housing',
                                                                          'node = ["rotor", 12], housing')
    f = tmp_path / "bad.toml"
    f.write_text(bad)
    capsys.readouterr()
    assert main(["check-engine", str(f), "--campbell", str(tmp_path / "c.png")]) == 2
    out = capsys.readouterr().out
    assert "stations overlap: node 2" in out and "attach.bearing5.node: node 12 does not exist" in out
    assert not (tmp_path / "c.png").exists()
    # the run of a scenario on that engine: one line naming the file, no traceback
    assert main(["critical-speeds", "--model", str(f)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "must increase strictly" in err[0]


def test_parameters_lists_and_sets_the_bearing_geometry(capsys):
    """Every parameter with unit, default, value and source; the ball count is one (as documented: "--set
    bearing0.balls=19" was "no parameter 'balls'"). Fewer balls carry the same preload with more load each:
    at rest, Q = P / (Z sin alpha) (Harris, Rolling Bearing Analysis, the axially loaded bearing), so 19 balls
    instead of 21 raise the contact load by a little less than 21/19: each ball's larger load opens its contact
    angle a little (the Hertz deflection grows as Q^(2/3)), and sin alpha with it."""
    import rotorcosim

    sc = rotorcosim.load_scenario("blade_loss_2850")
    rows = {r["name"]: r for r in sc.parameters("bearing5")}
    # every value of the bearing comes from the engine file's record of bearing 5
    assert rows["balls"]["value"] == 27 and rows["balls"]["source"].endswith("engine.toml [bearing.5] balls")
    assert rows["preload"]["source"].endswith("engine.toml [bearing.5] preload_N") and rows["preload"]["unit"] == "N"
    assert main(["parameters", "bearing0", "--json"]) == 0
    assert {r["name"] for r in json.loads(capsys.readouterr().out)} >= {"balls", "ball_diameter", "contact_angle"}

    from rotorcosim.master.scenario.build import create_component

    q = {}
    for z in (21, 19):
        spec = sc.set({"bearing0.balls": z, "bearing0.omega": 1e-9}).components["bearing0"]
        b = create_component(spec)
        b.setup(0.0)
        q[z] = float(b.y["Q_max"][0])
    assert 1.0 < q[19] / q[21] < 21 / 19 and q[19] / q[21] == pytest.approx(21 / 19, rel=1e-2)


@pytest.mark.parametrize("setting, message", [
    ("bearing0.ball_diameter=0.03", "a ball of 30 mm does not fit between the races"),
    ("bearing0.bore=nan", "'nan' is not a finite number"),
    ("bearing0.bore=-0.05", "bearing0.bore must be a finite number > 0"),
    # one quantity: the damper's radius is also the journal's and the thermal network's
    ("thermal0.damper_radius=-0.1", "thermal0.damper_radius must be a finite number > 0 (m), got -0.1 (the engine's "
                                    "damper.0.radius"),
])
def test_bad_geometry_is_one_line(tmp_path, capsys, setting, message):
    rc = main(["run", "--set", setting, "--duration", "0.001", "--no-figures", "--out", str(tmp_path / "o")])
    err = [l for l in capsys.readouterr().err.splitlines() if l.strip()]
    assert rc == 2 and len(err) == 1 and message in err[0], err
    assert not (tmp_path / "o" / "timeseries.h5").exists()


def test_a_pedestal_without_its_stiffness_names_the_missing_keys(tmp_path, capsys):
    """A pedestal with kxx only was reported as "pedestal.h0.k: must be a finite number > 0, got None"."""
    assert main(["new-engine", str(tmp_path / "X")]) == 0
    f = tmp_path / "X" / "engine.toml"
    f.write_text(f.read_text().replace("[pedestal.h0]\nmass = 3.0\nk = 5.0e8", "[pedestal.h0]\nmass = 3.0\nkxx = 5.0e8")
                 .replace("[pedestal.h5]\nmass = 3.0\nk = 5.0e8", "[pedestal.h5]\nmass = 3.0"))
    capsys.readouterr()
    assert main(["check-engine", str(f)]) == 2
    out = capsys.readouterr().out
    assert "pedestal.h0: kyy missing: give kxx and kyy, or k for both" in out, out
    assert "pedestal.h5: kxx and kyy missing: give kxx and kyy, or k for both" in out, out
    assert "None" not in out


def test_new_engine_into_a_folder_that_cannot_be_made_says_which_and_why(tmp_path, capsys, monkeypatch):
    """new-engine /proc/x printed a bare "[Errno 2] No such file or directory: '/proc/x'"; a write that fails
    half-way leaves nothing behind."""
    import errno
    from pathlib import Path

    if Path("/proc").is_dir():
        assert main(["new-engine", "/proc/x"]) == 2
        assert capsys.readouterr().err == ("rotorcosim new-engine: error: new-engine /proc/x: the folder cannot be "
                                           "created: No such file or directory (/proc does not take a new folder); "
                                           "choose a folder you can write in\n")
    real, calls = Path.write_text, []

    def disk_full(self, *a, **k):
        calls.append(self)
        if len(calls) == 2:
            raise OSError(errno.ENOSPC, "No space left on device")
        return real(self, *a, **k)

    monkeypatch.setattr(Path, "write_text", disk_full)
    assert main(["new-engine", str(tmp_path / "a" / "b")]) == 1
    err = capsys.readouterr().err
    assert err.startswith(f"rotorcosim new-engine: error: new-engine {tmp_path / 'a' / 'b'}: cannot write "
                          "blade_loss.toml into it: No space left on device"), err
    assert list(tmp_path.iterdir()) == []


def test_a_massless_pedestal_is_refused_by_name(tmp_path, capsys):
    """A pedestal of mass 0 leaves the mass matrix singular: check-engine and the run used to end in scipy's
    'The leading minor of order 59 of B is not positive definite'; now each names the key."""
    assert main(["new-engine", str(tmp_path / "X")]) == 0
    f = tmp_path / "X" / "engine.toml"
    f.write_text(f.read_text().replace("[pedestal.h0]\nmass = 3.0", "[pedestal.h0]\nmass = 0.0"))
    capsys.readouterr()
    assert main(["check-engine", str(f), "--campbell", str(tmp_path / "c.png")]) == 2
    assert "pedestal.h0.mass: must be a finite number > 0, got 0.0" in capsys.readouterr().out
    assert main(["run", str(tmp_path / "X" / "blade_loss.toml"), "--duration", "0.001", "--no-figures", "--quiet",
                 "--out", str(tmp_path / "o")]) == 2
    err = [line for line in capsys.readouterr().err.splitlines() if line.strip()]
    assert len(err) == 1 and err[0].endswith("pedestal.h0.mass must be a finite number > 0, got 0.0"), err
    assert not (tmp_path / "o").exists() and not (tmp_path / "c.png").exists()


#: a second spool on nothing: no support, pedestal or bearing holds it
FREE_SPOOL = """[spool.hp]
speed_rpm = 20000.0
material = "steel"
z_mm = [300, 400, 500]
d_out_mm = [120, 120]
d_in_mm = [100, 100]
drive_node = 0

"""


def test_a_spool_nothing_holds_is_named(tmp_path, capsys):
    """An engine whose stiffness with its supports is singular (a spool left on nothing) ended check-engine and
    critical-speeds in LAPACK's 'The leading minor of order 72 of B is not positive definite'; now one line
    naming the spool."""
    assert main(["new-engine", str(tmp_path / "X")]) == 0
    f = tmp_path / "X" / "engine.toml"
    f.write_text(f.read_text().replace("[pedestal.h0]", FREE_SPOOL + "[pedestal.h0]"))
    capsys.readouterr()
    for argv in (["check-engine", str(f), "--campbell", str(tmp_path / "c.png")], ["critical-speeds", "--model", str(f)]):
        assert main(argv) == 2
        err = [line for line in capsys.readouterr().err.splitlines() if line.strip()]
        assert len(err) == 1 and err[0].endswith(
            "error: the engine's stiffness with its supports is singular: spool 'hp' moves freely, held by no "
            "spring (a spool needs supports, pedestals, attached bearings or intershaft bearings at two nodes or "
            "more)"), err
    assert not (tmp_path / "c.png").exists()


def test_too_few_modes_for_a_rotor_free_without_its_bearings(tmp_path, capsys):
    """new-engine's rotor rests on its co-simulated bearings only: 4 rigid-body modes without them. n_modes <= 4
    ended the run in LAPACK's '55-th leading minor of the array is not positive definite'."""
    assert main(["new-engine", str(tmp_path / "X")]) == 0
    capsys.readouterr()
    rc = main(["run", str(tmp_path / "X" / "blade_loss.toml"), "--set", "rotor.n_modes=2", "--duration", "0.001",
               "--no-figures", "--quiet", "--out", str(tmp_path / "o")])
    err = [line for line in capsys.readouterr().err.splitlines() if line.strip()]
    assert rc == 2 and err == ["rotorcosim run: error: rotor: n_modes = 2 retains rigid-body modes only (the rotor "
                               "moves freely without its co-simulated bearings: 4 such modes); retain more than 4 "
                               "(n_modes >= 5)"], err
    assert not (tmp_path / "o").exists()


def test_critical_speeds_of_a_scenario_are_its_engines(tmp_path, capsys):
    """critical-speeds --scenario my_engine/blade_loss.toml (no --model) listed the paper's engine's speeds
    ('of spool 'pt'', 8500, 10200 ...) with the scenario's bearings linearised onto it; a shipped name was 'not
    found'. Now the scenario's engine, as --model of it gives, and shipped names are taken."""
    import json

    assert main(["new-engine", str(tmp_path / "X")]) == 0
    capsys.readouterr()
    assert main(["critical-speeds", "--scenario", str(tmp_path / "X" / "blade_loss.toml"), "--json"]) == 0
    by_scenario = json.loads(capsys.readouterr().out)
    assert main(["critical-speeds", "--model", str(tmp_path / "X" / "engine.toml"), "--json"]) == 0
    by_model = json.loads(capsys.readouterr().out)
    assert by_scenario["forward_synchronous_rpm"] == by_model["forward_synchronous_rpm"]
    assert by_scenario["spools"] == ["rotor"]
    assert main(["critical-speeds", "--scenario", "blade_loss", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["spools"][0] == "pt"


def test_a_scenario_whose_damper_is_a_plugin_cannot_linearise_the_engine(capsys):
    """The linearised engine reads the native damper's film: a plug-in (or an SSP's FMU) in its place ended in
    "error: 'k_spring'" ('FMUComponent' object has no attribute 'geometry' for an SSP, exit 1 'a bug')."""
    from pathlib import Path

    example = Path(__file__).resolve().parents[2] / "docs" / "examples" / "linear_damper" / "linear_damper.toml"
    assert main(["critical-speeds", "--scenario", str(example)]) == 2
    err = [line for line in capsys.readouterr().err.splitlines() if line.strip()]
    assert err == ["rotorcosim critical-speeds: error: scenario 'linear_damper_2850': damper0 is "
                   "linear_damper:LinearDamper, not the damper (damper.fast or damper.fe) whose model the linearised "
                   "engine reads: give a scenario of the native parts (--scenario FILE)"], err


def test_check_engine_draws_its_figure_only_where_asked(tmp_path, capsys, monkeypatch):
    """Without --campbell it wrote engine_campbell.png into the working folder."""
    assert main(["new-engine", str(tmp_path / "X")]) == 0
    monkeypatch.chdir(tmp_path)
    assert main(["check-engine", str(tmp_path / "X" / "engine.toml")]) == 0
    assert sorted(p.name for p in tmp_path.iterdir()) == ["X"]
    assert sorted(p.name for p in (tmp_path / "X").iterdir()) == ["blade_loss.toml", "engine.toml", "rundown.toml"]
    assert "Campbell diagram" not in capsys.readouterr().out
    assert main(["check-engine", str(tmp_path / "X" / "engine.toml"), "--campbell", str(tmp_path / "c.png")]) == 0
    assert (tmp_path / "c.png").is_file()
