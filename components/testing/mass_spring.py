"""Two masses and springs split into two components: the master's test system with an exact solution.

System: m1 x1'' = -k1 x1 - c1 x1' + F,    m2 x2'' = -k2 x2 - c2 x2' - kc (x2 - x1) - cc (x2' - x1'),
F = kc (x2 - x1) + cc (x2' - x1').  ``Mass`` is body 1 (force in, motion out); ``Spring`` is body 2 with the
coupling spring (motion of body 1 in, force on body 1 out). Each integrates its own linear ODE exactly over a
step with its inputs held, so the only error left is the coupling (the thing the master's tests measure).
"""
from __future__ import annotations

import numpy as np
from scipy.linalg import expm

from ..contract import Component, Variable


def _exact_step(A: np.ndarray, b: np.ndarray, z: np.ndarray, h: float, cache: dict) -> np.ndarray:
    """z(t+h) for z' = A z + b with A, b constant: exp of the augmented matrix [[A, b], [0, 0]]."""
    n = len(z)
    key = (h, A.tobytes())
    E = cache.get(key)
    if E is None:
        aug = np.zeros((n + 1, n + 1))
        aug[:n, :n] = A
        aug[:n, n] = 1.0
        E = expm(aug * h)
        cache.clear()
        cache[key] = E
    return E[:n, :n] @ z + E[:n, n] * b


class Mass(Component):
    description = "Mass on a spring-damper to ground, driven by an external force"
    variables = (
        Variable("m", "parameter", unit="kg", start=1.0, description="mass"),
        Variable("k", "parameter", unit="N/m", start=1.0, description="stiffness to ground"),
        Variable("c", "parameter", unit="N.s/m", start=0.0, description="damping to ground"),
        Variable("x0", "parameter", unit="m", start=0.0, description="initial displacement"),
        Variable("v0", "parameter", unit="m/s", start=0.0, description="initial velocity"),
        Variable("F", "input", unit="N", description="external force"),
        Variable("x", "output", unit="m", description="displacement"),
        Variable("v", "output", unit="m/s", description="velocity"),
    )
    preferred_step = 1e-3

    def setup(self, t0=0.0):
        super().setup(t0)
        self.state = {"z": np.array([self.p["x0"], self.p["v0"]])}
        self._cache = {}
        self._publish()

    def _publish(self):
        self.y["x"] = self.state["z"][:1].copy()
        self.y["v"] = self.state["z"][1:].copy()

    def do_step(self, t, h):
        m, k, c = self.p["m"], self.p["k"], self.p["c"]
        A = np.array([[0.0, 1.0], [-k / m, -c / m]])
        b = np.array([0.0, self.u["F"][0] / m])
        self.state["z"] = _exact_step(A, b, self.state["z"], h, self._cache)
        self.time = t + h
        self._publish()

    def energy(self) -> float:
        x, v = self.state["z"]
        return 0.5 * self.p["m"] * v * v + 0.5 * self.p["k"] * x * x


class Spring(Component):
    description = "Mass on a spring-damper to ground, coupled by a spring-damper to a moving point"
    variables = (
        Variable("m", "parameter", unit="kg", start=1.0, description="mass"),
        Variable("k", "parameter", unit="N/m", start=1.0, description="stiffness to ground"),
        Variable("c", "parameter", unit="N.s/m", start=0.0, description="damping to ground"),
        Variable("kc", "parameter", unit="N/m", start=1.0, description="coupling stiffness"),
        Variable("cc", "parameter", unit="N.s/m", start=0.0, description="coupling damping"),
        Variable("x0", "parameter", unit="m", start=0.0, description="initial displacement"),
        Variable("v0", "parameter", unit="m/s", start=0.0, description="initial velocity"),
        Variable("x_in", "input", unit="m", description="displacement of the other body"),
        Variable("v_in", "input", unit="m/s", description="velocity of the other body"),
        Variable("F", "output", unit="N", description="coupling force on the other body"),
        Variable("x", "output", unit="m", description="displacement"),
        Variable("v", "output", unit="m/s", description="velocity"),
    )
    preferred_step = 1e-3

    def setup(self, t0=0.0):
        super().setup(t0)
        self.state = {"z": np.array([self.p["x0"], self.p["v0"]])}
        self._cache = {}
        self._publish()

    def _publish(self):
        x, v = self.state["z"]
        self.y["x"] = np.array([x])
        self.y["v"] = np.array([v])
        self.y["F"] = np.array([self.p["kc"] * (x - self.u["x_in"][0]) + self.p["cc"] * (v - self.u["v_in"][0])])

    def do_step(self, t, h):
        p = self.p
        m = p["m"]
        A = np.array([[0.0, 1.0], [-(p["k"] + p["kc"]) / m, -(p["c"] + p["cc"]) / m]])
        b = np.array([0.0, (p["kc"] * self.u["x_in"][0] + p["cc"] * self.u["v_in"][0]) / m])
        self.state["z"] = _exact_step(A, b, self.state["z"], h, self._cache)
        self.time = t + h
        self._publish()

    def energy(self, x_other: float) -> float:
        x, v = self.state["z"]
        p = self.p
        return 0.5 * p["m"] * v * v + 0.5 * p["k"] * x * x + 0.5 * p["kc"] * (x - x_other) ** 2
