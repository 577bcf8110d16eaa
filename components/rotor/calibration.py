"""Calibration of the model geometry to the paper's two lowest forward synchronous critical speeds.

The paper (section 4.1) gives 8500 and 10 200 rev/min but not the geometry. Two knobs of data/engine.toml's
[calibration] table are solved for by Newton's method with a finite-difference Jacobian (everything else fixed
beforehand): ``pt_stage_mass_kg`` (mainly the first critical speed, the overhung power turbine on bearing #0) and
``mount_k``, the stiffness of each engine-mount link (mainly the second, a casing-on-mounts mode with the gas
generator and the power turbine whirling with it), on the engine with bearings #0/#5 as the co-simulated system
linearised (``sup``, :meth:`model.FullModel.coupled`). Run ``python -m rotorcosim.cases.blade_loss.linear_engine [FILE]``
(the system's linearisation lives in the master: it takes the bearing and damper components, which this package,
bundled alone into the rotor's FMU, may not import): it prints the knob values to write into the data file (the
file is not rewritten, so its comments stay the record). ``--layout-search`` / ``--response-study`` there rerun
the studies below.

``--layout-search`` reruns the search that fixed the layout before the fit (data file, [calibration]): for each
combination of bearing-frame strut stiffness (x1, x3), mount planes and PT tube inside the gas generator, the two
knobs are fitted, then the linear 2850 N response at 16 000 rev/min at bearings #0/#5 is printed (the paper has
about 0.2 mm at #0 and less than 0.01 mm at #5) with the distance of the nearest forward critical speed to the
running speed. Slow (minutes): a design study, not a test.

``--response-study`` reruns the later study that calibrated the layout on the paper's 2850 N response (data file,
[calibration], item 2): from the shipped layout, the span between bearing #0 and the forward intermediate bearing
(everything aft of it moved with it), the PT tube and the neck between bearing #0 and the forward intermediate
bearing are varied, each variant refitted to the critical speeds, and the linear response at #0/#5 (whirl,
relative to the housing, transmissibility |F_spring + F_film| / F_u) printed (:func:`linear_response_detail`).
"""
from __future__ import annotations

import copy

import numpy as np

from . import critical, model

KNOBS = ("pt_stage_mass_kg", "mount_k")


def _supports(sup):
    if sup is None:
        raise ValueError("the #0/#5 supports of the linear engine are needed (rotorcosim.cases.blade_loss.linear_engine.supports)")
    return sup


def forward_criticals(data: dict, values=None, n: int = 2, sup: dict | None = None) -> np.ndarray:
    d = copy.deepcopy(data)
    if values is not None:
        d["calibration"].update({k: float(v) for k, v in zip(KNOBS, values)})
    fw = critical.synchronous_critical_speeds(model.build(d), _supports(sup), n=n)["forward_synchronous_rpm"]
    return np.asarray(fw[:n])


def calibrate(data: dict, tol_rpm: float = 1.0, max_iter: int = 10, sup: dict | None = None):
    """Newton on the two knobs until the lowest two forward critical speeds of the linear engine (supports
    ``sup``, default the co-simulated system linearised) meet [calibration] target_rpm within tol_rpm."""
    sup = _supports(sup)
    target = np.asarray(data["calibration"]["target_rpm"], float)
    x = np.array([float(data["calibration"][k]) for k in KNOBS])
    for _ in range(max_iter):
        f = forward_criticals(data, x, sup=sup)
        print(f"  {dict(zip(KNOBS, x.round(4).tolist()))} -> {f.round(1)} rev/min", flush=True)
        if np.max(np.abs(f - target)) < tol_rpm:
            break
        J = np.empty((2, 2))
        for j in range(2):
            dx = x.copy()
            dx[j] *= 1.01
            J[:, j] = (forward_criticals(data, dx, sup=sup) - f) / (dx[j] - x[j])
        x = x - np.linalg.solve(J, f - target)
    return x, f


