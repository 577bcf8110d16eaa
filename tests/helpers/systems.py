"""Shared builders for the master's tests: the two-mass system with its exact solution."""
from __future__ import annotations

import numpy as np
from scipy.linalg import expm

from rotorcosim.components.registry import create
from rotorcosim.master.core.system import Connection, System

P1 = dict(m=1.0, k=40.0, c=0.0, x0=0.1, v0=0.0)
P2 = dict(m=2.0, k=30.0, c=0.0, kc=100.0, cc=0.0, x0=0.0, v0=0.0)


def two_masses(p1=P1, p2=P2) -> System:
    comps = {"m1": create("testing.mass", "m1", p1), "m2": create("testing.spring", "m2", p2)}
    cons = [Connection("m1.x", "m2.x_in"), Connection("m1.v", "m2.v_in"), Connection("m2.F", "m1.F")]
    return System(comps, cons)


def exact(t: float, p1=P1, p2=P2) -> np.ndarray:
    """[x1, v1, x2, v2](t) of the coupled system, by the matrix exponential."""
    m1, k1, c1 = p1["m"], p1["k"], p1["c"]
    m2, k2, c2, kc, cc = p2["m"], p2["k"], p2["c"], p2["kc"], p2["cc"]
    A = np.array([
        [0, 1, 0, 0],
        [-(k1 + kc) / m1, -(c1 + cc) / m1, kc / m1, cc / m1],
        [0, 0, 0, 1],
        [kc / m2, cc / m2, -(k2 + kc) / m2, -(c2 + cc) / m2],
    ])
    z0 = np.array([p1["x0"], p1["v0"], p2["x0"], p2["v0"]])
    return expm(A * t) @ z0


def energy(sys: System, p1=P1, p2=P2) -> float:
    x1, v1 = sys.components["m1"].state["z"]
    x2, v2 = sys.components["m2"].state["z"]
    return 0.5 * (p1["m"] * v1**2 + p1["k"] * x1**2 + p2["m"] * v2**2 + p2["k"] * x2**2 + p2["kc"] * (x2 - x1) ** 2)
