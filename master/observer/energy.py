"""Energy residual of power bonds (the ECCO idea of Sadjina et al. 2017, as used by libcosim).

A bond is a force/velocity pair exchanged between two components: component A receives a force ``F`` and
outputs the velocity ``v`` of the point it acts on; component B receives that velocity and outputs the force.
Exact coupling would make the power A receives, F_A . v_A, equal the power B delivers, F_B . v_B, at every
instant; a co-simulation with held inputs does not, and the integral of the difference is energy the coupling
created or destroyed. Its size relative to the energy exchanged measures the coupling error without knowing
the exact solution (the convergence study uses it beside the step halving).
"""
from __future__ import annotations

from typing import Sequence

import numpy as np

from rotorcosim.components.contract import COUPLED
from rotorcosim.master.observer.observer import Observer


class EnergyResidual(Observer):
    """``bonds``: pairs ("A.force_input", "A.velocity_output"), e.g. ("rotor.F_brgA", "rotor.V_brgA")."""

    def __init__(self, bonds: Sequence[tuple[str, str]]):
        self.bonds = [tuple(b) for b in bonds]
        self.residual = {b: 0.0 for b in self.bonds}
        self.exchanged = {b: 0.0 for b in self.bonds}

    def start(self, sim, schedule):
        self._pairs = []
        by_dst = {c.dst: c for c in sim.system.connections}
        by_src = {}
        for c in sim.system.connections:
            by_src.setdefault(c.src, []).append(c)
        for f_in, v_out in self.bonds:
            if f_in not in by_dst:
                raise ValueError(f"energy bond: {f_in} is not a connected input")
            f_src = by_dst[f_in].src  # B's force output
            b = f_src.partition(".")[0]
            v_dst = [c.dst for c in by_src.get(v_out, []) if c.dst.partition(".")[0] == b]
            if not v_dst:
                raise ValueError(f"energy bond: {v_out} does not drive the component {b!r} that produces {f_src}")
            a = f_in.partition(".")[0]
            self._pairs.append(((a, f_in.partition(".")[2]), (a, v_out.partition(".")[2]),
                                (b, f_src.partition(".")[2]), (b, v_dst[0].partition(".")[2])))
        self._last_t = sim.t

    def interval_start(self, sim, phase, step):
        self.active = phase == COUPLED
        self._last_t = sim.t

    def step(self, sim, t):
        h = t - self._last_t
        self._last_t = t
        if not self.active:
            return
        comps = sim.system.components
        for bond, ((a, fa), (_, va), (b, fb), (_, vb)) in zip(self.bonds, self._pairs):
            F_a = comps[a].u[fa]
            v_a = comps[a].y[va][: len(F_a)]
            F_b = comps[b].y[fb]
            v_b = comps[b].u[vb][: len(F_b)]
            p_a = float(np.dot(F_a, v_a))
            p_b = float(np.dot(F_b, v_b))
            self.residual[bond] += (p_b - p_a) * h
            self.exchanged[bond] += abs(p_a) * h

    def relative(self) -> dict:
        """Per bond (``"force / velocity"``): the energy residual relative to the energy exchanged [-] (0 for a
        bond that exchanged none)."""
        return {f"{a} / {b}": (self.residual[(a, b)] / self.exchanged[(a, b)] if self.exchanged[(a, b)] else 0.0)
                for a, b in self.bonds}