def harmonic_matrix(full: model.FullModel, system: dict, W: float) -> np.ndarray:
    """The dynamic stiffness of the linear engine ``system`` (:meth:`model.FullModel.coupled`) for a synchronous
    response at the power turbine's speed ``W`` [rad/s], the gas generator at its ratio r of it:
    A = K - W^2 M + i W (C + W G_pt + W r G_gg), so that A X = F for X, F rotating as exp(i W t)."""
    s = system
    r = full.omega_gg / full.omega_pt
    return s["K"] - W ** 2 * s["M"] + 1j * W * (s["C"] + W * s["G_pt"] + W * r * s["G_gg"])


def orbit_semi_axis(x, y):
    """The major semi-axis |a_f| + |a_b| of the elliptic orbit whose x and y move as Re(x exp(i W t)) and
    Re(y exp(i W t)) (complex amplitudes ``x``, ``y``; numbers or arrays): the orbit is a forward circle of radius
    |a_f| = |x + i y| / 2 plus a backward one of |a_b| = |x - i y| / 2."""
    return (abs(x + 1j * y) + abs(x - 1j * y)) / 2.0


def coupled_response(full: model.FullModel, sup: dict, F_u: float, rpm: float | None = None,
                     system: dict | None = None) -> dict:
    """Steady synchronous response of the linear engine (supports ``sup``, :meth:`model.FullModel.coupled`) to F_u
    rotating at the PT speed at the blade-loss node (direct harmonic solve, damping and gyroscopic terms
    included). Per bearing "0"/"5": ``whirl_mm`` (major semi-axis |a_f| + |a_b| of the PT node's orbit),
    ``journal_mm`` (orbit of the journal relative to the hub) and ``transmissibility`` |F_spring + F_film| / F_u
    (eq. 23) of the linear support. ``system``: ``full.coupled(sup)`` when the caller has it (a speed scan)."""
    W = full.omega_pt if rpm is None else rpm * model.RPM
    s = full.coupled(sup) if system is None else system
    A = harmonic_matrix(full, s, W)
    f = np.zeros(A.shape[0], complex)
    ux, uy = full.ports["unbalance"]
    f[ux], f[uy] = F_u, -1j * F_u
    X = np.linalg.solve(A, f)
    amp = orbit_semi_axis
    out = {}
    for key, sp in sup.items():
        i, j = full.ports[f"brg{key[1:]}"][:2]
        hi, hj = full.ports[f"housing{key[1:]}"]
        jx, jy = s["journal"][key]
        rx, ry = X[jx] - X[hi], X[jy] - X[hj]
        z = sp["k_spring"] + 1j * W * sp["c_film"]
        out[key[1:]] = {"whirl_mm": 1e3 * amp(X[i], X[j]), "journal_mm": 1e3 * amp(rx, ry),
                        "transmissibility": amp(z * rx, z * ry) / F_u if F_u > 0 else float("nan")}
    return out


def linear_response_detail(data: dict, rpm: float = 16000.0, F_u: float = 2850.0, sup: dict | None = None) -> dict:
    """:func:`coupled_response` of the model built from ``data``."""
    return coupled_response(model.build(data), _supports(sup), F_u, rpm)


def linear_response(data: dict, rpm: float = 16000.0, F_u: float = 2850.0, sup: dict | None = None):
    r = linear_response_detail(data, rpm, F_u, sup)
    return r["0"]["whirl_mm"], r["5"]["whirl_mm"]


