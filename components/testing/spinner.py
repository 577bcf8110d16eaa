"""A toy shaft whose speed changes between thermo-mechanical intervals, to test cycle sources that follow a speed.

``Spinner``: turns at ``Omega0`` until its own time (the time it has been stepped) reaches ``t_switch``, then at
``Omega1`` [rad/s]; its angle integrates the speed of each step exactly. It outputs the speed it turns at over the next step
``Omega`` (rad/s), the angle ``theta`` (rad) and a power that fluctuates once a turn,
``P = P0 (1 + a cos(theta))`` [W], whose mean over whole turns is ``P0``. Mechanical: it takes part in
thermo-mechanical intervals only, so a thermal-only interval freezes it (its time, angle and speed).
"""
from __future__ import annotations

import math

import numpy as np

from ..contract import Component, ContractError, Variable


class Spinner(Component):
    variables = (
        Variable("Omega0", "parameter", unit="rad/s", start=2 * math.pi * 50.0, description="speed before t_switch"),
        Variable("Omega1", "parameter", unit="rad/s", start=2 * math.pi * 25.0, description="speed from t_switch"),
        Variable("t_switch", "parameter", unit="s", start=1e9, description="own time of the speed change"),
        Variable("P0", "parameter", unit="W", start=100.0, description="mean power"),
        Variable("a", "parameter", unit="1", start=0.5, description="relative amplitude of the power"),
        Variable("Omega", "output", unit="rad/s", description="speed over the next step"),
        Variable("theta", "output", unit="rad", description="angle"),
        Variable("P", "output", unit="W", description="power, fluctuating once a turn"),
    )
    preferred_step = 1e-3

    def _speed(self, t_own: float) -> float:
        # 1e-9 s: an own time that reaches t_switch by a sum of steps counts as reached
        return self.p["Omega1"] if t_own >= self.p["t_switch"] - 1e-9 else self.p["Omega0"]

    def _outputs(self) -> None:
        th = self.state["theta"]
        self.y["Omega"] = np.array([self._speed(self.state["t_own"])])
        self.y["theta"] = np.array([th])
        self.y["P"] = np.array([self.p["P0"] * (1.0 + self.p["a"] * math.cos(th))])

    def setup(self, t0=0.0):
        super().setup(t0)
        for key in ("Omega0", "Omega1", "t_switch"):
            if not math.isfinite(self.p[key]):
                raise ContractError(f"{self.name}.{key} must be finite, got {self.p[key]}")
        # its own time: it advances only while the spinner is stepped (a thermal-only interval freezes it)
        self.state = {"theta": 0.0, "t_own": float(t0)}
        self._outputs()

    def do_step(self, t, h):
        self.state["theta"] += self._speed(self.state["t_own"]) * h
        self.state["t_own"] += h
        self.time = t + h
        self._outputs()
