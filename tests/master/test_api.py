"""The Python API, line by line of the README's snippet, on the blade-loss system (1 ms) and the toy.

    import rotorcosim
    sc = rotorcosim.load_scenario("blade_loss_2850")
    sc = sc.set({"rotor.F_unbalance": 5700.0})
    sc = sc.swap("damper0", "damper.fe")
    res = rotorcosim.simulate(sc, duration=0.05)
    res.time, res.phase, res["bearing0.P_drag"], res.summary
    df = res.to_dataframe()
"""
import json
import re

import h5py
import numpy as np

import pytest

import rotorcosim
from rotorcosim import scenarios
from rotorcosim.master.cli import main
from rotorcosim.master.scenario.build import ScenarioError


# -- load_scenario -------------------------------------------------------------------------------------
def test_load_scenario_by_shipped_name_or_path_is_the_same():
    a = rotorcosim.load_scenario("blade_loss_2850")
    b = rotorcosim.load_scenario(scenarios.path("blade_loss_2850"))
    assert a.name == b.name == "blade_loss_2850"
    assert a.components["rotor"].parameters == b.components["rotor"].parameters
    assert len(a.connections) == 46 and isinstance(a, rotorcosim.Scenario)


def test_load_scenario_unknown_name_lists_the_shipped_ones():
    with pytest.raises(FileNotFoundError, match="no shipped scenario 'nope'; shipped: .*blade_loss_2850"):
        rotorcosim.load_scenario("nope")


# -- set -----------------------------------------------------------------------------------------------
def test_set_returns_a_new_scenario_and_leaves_the_old_one():
    sc = rotorcosim.load_scenario("blade_loss_2850")
    sc2 = sc.set({"rotor.F_unbalance": 5700.0, "bearing0.drag_in_thermal_only": False})
    assert sc2 is not sc
    assert sc2.components["rotor"].parameters["F_unbalance"] == 5700.0
    assert sc.components["rotor"].parameters["F_unbalance"] == 2850.0
    assert sc2.components["bearing0"].parameters["drag_in_thermal_only"] is False


@pytest.mark.parametrize("values, message", [
    ({"rotr.F_unbalance": 1.0}, r"no component 'rotr' \(components: rotor, bearing0"),
    ({"rotor.F_unbalanc": 1.0}, r"rotor.mta \(rotor\) has no parameter 'F_unbalanc' \(its parameters: .*F_unbalance"),
    ({"rotor": 1.0}, "must be written 'component.parameter'"),
    ({"rotor.F_unbalance": float("nan")}, "not finite"),
    # the value's kind and size are checked when set, not when the run builds the component
    ({"rotor.F_unbalance": "abc"}, r"set rotor.F_unbalance: expected a number \(Real\), got 'abc'"),
    ({"rotor.F_unbalance": [1.0, 2.0]}, r"set rotor.F_unbalance: expected 1 value\(s\), got 2"),
    ({"damper0.n_theta": 2.5}, r"set damper0.n_theta: expected an integer"),
    ({"damper0.cavitation": 2}, r"set damper0.cavitation: expected a Boolean"),
])
def test_set_errors_name_the_problem(values, message):
    with pytest.raises((ScenarioError, ValueError), match=message):
        rotorcosim.load_scenario("blade_loss_2850").set(values)


# -- swap ----------------------------------------------------------------------------------------------
def test_swap_by_registry_name_and_by_module_class():
    sc = rotorcosim.load_scenario("blade_loss_2850")
    a = sc.swap("damper0", "damper.fe")
    assert a.components["damper0"].implementation == "damper.fe" and a.components["damper0"].fmu is None
    assert sc.components["damper0"].implementation == "damper.fast"
    assert a.components["damper0"].parameters == sc.components["damper0"].parameters  # kept
    b = sc.swap("damper0", "rotorcosim.components.damper.component:FEDamper", parameters={"damper": 0})
    assert b.components["damper0"].implementation.endswith(":FEDamper")


def test_swap_to_an_fmu_file(tmp_path):
    sc = rotorcosim.load_scenario("toy_thermomechanical")
    fmu = tmp_path / "node.fmu"
    fmu.write_bytes(b"")  # existence is checked at swap time; the FMU is read when the system is built
    s2 = sc.swap("node", str(fmu))
    assert s2.components["node"].fmu == str(fmu.resolve()) and s2.components["node"].implementation is None
    with pytest.raises(FileNotFoundError, match="FMU file .*missing.fmu not found"):
        sc.swap("node", str(tmp_path / "missing.fmu"))


