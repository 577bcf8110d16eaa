"""The critical speeds the rundown figures mark (cases/rundown/modes.marked_critical_speeds): the scenario's
``[results] critical_speeds_rpm`` when it gives them, else the engine's forward synchronous critical speeds of the
linear engine ``check-engine`` lists, up to 1.1 x the run's top speed."""
from __future__ import annotations

from pathlib import Path

import pytest

import rotorcosim
from rotorcosim.cases.blade_loss import linear_engine
from rotorcosim.cases.rundown.modes import marked_critical_speeds
from rotorcosim.components.rotor import critical
from rotorcosim.components.rotor import model as fem
from rotorcosim.master.core.threads import one_thread

THREE = Path(__file__).resolve().parents[2] / "docs" / "examples" / "three_bearings"


def test_given_speeds_are_drawn_as_given():
    sc = rotorcosim.load_scenario("blade_loss_rundown")
    assert marked_critical_speeds(sc, "spool_pt", 16000.0) == [8500.0, 10200.0]


def test_derived_from_the_engine_when_the_scenario_gives_none():
    with one_thread():
        sc = rotorcosim.load_scenario(THREE / "rundown.toml")
        assert "critical_speeds_rpm" not in sc.extra["results"]
        got = marked_critical_speeds(sc, "spool", 16000.0)
        # the forward critical speeds of the undamped engine's own eigenproblem (critical.synchronous_critical_speeds,
        # another solve than the figures' every_synchronous_critical_speed) up to 1.1 x 16 000 rev/min
        m = fem.load(THREE / "engine.toml")
        ref = critical.synchronous_critical_speeds(m, linear_engine.supports(sc, data=m.data), n=20, max_rpm=17600.0)
        assert got == pytest.approx(ref["forward_synchronous_rpm"], rel=1e-9) and len(got) == 3
        # the paper's rundown without its key: the engine's own, where the scenario's were copied from
        paper = rotorcosim.load_scenario("blade_loss_rundown")
        del paper.extra["results"]["critical_speeds_rpm"]
        assert marked_critical_speeds(paper, "spool_pt", 16000.0) == pytest.approx([8500.0, 10200.0], rel=1e-4)
