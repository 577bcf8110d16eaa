"""Sweeps on a Dask cluster of separate processes, and the --set parameter grid.

The cluster test starts ``dask scheduler`` and two ``dask worker`` processes, each worker in a working folder of
its own (as on other machines), and checks that every case's files come back to the client's --out folder and
that the numbers equal the same cases run in this process.
"""
from __future__ import annotations

import json
import os
import socket
import subprocess
import sys
import time

import pytest

from rotorcosim.master.cli import main
from rotorcosim.master.cli.sweep import cases_of, parse_grid, sweep


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@pytest.fixture(scope="module")
def dask_cluster(tmp_path_factory):
    """``dask scheduler`` + two ``dask worker`` processes on loopback, each worker in its own folder."""
    root = tmp_path_factory.mktemp("cluster")
    port = _free_port()
    address = f"tcp://127.0.0.1:{port}"
    env = {**os.environ, "PYTHONUNBUFFERED": "1"}
    procs = [subprocess.Popen([sys.executable, "-m", "distributed.cli.dask_scheduler", "--host", "127.0.0.1",
                               "--port", str(port), "--no-dashboard"], cwd=root, env=env,
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)]
    for i in range(2):
        wdir = root / f"worker{i}"
        wdir.mkdir()
        procs.append(subprocess.Popen([sys.executable, "-m", "distributed.cli.dask_worker", address,
                                       "--nthreads", "1", "--nworkers", "1", "--no-dashboard",
                                       "--local-directory", str(wdir), "--name", f"w{i}"],
                                      cwd=wdir, env={**env, "TMPDIR": str(wdir)},
                                      stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
    try:
        from dask.distributed import Client

        deadline = time.monotonic() + 60
        while True:
            try:
                with Client(address, timeout=5) as c:
                    if len(c.scheduler_info()["workers"]) == 2:
                        break
            except OSError:
                pass
            if time.monotonic() > deadline:
                pytest.fail("the Dask scheduler and two workers did not come up within 60 s")
            time.sleep(0.5)
        yield address, root
    finally:
        for p in procs[::-1]:
            p.terminate()
        for p in procs:
            try:
                p.wait(timeout=20)
            except subprocess.TimeoutExpired:
                p.kill()


def test_sweep_on_separate_scheduler_and_workers(dask_cluster, tmp_path):
    address, root = dask_cluster
    out = tmp_path / "client_out"
    info = sweep([50.0, 100.0], out, "toy_thermomechanical", scheduler=address, duration=5.0,
                 grid={"node.C": [10.0, 20.0]})
    assert not info["errors"], info["errors"]
    assert info["executed_on"].startswith(address)
    assert len(info["cases"]) == 4
    ref = sweep([50.0], tmp_path / "serial", "toy_thermomechanical", duration=5.0, serial=True,
                grid={"node.C": [20.0]})
    for name in info["cases"]:
        folder = out / name
        assert (folder / "summary.json").exists() and (folder / "timeseries.h5").exists(), name
    a = json.loads((out / "level_50_node.C=20" / "summary.json").read_text())
    b = json.loads((tmp_path / "serial" / "level_50_node.C=20" / "summary.json").read_text())
    assert a["final_outputs"] == b["final_outputs"]
    assert ref["cases"] == ["level_50_node.C=20"]
    # the workers ran in their own folders and left no case files there or in the client's working folder
    for i in range(2):
        leftovers = [p for p in (root / f"worker{i}").rglob("rotorcosim-case-*")]
        assert not leftovers, leftovers
    rows = (out / "sweep.csv").read_text().splitlines()
    assert rows[0].startswith("case,level,node.C,") and len(rows) == 5   # the toy's generic level column


def test_unreachable_scheduler_is_a_clear_error(tmp_path):
    port = _free_port()  # nothing listens there
    with pytest.raises(ValueError, match="cannot reach the Dask scheduler"):
        sweep([50.0], tmp_path / "x", "toy_thermomechanical", scheduler=f"tcp://127.0.0.1:{port}", duration=1.0,
              connect_timeout=2.0)


def test_parse_grid_and_cases():
    grid = parse_grid(["damper0.c=0.1,0.2", "bearing0.mode=fast,exact", "rotor.on=true,false"])
    assert grid == {"damper0.c": [0.1, 0.2], "bearing0.mode": ["fast", "exact"], "rotor.on": [True, False]}
    cases = cases_of([712.0], {"damper0.c": [0.1, 0.2]})
    assert [c.name for c in cases] == ["F_712_damper0.c=0.1", "F_712_damper0.c=0.2"]
    assert cases[1].settings == {"damper0.c": 0.2} and cases[1].level == 712.0
    for bad, msg in [(["damper0.c"], "COMP.PARAM="), (["c=1"], "COMP.PARAM="), (["a.b=1,1"], "repeated"),
                     (["a.b=1", "a.b=2"], "twice"), (["a.b=1,,2"], "empty value"), (["a.b=nan"], "finite")]:
        with pytest.raises(ValueError, match=msg):
            parse_grid(bad)
    with pytest.raises(ValueError, match="nothing to sweep"):
        cases_of(None, {})


def test_set_grid_names_unknown_component(tmp_path, capsys):
    rc = main(["sweep", "--set", "nosuch.C=1,2", "--scenario", "toy_thermomechanical", "--serial",
               "--out", str(tmp_path / "x")])
    assert rc == 2
    assert "no component 'nosuch'" in capsys.readouterr().err


@pytest.mark.parametrize("item, message", [
    ("osc.nope=1,2", "has no parameter 'nope'"),
    ("osc.F0=100,abc", "set osc.F0: expected a number"),   # the bad value is the second case's
])
def test_set_grid_is_checked_before_any_case_runs(tmp_path, capsys, item, message):
    """A parameter the component lacks or a value of the wrong kind in any case: exit 2 before the first case
    runs (not a failed case after the others ran), and no case folder written."""
    out = tmp_path / "x"
    rc = main(["sweep", "--set", item, "--scenario", "toy_thermomechanical", "--serial", "--duration", "0.01",
               "--out", str(out)])
    assert rc == 2
    err = capsys.readouterr().err
    assert message in err and "Traceback" not in err
    assert not out.exists() or not any(out.iterdir())


def test_scheduler_address_that_is_not_one(tmp_path):
    with pytest.raises(ValueError, match=r"--scheduler bogus://x:1: not a Dask scheduler's address \(unknown "
                                         r"address scheme"):
        sweep([50.0], tmp_path / "x", "toy_thermomechanical", scheduler="bogus://x:1", duration=1.0)


def test_workers_must_be_positive(tmp_path):
    for n in (0, -1):
        with pytest.raises(ValueError, match="--workers must be at least 1"):
            sweep([50.0], tmp_path / "x", "toy_thermomechanical", duration=1.0, workers=n)


def test_case_folder_names_from_file_paths_and_collisions():
    """A file path names its case by its file name (``--set rotor.model_file=/abs/x.toml`` was refused as "not a
    usable folder name"); two files of one name would share a folder: refused, naming both."""
    cases = cases_of([712.0], {"rotor.model_file": ["/tmp/study/cand.toml"], "damper0.c": [0.1]})
    assert [c.name for c in cases] == ["F_712_rotor.model_file=cand.toml_damper0.c=0.1"]
    assert cases[0].settings["rotor.model_file"] == "/tmp/study/cand.toml"   # the value itself is kept whole
    assert [c.name for c in cases_of(None, {"a.b": [["/x/y", "z"], "p\nq"]})] == ["a.b=['_x_y', 'z']", "a.b=p_q"]
    with pytest.raises(ValueError, match="two cases would share the folder 'rotor.model_file=e.toml'"):
        cases_of(None, {"rotor.model_file": ["/a/e.toml", "/b/e.toml"]})
    with pytest.raises(ValueError, match="longer than a folder name may be"):
        cases_of(None, {"a.b": ["x" * 300]})


@pytest.mark.slow   # ~20 s (measured): a local Dask cluster started and stopped for seven levels
def test_levels_with_one_value_per_parameter_get_the_paper_tables(tmp_path):
    """A modified model at the paper's levels (one --set value: one case a level) gets table5.csv and
    paper_comparison.csv like a plain level sweep; a model file given by an absolute path runs."""
    from rotorcosim.components.rotor import model as fem

    model = tmp_path / "models" / "engine copy.toml"
    model.parent.mkdir()
    model.write_bytes(fem.DEFAULT_FILE.read_bytes())
    info = sweep([712.0, 1425.0], tmp_path / "out", "blade_loss", duration=0.002, serial=True,
                 grid={"rotor.model_file": [str(model)]})
    assert info["errors"] == {}
    assert sorted(p.name for p in (tmp_path / "out").iterdir() if p.is_dir()) == [
        "F_1425_rotor.model_file=engine copy.toml", "F_712_rotor.model_file=engine copy.toml"]
    for name in ("table5.csv", "table5.md", "paper_comparison.csv", "paper_comparison.png"):
        assert (tmp_path / "out" / name).is_file(), name
    # the two levels' cells: 11 results x 2 bearings x 2, less 712 N's two printed zeros that are rounding
    assert info["paper_score"]["cells"] == 42