@pytest.mark.parametrize("impl, message", [
    ("damper.nope", "unknown component implementation 'damper.nope'; known: .*damper.fast"),
    ("no_such_module:Damper", "no module 'no_such_module'"),
    ("rotorcosim.components.damper.component:Nope", "has no 'Nope'"),
    ("a:b:c", "must be written 'module:Class'"),
])
def test_swap_errors_name_the_implementation(impl, message):
    with pytest.raises(ScenarioError, match=message):
        rotorcosim.load_scenario("blade_loss_2850").swap("damper0", impl)


# -- simulate and the result, on the blade-loss system ---------------------------------------------------
@pytest.fixture(scope="module")
def run(tmp_path_factory):
    """The snippet, shortened to 1 ms (the FE damper costs ~10 ms per step), written to a folder too."""
    out = tmp_path_factory.mktemp("api")
    sc = rotorcosim.load_scenario("blade_loss_2850")
    sc = sc.set({"rotor.F_unbalance": 5700.0})
    sc = sc.swap("damper0", "damper.fe")
    res = rotorcosim.simulate(sc, duration=0.001, out=out, figures=False)
    return res, out


def test_simulate_returns_arrays_in_memory(run):
    res, out = run
    step = 5e-6 * round(5e-5 / 5e-6)  # the scenario's record_step, a whole number of TM steps
    assert isinstance(res.time, np.ndarray) and res.time[0] == 0.0 and abs(res.time[-1] - 0.001) < 1e-12
    assert np.allclose(np.diff(res.time), step)
    assert list(np.unique(res.phase)) == ["TM"]
    p = res["bearing0.P_drag"]
    assert p.shape == res.time.shape and np.all(p[1:] > 0)  # viscous drag: positive power once stepped
    assert res["rotor.X_brg0"].shape == (len(res.time), 3)
    assert res.unit("bearing0.P_drag") == "W" and res.columns("thermal0.T_nodes")[1] == "inner_race"
    with pytest.raises(KeyError, match="'rotor.V_brg0' was not recorded; recorded: rotor.X_brg0"):
        res["rotor.V_brg0"]


def test_result_arrays_equal_the_hdf5_file(run):
    res, out = run
    with h5py.File(out / "timeseries.h5") as f:
        assert np.array_equal(f["time"][:], res.time)
        assert np.array_equal(f["bearing0.P_drag"][:, 0], res["bearing0.P_drag"])
        assert np.array_equal(f["rotor.X_brg0"][:], res["rotor.X_brg0"])
        assert list(f["thermal0.T_nodes"].attrs["columns"])[:2] == ["shaft", "inner_race"]
        assert f["rotor.X_brg0"].attrs["description"].startswith("PT displacement at bearing #0")
        assert f["rotor.X_brg0"].attrs["sampling_interval_s"] == 5e-5


def test_summary_is_summary_json(run):
    res, out = run
    assert res.summary == json.loads((out / "summary.json").read_text())
    assert res.summary["unbalance_N"] == 5700.0
    assert res.summary["bearings"]["0"]["max_contact_load_N"] > 0
    assert [p.name for p in res.files] == ["summary.json", "timeseries.h5"]


def test_to_dataframe_has_labelled_columns_with_units(run):
    import pandas as pd   # in the test extra: its absence fails

    res, _ = run
    df = res.to_dataframe()
    assert isinstance(df, pd.DataFrame) and len(df) == len(res.time)
    assert list(df.columns[:5]) == ["time (s)", "phase", "rotor.X_brg0[x] (m)", "rotor.X_brg0[y] (m)",
                                    "rotor.X_brg0[z] (m)"]
    assert np.array_equal(df["bearing0.P_drag (W)"].to_numpy(), res["bearing0.P_drag"])
    assert "thermal0.T_nodes[sfd_oil] (K)" in df.columns


