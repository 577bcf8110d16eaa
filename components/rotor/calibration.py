"""Calibration of the model geometry to the paper's two lowest forward synchronous critical speeds.

The paper (section 4.1) gives 8500 and 10 200 rev/min but not the geometry. Two knobs of data/engine.toml's
[calibration] table are solved for by Newton's method with a finite-difference Jacobian (everything else fixed
beforehand): ``pt_stage_mass_kg`` (mainly the first critical speed, the overhung power turbine on bearing #0) and
``mount_k``, the stiffness of each engine-mount link (mainly the second, a casing-on-mounts mode with the gas
generator and the power turbine whirling with it). Run ``python -m rotorcosim.components.rotor.calibration [FILE]``: it
prints the knob values to write into the data file (the file is not rewritten, so its comments stay the record).

``--layout-search`` reruns the search that fixed the layout before the fit (data file, [calibration]): for each
combination of bearing-frame strut stiffness (x1, x3), mount planes and PT tube inside the gas generator, the two
knobs are fitted, then the linear 2850 N response at 16 000 rev/min at bearings #0/#5 is printed (the paper has
about 0.2 mm at #0 and less than 0.01 mm at #5) with the distance of the nearest forward critical speed to the
running speed. Slow (minutes): a design study, not a test.
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
        print(f"  {dict(zip(KNOBS, x.round(4).tolist()))} -> {f.round(1)} rev/min", flush=True)
        if np.max(np.abs(f - target)) < tol_rpm:
            break
        J = np.empty((2, 2))
        for j in range(2):
            dx = x.copy()
            dx[j] *= 1.01
            J[:, j] = (forward_criticals(data, dx) - f) / (dx[j] - x[j])
        x = x - np.linalg.solve(J, f - target)
    return x, f


def linear_response(data: dict, rpm: float = 16000.0, F_u: float = 2850.0) -> tuple[float, float]:
    """Steady whirl amplitude (mm, major semi-axis bound |a_f| + |a_b|) at bearings #0/#5 for F_u at the
    blade-loss node, bearings #0/#5 linearised, undamped modes not assumed (direct harmonic solve)."""
    m = model.build(data)
    Ks, Cs = m.linear_support()
    W = rpm * model.RPM
    A = m.K + Ks - W ** 2 * m.M + 1j * W * (m.C + Cs + W * m.G_pt + W * critical.speed_ratio(m) * m.G_gg)
    f = np.zeros(m.n, complex)
    ux, uy = m.ports["unbalance"]
    f[ux], f[uy] = F_u, -1j * F_u
    X = np.linalg.solve(A, f)

    def amp(i):
        return 1e3 * (abs(X[i[0]] + 1j * X[i[1]]) + abs(X[i[0]] - 1j * X[i[1]])) / 2

    return amp(m.ports["brg0"]), amp(m.ports["brg5"])


def layout_search(data: dict) -> list[dict]:
    import itertools

    rows = []
    for strut, mounts, tube in itertools.product((1.0, 3.0), ((1, 4), (1, 6), (0, 6)), ((50, 30), (60, 44))):
        d = copy.deepcopy(data)
        base_struts = {"k_r": 5.0e7, "k_t": 1.0e7, "k_a": 1.0e7}      # the first layout's struts
        d["casing"]["struts"] = {k: v * strut for k, v in base_struts.items()}
        rings = sorted({mt["ring"] for mt in data["casing"]["mounts"]})
        for mt in d["casing"]["mounts"]:
            mt["ring"] = mounts[0] if mt["ring"] == rings[0] else mounts[1]
        p = d["power_turbine"]
        for e in range(5, 16):
            p["d_out_mm"][e], p["d_in_mm"][e] = tube
        try:
            x, f = calibrate(d, tol_rpm=30.0, max_iter=8)
        except (np.linalg.LinAlgError, ValueError) as exc:
            print(f"strut x{strut}, mounts {mounts}, tube {tube}: fit failed ({exc})")
            continue
        d["calibration"].update(dict(zip(KNOBS, x)))
        fw = critical.synchronous_critical_speeds(model.build(d), n=5)["forward_synchronous_rpm"]
        r0, r5 = linear_response(d)
        row = {"strut": strut, "mounts": mounts, "tube": tube, "knobs": x.round(4).tolist(),
               "forward_rpm": [round(v) for v in fw], "x0_mm": round(float(r0), 4), "x5_mm": round(float(r5), 4),
               "nearest_to_16000": round(float(min(abs(v / 16000 - 1) for v in fw)), 3)}
        print(row, flush=True)
        rows.append(row)
    return rows


if __name__ == "__main__":
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    d, _ = model.load_data(args[0] if args else None)
    if "--layout-search" in sys.argv:
        layout_search(d)
        sys.exit(0)
    x, f = calibrate(d)
    for k, v in zip(KNOBS, x):
        print(f"{k} = {v:.4f}")
    print("forward synchronous critical speeds:", f.round(1))
    r0, r5 = linear_response(d)
    print(f"linear 2850 N response at 16 000 rev/min: {r0:.4f} mm at #0, {r5:.4f} mm at #5")
