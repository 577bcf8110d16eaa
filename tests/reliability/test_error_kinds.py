"""A run's failure says first what happened: a divergence (NaN/inf), a component's own exception, a timed-out step
and a crashed process each have their own first words on the command line and their own kind in summary.json's
``error`` (``status`` "failed" for all). The timed-out and crashed steps of an FMU out of process are checked in
tests/fmus/test_fmu_process.py, the in-process time limit in test_watchdog.py; here the two a plain component
makes, through ``rotorcosim run`` and ``rotorcosim sweep``."""
from __future__ import annotations

import json

import pytest

from rotorcosim.master.cli import main
from rotorcosim.master.core.algorithm import (ComponentCrashed, ComponentFailed, SimulationDiverged,
                                              SimulationFailed, StepTimedOut)
from tests.helpers import faulty


@pytest.mark.parametrize("fault, first, kind", [
    ({"nan_at": 0.0105}, "the simulation diverged: node.T is not finite at t = 0.012 s", "SimulationDiverged"),
    ({"raise_at": 0.0105}, "a component failed: node failed in do_step at t = 0.011 s: the faulty node's own error",
     "ComponentFailed"),
])
def test_run_says_what_happened_first(tmp_path, capsys, fault, first, kind):
    sc = faulty.scenario(tmp_path, **fault)
    out = tmp_path / "out"
    assert main(["run", str(sc), "--duration", "0.05", "--quiet", "--no-figures", "--out", str(out)]) == 1
    err = capsys.readouterr().err.splitlines()
    assert err[0].startswith(f"rotorcosim run: {first}"), err
    s = json.loads((out / "summary.json").read_text())
    assert s["status"] == "failed" and s["error"].startswith(f"{kind}: "), s["error"]
    if kind != "SimulationDiverged":
        assert "diverged" not in err[0] and "diverged" not in s["error"]


def test_a_sweep_case_names_its_kind(tmp_path, capsys):
    sc = faulty.scenario(tmp_path)
    argv = ["sweep", str(sc), "--set", "node.raise_at=-1,0.01", "--set", "node.nan_at=-1,0.02", "--duration", "0.05",
            "--serial", "--quiet", "--out", str(tmp_path / "out")]
    assert main(argv) == 1
    errors = json.loads((tmp_path / "out" / "sweep.json").read_text())["errors"]
    assert sorted(errors) == ["node.raise_at=-1_node.nan_at=0.02", "node.raise_at=0.01_node.nan_at=-1",
                              "node.raise_at=0.01_node.nan_at=0.02"]
    assert errors["node.raise_at=-1_node.nan_at=0.02"].startswith("SimulationDiverged: node.T is not finite")
    assert errors["node.raise_at=0.01_node.nan_at=-1"].startswith("ComponentFailed: node failed in do_step")
    assert errors["node.raise_at=0.01_node.nan_at=0.02"].startswith("ComponentFailed: node failed in do_step")


def test_the_kinds_are_distinct():
    """Each kind's first words differ, and only a divergence is a SimulationDiverged."""
    kinds = (SimulationDiverged, ComponentFailed, StepTimedOut, ComponentCrashed)
    assert len({k.what for k in kinds}) == 4 and all(issubclass(k, SimulationFailed) for k in kinds)
    assert [k for k in kinds if issubclass(k, SimulationDiverged)] == [SimulationDiverged]
