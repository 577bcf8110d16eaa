"""Steady synchronous unbalance response of a linear engine model (direct harmonic solve).

The model (:class:`~rotorcosim.components.rotor.model.FullModel`, optionally with its co-simulated bearings
linearised, :meth:`FullModel.coupled`) under a force of amplitude F rotating forward at the first spool's
speed Omega at one node: (K - Omega^2 M + i Omega (C + Omega G_1 + Omega r G_2)) X = F (1, -i) in (x, y), r the
second spool's speed ratio, K and C with the speed-dependent supports' coefficients at Omega. The complex amplitudes X of every DOF are returned; a node's x amplitude is |X_x|.

Example::

    from rotorcosim.components.rotor import model, response
    m = model.load("engine.toml")
    X = response.unbalance_response(m, None, ("shaft", 2), force=1.0, rpm=4000.0)
    amp_x = abs(X[m.info["dof"]("shaft", 2, 0)])
"""
from __future__ import annotations

import numpy as np

from .model import RPM, FullModel, speed_support_delta


def unbalance_response(model: FullModel, supports: dict | None, node: tuple, force: float, rpm: float,
                       phase: float = 0.0) -> np.ndarray:
    """Complex DOF amplitudes [m] of the model (with ``supports`` linearised, or None) under ``force`` [N]
    rotating at ``rpm`` [rev/min] at ``node`` = (spool, node), angle ``phase`` [rad] at t = 0."""
    W = float(rpm) * RPM
    r = model.omega_gg / model.omega_pt
    s = model.coupled(supports) if supports is not None else {
        "M": model.M, "K": model.K, "C": model.C, "G_pt": model.G_pt, "G_gg": model.G_gg}
    K, C = s["K"], s["C"]
    if model.info.get("speed_supports"):   # their coefficients at this speed (K and C hold the file's speed_rpm's)
        dK, dC = speed_support_delta(model, W, K.shape[0])
        K, C = K + dK, C + dC
    A = K - W ** 2 * s["M"] + 1j * W * (C + W * s["G_pt"] + W * r * s["G_gg"])
    f = np.zeros(A.shape[0], complex)
    ux = model.info["dof"](node[0], node[1], 0)
    uy = model.info["dof"](node[0], node[1], 1)
    f[ux], f[uy] = force * np.exp(1j * phase), -1j * force * np.exp(1j * phase)
    return np.linalg.solve(A, f)
