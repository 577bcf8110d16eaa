"""The command line on the toy system: run writes whole result files, sweep runs levels on Dask."""
import json
import subprocess
import sys

import h5py
import numpy as np
import pytest

from rotorcosim.master.cli import main
from rotorcosim.master.cli.sweep import parse_levels, sweep


def test_run_writes_summary_and_timeseries(tmp_path):
    assert main(["run", "toy_thermomechanical", "--out", str(tmp_path), "--quiet"]) == 0
    s = json.loads((tmp_path / "summary.json").read_text())
    assert [u["phase"] for u in s["timeline"]][:2] == ["TM", "TO"]
    assert abs(s["t_end_s"] - 30.0) < 1e-9
    with h5py.File(tmp_path / "timeseries.h5") as f:
        assert f.attrs["complete"]
        assert f["node.T"].attrs["unit"] == "K"
        assert np.isclose(f["node.T"][-1, 0], s["final_outputs"]["node.T"][0])
    assert not list(tmp_path.glob("*.part"))


def test_run_monolithic_and_duration(tmp_path):
    assert main(["run", "toy_thermomechanical", "--schedule", "monolithic", "--duration", "0.5",
                 "--out", str(tmp_path), "--quiet"]) == 0
    s = json.loads((tmp_path / "summary.json").read_text())
    assert len(s["timeline"]) == 1 and s["timeline"][0]["phase"] == "TM" and s["timeline"][0]["steps"] == 500


def test_run_csv_output(tmp_path):
    src = (tmp_path / "toy.toml")
    from rotorcosim import scenarios
    text = scenarios.path("toy_thermomechanical").read_text().replace('format = "h5"', 'format = "csv"')
    src.write_text(text)
    assert main(["run", str(src), "--out", str(tmp_path / "o"), "--quiet", "--duration", "1"]) == 0
    header = (tmp_path / "o" / "timeseries.csv").read_text().splitlines()[0]
    assert header.startswith("time (s),phase,osc.x (m)")


@pytest.mark.parametrize("argv, message", [
    (["run", "no_such_scenario", "--out", "X"], "no shipped scenario"),
    (["run", "toy_thermomechanical", "--duration", "-1", "--out", "X"], "--duration must be a positive"),
    (["run", "toy_thermomechanical", "--unbalance", "nan", "--out", "X"], "--unbalance must be a finite"),
    (["sweep", "toy_thermomechanical", "--unbalance", "paper", "--out", "X"],
     "'paper' is neither a number nor a named set (the scenario's case declares none)"),
    (["sweep", "--unbalance", "1,abc", "--out", "X"], "'abc' is neither a number nor one of the scenario's named sets (paper)"),
])
def test_cli_errors_are_one_line(tmp_path, argv, message):
    argv = [a if a != "X" else str(tmp_path / "x") for a in argv]
    r = subprocess.run([sys.executable, "-m", "rotorcosim.master.cli", *argv], capture_output=True, text=True)
    assert r.returncode == 2
    assert message in r.stderr and "Traceback" not in r.stderr


def test_parse_levels():
    from rotorcosim.cases.blade_loss import LEVELS

    assert parse_levels("paper", LEVELS) == [712.0, 1425.0, 2850.0, 5700.0, 8551.0, 11401.0, 14252.0]
    assert parse_levels("1, 2,3") == [1.0, 2.0, 3.0]
    with pytest.raises(ValueError, match="repeated"):
        parse_levels("1,1")


def test_sweep_on_local_dask_cluster_matches_serial(tmp_path):
    """Two levels on a 2-worker local Dask cluster give the same numbers as run one after another."""
    a = sweep([50.0, 100.0], tmp_path / "dask", "toy_thermomechanical", duration=5.0, workers=2)
    b = sweep([50.0, 100.0], tmp_path / "serial", "toy_thermomechanical", duration=5.0, serial=True)
    assert not a["errors"] and not b["errors"]
    for f in ("50", "100"):
        sa = json.loads((tmp_path / "dask" / f"level_{f}" / "summary.json").read_text())
        sb = json.loads((tmp_path / "serial" / f"level_{f}" / "summary.json").read_text())
        assert sa["final_outputs"] == sb["final_outputs"]
    assert (tmp_path / "dask" / "sweep.csv").exists()
    # the toy scenario has no case: the paper's Table 5 is not written for it (the blade-loss sweeps' is checked in
    # tests/master/test_sweep_cluster.py)
    assert not (tmp_path / "dask" / "table5.csv").exists()
