"""Calibration of the model geometry to the paper's two lowest forward synchronous critical speeds.

The paper (section 4.1) gives 8500 and 10 200 rev/min but not the geometry. Two knobs of data/engine.toml's
[calibration] table are solved for by Newton's method with a finite-difference Jacobian (everything else fixed
beforehand): ``pt_stage_mass_kg`` (mainly the first critical speed, the overhung power turbine on bearing #0) and
``mount_k``, the stiffness of each engine-mount link (mainly the second, a casing-on-mounts mode with the gas
generator and the power turbine whirling with it). Run ``python -m rotorcosim.components.rotor.calibration [FILE]``: it
prints the knob values to write into the data file (the file is not rewritten, so its comments stay the record).
"""
from __future__ import annotations

import copy
import sys

import numpy as np

from . import critical, model

KNOBS = ("pt_stage_mass_kg", "mount_k")


def forward_criticals(data: dict, values=None, n: int = 2) -> np.ndarray:
    d = copy.deepcopy(data)
    if values is not None:
        d["calibration"].update({k: float(v) for k, v in zip(KNOBS, values)})
    return np.asarray(critical.synchronous_critical_speeds(model.build(d), n=n)["forward_synchronous_rpm"][:n])


def calibrate(data: dict, tol_rpm: float = 1.0, max_iter: int = 10) -> tuple[np.ndarray, np.ndarray]:
    target = np.asarray(data["calibration"]["target_rpm"], float)
    x = np.array([float(data["calibration"][k]) for k in KNOBS])
    for _ in range(max_iter):
        f = forward_criticals(data, x)
        print(f"  {dict(zip(KNOBS, x.round(4)))} -> {f.round(1)} rev/min", flush=True)
        if np.max(np.abs(f - target)) < tol_rpm:
            break
        J = np.empty((2, 2))
        for j in range(2):
            dx = x.copy()
            dx[j] *= 1.01
            J[:, j] = (forward_criticals(data, dx) - f) / (dx[j] - x[j])
        x = x - np.linalg.solve(J, f - target)
    return x, f


if __name__ == "__main__":
    d, _ = model.load_data(sys.argv[1] if len(sys.argv) > 1 else None)
    x, f = calibrate(d)
    for k, v in zip(KNOBS, x):
        print(f"{k} = {v:.4f}")
    print("forward synchronous critical speeds:", f.round(1))