def response_study(data: dict, sup: dict) -> list[dict]:
    """The 2850 N response study behind the shipped layout (module docstring, ``--response-study``)."""
    pt = data["spool"]["pt"]
    i0, i5 = int(data["attach"]["bearing0"]["node"][1]), 5                   # bearing #0 node, forward intermediate bearing node
    z0 = float(pt["z_mm"][i0])
    span0 = float(pt["z_mm"][i5]) - z0

    def variant(span, tube, neck):
        d = copy.deepcopy(data)
        D = span - span0
        p, g, cas = d["spool"]["pt"], d["spool"]["gg"], d["casing"]
        p["z_mm"] = [z for z in p["z_mm"][:i0 + 1]] + [z0 + span / 2, z0 + span] + [z + D for z in p["z_mm"][i5 + 1:]]
        g["z_mm"] = [z + D for z in g["z_mm"]]
        cas["ring_z_mm"] = [z if z <= z0 else z + D for z in cas["ring_z_mm"]]
        for hv in cas["hubs"].values():
            if hv["z_mm"] > z0:
                hv["z_mm"] += D
        for e in range(i5, 16):
            p["d_out_mm"][e], p["d_in_mm"][e] = tube
        p["d_out_mm"][i0 + 1] = neck
        return d

    tube0 = (pt["d_out_mm"][i5], pt["d_in_mm"][i5])
    neck0 = pt["d_out_mm"][i0 + 1]
    rows = []
    cases = [(s, tube0, neck0) for s in (160.0, 250.0, 300.0, 350.0, 400.0)]
    cases += [(span0, t, neck0) for t in ((60, 44), (70, 54))] + [(span0, tube0, n) for n in (60.0, 50.8, 40.0)]
    for span, tube, neck in cases:
        d = variant(span, tube, neck)
        try:
            x, f = calibrate(d, tol_rpm=10.0, max_iter=10, sup=sup)
        except (np.linalg.LinAlgError, ValueError) as exc:
            print(f"span {span} mm, tube {tube}, neck {neck}: fit failed ({exc})")
            continue
        d["calibration"].update(dict(zip(KNOBS, x)))
        r = linear_response_detail(d, sup=sup)
        row = {"span_mm": span, "tube": tube, "neck_mm": neck, "knobs": x.round(4).tolist(),
               "forward_rpm": [round(v) for v in f],
               **{f"{k}_{b}": round(float(v), 4) for b in r for k, v in r[b].items()}}
        print(row, flush=True)
        rows.append(row)
    return rows


def layout_search(data: dict, sup: dict) -> list[dict]:
    import itertools

    rows = []
    for strut, mounts, tube in itertools.product((1.0, 3.0), ((1, 4), (1, 6), (0, 6)), ((50, 30), (60, 44))):
        d = copy.deepcopy(data)
        base_struts = {"k_r": 5.0e7, "k_t": 1.0e7, "k_a": 1.0e7}      # the first layout's struts
        d["casing"]["struts"] = {k: v * strut for k, v in base_struts.items()}
        rings = sorted({mt["ring"] for mt in data["casing"]["mounts"]})
        for mt in d["casing"]["mounts"]:
            mt["ring"] = mounts[0] if mt["ring"] == rings[0] else mounts[1]
        p = d["spool"]["pt"]
        for e in range(5, 16):
            p["d_out_mm"][e], p["d_in_mm"][e] = tube
        try:
            x, f = calibrate(d, tol_rpm=30.0, max_iter=8, sup=sup)
        except (np.linalg.LinAlgError, ValueError) as exc:
            print(f"strut x{strut}, mounts {mounts}, tube {tube}: fit failed ({exc})")
            continue
        d["calibration"].update(dict(zip(KNOBS, x)))
        fw = critical.synchronous_critical_speeds(model.build(d), sup, n=5)["forward_synchronous_rpm"]
        r0, r5 = linear_response(d, sup=sup)
        row = {"strut": strut, "mounts": mounts, "tube": tube, "knobs": x.round(4).tolist(),
               "forward_rpm": [round(v) for v in fw], "x0_mm": round(float(r0), 4), "x5_mm": round(float(r5), 4),
               "nearest_to_16000": round(float(min(abs(v / 16000 - 1) for v in fw)), 3)}
        print(row, flush=True)
        rows.append(row)
    return rows
