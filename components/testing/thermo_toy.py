"""A toy thermo-mechanical pair with known behaviour, to test the master's multi-rate and staggered schemes.

``DampedOscillator``: m x'' + c(T) x' + k x = F0 sin(W t), with c(T) = c0 exp(-b (T - T0)) (damping falls as
the oil heats, as in the squeeze film damper). It outputs the dissipated power as the mean over its step
(exact energy over the step / h) and the cumulative dissipated energy. RK4 sub-steps, the energy integrated
alongside the motion.

``ThermalNode``: C dT/dt = P - (T - Ta) / R, integrated exactly with P held over the step; it outputs T and
the cumulative heat received.
"""
from __future__ import annotations

import math

import numpy as np

from ..contract import Component, ContractError, Variable


def _positive(comp, keys):
    for key in keys:
        if not comp.p[key] > 0.0:
            raise ContractError(f"{comp.name}.{key} must be > 0, got {comp.p[key]}")


class DampedOscillator(Component):
    description = "Forced damped oscillator whose damping depends on temperature"
    step_cost_s = 55e-6  # it sub-steps (bench/bench_estimate.py)
    variables = (
        Variable("m", "parameter", unit="kg", start=1.0),
        Variable("k", "parameter", unit="N/m", start=(2 * math.pi * 50.0) ** 2),
        Variable("c0", "parameter", unit="N.s/m", start=100.0, description="damping at T0"),
        Variable("b", "parameter", unit="1/K", start=0.03, description="damping temperature coefficient"),
        Variable("T0", "parameter", unit="K", start=303.15),
        Variable("F0", "parameter", unit="N", start=100.0, description="forcing amplitude"),
        Variable("W", "parameter", unit="rad/s", start=2 * math.pi * 45.0, description="forcing frequency"),
        Variable("max_substep", "parameter", unit="s", start=2e-4),
        Variable("T", "input", unit="K", start=303.15, description="temperature"),
        Variable("x", "output", unit="m"),
        Variable("v", "output", unit="m/s"),
        Variable("P", "output", unit="W", description="dissipated power, mean over the last step"),
        Variable("E", "output", unit="J", description="dissipated energy since the start"),
    )
    preferred_step = 1e-3

    def setup(self, t0=0.0):
        super().setup(t0)
        _positive(self, ("m", "k", "max_substep", "T0"))
        if self.p["c0"] < 0.0:
            raise ContractError(f"{self.name}.c0 must be >= 0, got {self.p['c0']}")
        self.state = {"z": np.zeros(3)}  # x, v, dissipated energy
        self.y["P"] = np.zeros(1)

    def _rhs(self, t, z, c):
        p = self.p
        x, v, _ = z
        a = (p["F0"] * math.sin(p["W"] * t) - c * v - p["k"] * x) / p["m"]
        return np.array([v, a, c * v * v])

    def do_step(self, t, h):
        p = self.p
        c = p["c0"] * math.exp(-p["b"] * (self.u["T"][0] - p["T0"]))
        n = max(1, math.ceil(h / p["max_substep"] - 1e-9))
        dt = h / n
        z = self.state["z"].copy()
        e0 = z[2]
        for i in range(n):
            ti = t + i * dt
            k1 = self._rhs(ti, z, c)
            k2 = self._rhs(ti + dt / 2, z + dt / 2 * k1, c)
            k3 = self._rhs(ti + dt / 2, z + dt / 2 * k2, c)
            k4 = self._rhs(ti + dt, z + dt * k3, c)
            z = z + dt / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
        self.state["z"] = z
        self.time = t + h
        self.y["x"] = z[:1].copy()
        self.y["v"] = z[1:2].copy()
        self.y["E"] = z[2:].copy()
        self.y["P"] = np.array([(z[2] - e0) / h])


class ThermalNode(Component):
    description = "Lumped thermal node heated by a power input, cooled to ambient"
    variables = (
        Variable("C", "parameter", unit="J/K", start=50.0, description="heat capacity"),
        Variable("R", "parameter", unit="K/W", start=0.04, description="resistance to ambient"),
        Variable("Ta", "parameter", unit="K", start=303.15, description="ambient temperature"),
        Variable("T_init", "parameter", unit="K", start=303.15),
        Variable("P", "input", unit="W", description="heat input"),
        Variable("T", "output", unit="K", start=303.15),
        Variable("E_in", "output", unit="J", description="heat received since the start"),
    )
    preferred_step = 0.05
    phases = frozenset({"TM", "TO"})
    step_cost_s = 2e-6

    def setup(self, t0=0.0):
        super().setup(t0)
        _positive(self, ("C", "R", "Ta", "T_init"))
        self.state = {"T": self.p["T_init"], "E": 0.0}
        self.y["T"] = np.array([self.p["T_init"]])
        self.y["E_in"] = np.zeros(1)

    def do_step(self, t, h):
        p = self.p
        P = self.u["P"][0]
        T_inf = p["Ta"] + P * p["R"]
        T = T_inf + (self.state["T"] - T_inf) * math.exp(-h / (p["R"] * p["C"]))
        self.state["T"] = T
        self.state["E"] += P * h
        self.time = t + h
        self.y["T"] = np.array([T])
        self.y["E_in"] = np.array([self.state["E"]])