def test_to_dataframe_without_pandas_says_how_to_get_it(run, monkeypatch):
    import builtins

    real = builtins.__import__

    def no_pandas(name, *a, **k):
        if name == "pandas":
            raise ImportError("no pandas")
        return real(name, *a, **k)

    monkeypatch.setattr(builtins, "__import__", no_pandas)
    with pytest.raises(ImportError, match="needs pandas, which rotorcosim does not install: pip install pandas"):
        run[0].to_dataframe()


# -- simulate on the toy: schedules, record, no files ---------------------------------------------------
def test_simulate_without_out_writes_nothing(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    res = rotorcosim.simulate("toy_thermomechanical", duration=1.0, record=["node.T"])
    assert list(tmp_path.iterdir()) == [] and res.files == []
    assert res.signals == ["node.T"] and res["node.T"].shape == res.time.shape
    assert set(res.phase) == {"TM", "TO"}
    assert res.summary["final_outputs"]["node.T"][0] == pytest.approx(res["node.T"][-1])


def test_simulate_schedule_names():
    res = rotorcosim.simulate("toy_thermomechanical", duration=0.5, schedule="monolithic", record=[])
    assert [u["phase"] for u in res.summary["timeline"]] == ["TM"]
    with pytest.raises(ValueError, match="schedule 'fast'"):
        rotorcosim.simulate("toy_thermomechanical", schedule="fast")


# -- the command line over the API ---------------------------------------------------------------------
def test_cli_set_swap_record(tmp_path, capsys):
    assert main(["run", "toy_thermomechanical", "--duration", "1", "--quiet", "--out", str(tmp_path),
                 "--set", "node.C=20", "--set", "osc.F0=50", "--swap", "node=testing.thermal_node",
                 "--record", "node.T,osc.P"]) == 0
    s = json.loads((tmp_path / "summary.json").read_text())
    api = rotorcosim.simulate(rotorcosim.load_scenario("toy_thermomechanical").set({"node.C": 20.0, "osc.F0": 50.0}),
                              duration=1.0, record=["node.T", "osc.P"])
    assert s["final_outputs"]["node.T"] == api.summary["final_outputs"]["node.T"]
    with h5py.File(tmp_path / "timeseries.h5") as f:
        assert sorted(k for k in f if k not in ("time", "phase")) == ["node.T", "osc.P"]
        assert np.array_equal(f["node.T"][:, 0], api["node.T"])
    last = capsys.readouterr().out.strip().splitlines()[-1]
    assert last == f"written: {tmp_path / 'summary.json'}, {tmp_path / 'timeseries.h5'}"


def test_parse_set_values():
    from rotorcosim.master.scenario.overrides import parse_set

    assert parse_set("rotor.F_unbalance=5700") == ("rotor.F_unbalance", 5700)
    assert parse_set("thermal0.method=exact") == ("thermal0.method", "exact")
    assert parse_set("a.b=true") == ("a.b", True)
    assert parse_set("a.b=[1, 2.5]") == ("a.b", [1, 2.5])
    assert parse_set("rotor.F_unbalance=712,1425", values=True) == ("rotor.F_unbalance", [712, 1425])
    assert parse_set("a.v=[1,2],[3,4]", values=True) == ("a.v", [[1, 2], [3, 4]])
    with pytest.raises(ValueError, match="expected COMP.PARAM=VALUE"):
        parse_set("F_unbalance=1")
    with pytest.raises(ValueError, match="an empty value"):
        parse_set("a.b=")
    with pytest.raises(ValueError, match="'inf' is not a finite number"):
        parse_set("a.b=inf")


def test_scenarios_command_lists_each_shipped_scenario_on_one_line(capsys):
    assert main(["scenarios"]) == 0
    lines = capsys.readouterr().out.strip().splitlines()
    names = [ln.split()[0] for ln in lines]
    assert sorted(names) == sorted(p.stem for p in scenarios.FOLDER.glob("*.toml"))
    # natural order: the levels by value (1425 before 11401), as the error naming the shipped ones
    levels = [f"blade_loss_{f}" for f in (712, 1425, 2850, 5700, 8551, 11401, 14252)]
    # (the level scenarios; a named variant such as blade_loss_2850_updated follows its level)
    assert [n for n in names if re.fullmatch(r"blade_loss_\d+", n)] == levels
    assert names == scenarios.names()
    with pytest.raises(FileNotFoundError, match=", ".join(names)):
        scenarios.path("nope")
    assert any(ln.startswith("blade_loss_2850 ") and "2 850 N" in ln for ln in lines)
    assert all(len(ln.split(None, 1)) == 2 for ln in lines)  # every one has a description


def test_version(capsys):
    with pytest.raises(SystemExit) as info:
        main(["--version"])
    assert info.value.code == 0 and capsys.readouterr().out.strip() == f"rotorcosim {rotorcosim.__version__}"


def test_a_file_run_reads_its_arrays_from_the_file_and_they_equal_a_memory_run(tmp_path):
    """With out= and HDF5 the recorder keeps nothing in memory (a 2-minute monolithic run records ~0.5 GB): the
    result reads the file. Its arrays must be the very ones an in-memory run of the same scenario gives."""
    from rotorcosim.master.observer.series import SeriesFile

    on_file = rotorcosim.simulate("toy_thermomechanical", duration=1.0, record=["node.T"], out=tmp_path / "a")
    in_memory = rotorcosim.simulate("toy_thermomechanical", duration=1.0, record=["node.T"])
    assert isinstance(on_file._data, SeriesFile) and not isinstance(in_memory._data, SeriesFile)
    assert np.array_equal(on_file.time, in_memory.time)
    assert np.array_equal(on_file["node.T"], in_memory["node.T"])
    assert list(on_file.phase) == list(in_memory.phase)


def test_draw_figures_of_a_run_folder_names_what_is_missing(tmp_path):
    """api.draw_figures (compare draws its runs' figures with it after the timing) refuses, with a clear error,
    a folder that holds no finished run, a failed run, a run without an HDF5 time series, a scenario without
    figures."""
    from rotorcosim.master.api import draw_figures

    sc = rotorcosim.load_scenario("blade_loss_2850")
    with pytest.raises(ValueError, match="no readable summary.json"):
        draw_figures(sc, tmp_path)
    (tmp_path / "summary.json").write_text(json.dumps({"status": "failed", "timeseries": "timeseries.h5"}))
    with pytest.raises(ValueError, match="status is 'failed'"):
        draw_figures(sc, tmp_path)
    (tmp_path / "summary.json").write_text(json.dumps({"status": "complete", "timeseries": "timeseries.csv"}))
    with pytest.raises(ValueError, match="no HDF5 time series"):
        draw_figures(sc, tmp_path)
    with pytest.raises(ValueError, match="no \\[results\\] kind"):
        draw_figures("toy_thermomechanical", tmp_path)


@pytest.mark.parametrize("kwargs, error, message", [
    ({"duration": "1"}, TypeError, "duration must be a number of seconds, got str '1'"),
    ({"duration": True}, TypeError, "duration must be a number of seconds"),
    ({"record": "osc.x"}, TypeError, r"record: give a list of 'component.port' names, e.g. record=\['osc.x'\]"),
    ({"record": ["osc.x", "osc.x"]}, ValueError, r"record: 'osc.x' is listed twice"),
    # checked by the command line only before: the API ran with them
    ({"step_timeout": -1}, ValueError, r"step_timeout must be a number of seconds >= 0 \(0: no limit\), got -1"),
    ({"step_timeout": float("nan")}, ValueError, "step_timeout must be a number of seconds >= 0"),
    ({"checkpoint_every": 0}, ValueError, "checkpoint_every must be a positive number of seconds"),
])
def test_simulate_arguments_of_the_wrong_kind(kwargs, error, message):
    """A string where a number or a list is meant: named (was: "'>' not supported", or a record of letters)."""
    with pytest.raises(error, match=message):
        rotorcosim.simulate(rotorcosim.load_scenario("toy_thermomechanical"), **kwargs)


def test_load_scenario_with_an_empty_name():
    """Path("") is the current folder: was "scenario file ... is a folder"."""
    with pytest.raises(ValueError, match="an empty name"):
        rotorcosim.load_scenario("")


def test_simulate_accepts_numpy_numbers():
    import numpy as np

    res = rotorcosim.simulate("toy_thermomechanical", duration=np.float64(0.01), figures=False)
    assert res.summary["status"] == "complete"
    with pytest.raises(TypeError, match="give a Scenario, a shipped scenario's name or a file, got int"):
        rotorcosim.simulate(5)
