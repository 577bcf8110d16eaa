"""The spools' energy balance (cases/rundown/energy.py) is a check that can fail: the kinetic energy a spool loses
against the work of the torques its producers report, integrated apart from the spool's own step. A spool that
integrates one torque 1 % off what its producer reports moves the residual by 1 % of that torque's work; the
rub ring's dissipated energy exceeds its torque's work by the whirl's share it reports."""
from __future__ import annotations

import numpy as np
import pytest

from rotorcosim.cases.rundown.energy import SpoolEnergy
from rotorcosim.components.contract import Component, Variable
from rotorcosim.components.spool.component import Spool
from rotorcosim.master.core.system import Connection, System
from rotorcosim.master.schedule import Interval, Timeline
from rotorcosim.master.simulation import Simulation

#: the ring's power exceeds its torque's work by this share (a whirl's share of the sliding speed)
WHIRL = 0.024


class Ring(Component):
    """A rub ring's torque on a spool, growing with its speed, and its dissipated power."""

    variables = (
        Variable("Omega", "input", 1, "rad/s", "spool speed"),
        Variable("T_rub", "output", 1, "N.m", "friction torque"),
        Variable("P_rub", "output", 1, "W", "dissipated power"),
    )

    def do_step(self, t, h):
        w = float(self.u["Omega"][0])
        T = 2.0 + 4e-3 * w
        self.y["T_rub"] = np.array([T])
        self.y["P_rub"] = np.array([T * w * (1.0 + WHIRL)])
        self.time = t + h


class Perturbed(Spool):
    """A spool that integrates its first rub torque input ``SCALE`` times what the ring reports."""

    SCALE = 1.01

    def do_step(self, t, h):
        self.u["T_rub1"] = self.u["T_rub1"] * self.SCALE
        super().do_step(t, h)


def _run(spool_class):
    spool = spool_class("spool", {"profile": "torque", "inertia": 0.04, "speed_rpm": 16000.0, "t_fuel_cut": 0.05,
                                   "windmill_rpm": 4900.0, "aero_torque": 30.0})
    ring = Ring("ring")
    system = System({"spool": spool, "ring": ring},
                    [Connection("spool.Omega", "ring.Omega"), Connection("ring.T_rub", "spool.T_rub1")],
                    inputs={"spool.T_drag1": 0.5, "spool.T_drag2": 0.0, "spool.T_rub2": 0.0})
    energy = SpoolEnergy(["spool"])
    sim = Simulation(system, order=["spool", "ring"], observers=[energy])
    sim.run(Timeline([Interval("TM", 0.5, 1e-4)]))
    return energy.summary(sim)["spool"]


def test_balance_closes_and_a_one_percent_torque_error_moves_it():
    """The balance closes to the coupling's one-step lag (below 0.01 % of the energy exchanged); the spool that
    feels 1 % more rub torque than the ring reports loses 1 % of the rub work more kinetic energy than the reported
    torques account for: its residual is that, within 2 %."""
    ok = _run(Spool)
    assert ok["kinetic_energy_lost_J"] > 0.0 and ok["work_J"]["rub"] > 0.0 and ok["work_J"]["aero"] > 0.0
    assert abs(ok["residual_pct"]) < 0.01
    bad = _run(Perturbed)
    moved = bad["residual_J"] - ok["residual_J"]
    assert moved == pytest.approx((Perturbed.SCALE - 1.0) * bad["work_J"]["rub"], rel=0.02)
    assert abs(bad["residual_pct"]) > 20 * abs(ok["residual_pct"])


def test_rub_dissipation_and_its_whirl_share():
    """The ring's dissipated energy is reported apart from its torque's work, the difference its whirl share."""
    e = _run(Spool)
    assert e["rub_dissipated_J"] == pytest.approx((1.0 + WHIRL) * e["work_J"]["rub"], rel=1e-3)
    assert e["rub_whirl_share_J"] == pytest.approx(WHIRL * e["work_J"]["rub"], rel=0.05)
    assert e["drag_dissipated_J"] is None
