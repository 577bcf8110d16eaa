"""Damped critical speeds: the speeds at which the linear engine's synchronous unbalance response peaks.

The undamped critical speeds (:func:`rotorcosim.components.rotor.critical.synchronous_critical_speeds`) are where
an eigenvalue of the undamped rotor meets the synchronous line. A run, a test stand or a rundown sees something
else: the speed at which the response to the unbalance peaks, which is how API 684 (Tutorial on rotordynamics)
identifies a critical speed in an unbalance response, the *damped* critical speed. With the squeeze film dampers'
damping the two differ by several per cent, and the rundown's crossings are read against these.

The response is the steady synchronous solve of the linear engine (:func:`linear_engine.response`): the unbalance
force ``F_u (Omega / Omega_ref)^2`` rotating at the spool's speed, damping and gyroscopic terms included, per
co-simulated bearing the whirl of the rotor there. Peaks are found on a geometric speed grid (``STEP`` apart) and
each refined by a bounded scalar search (scipy.optimize.minimize_scalar) between its grid neighbours.
"""
from __future__ import annotations

import numpy as np

from rotorcosim.cases.blade_loss import linear_engine

#: relative spacing of the speed grid: the damped peaks of the paper's engine are ~10 % wide at half height, so a
#: 1.5 % grid has several points on each; the refinement then locates the peak to ``XTOL_RPM``
STEP = 0.015
XTOL_RPM = 0.5
#: a local maximum counts as a peak when it stands out of its surroundings by this fraction of the largest
#: response in the range (below, grid ripples and shoulders of a neighbouring peak)
PROMINENCE = 0.01


def damped_critical_speeds(full, sup: dict, min_rpm: float, max_rpm: float, ref_rpm: float) -> dict[str, list[float]]:
    """Per co-simulated bearing (the keys of :func:`linear_engine.response`), the speeds [rev/min] between
    ``min_rpm`` and ``max_rpm`` at which the rotor's whirl there peaks under an unbalance growing with the square
    of the speed (its level at ``ref_rpm`` does not matter: the system is linear)."""
    # scipy.signal imports scipy.stats (~1 s of CPU): at the first call, not with the module
    from scipy.optimize import minimize_scalar
    from scipy.signal import find_peaks

    if not 0.0 < min_rpm < max_rpm:
        raise ValueError(f"damped critical speeds: need 0 < min_rpm < max_rpm, got {min_rpm:g} and {max_rpm:g}")
    n = max(int(np.ceil(np.log(max_rpm / min_rpm) / np.log1p(STEP))) + 1, 3)
    grid = np.geomspace(min_rpm, max_rpm, n)

    system = full.coupled(sup)

    def whirl(rpm: float) -> dict[str, float]:
        r = linear_engine.response(full, sup, (rpm / ref_rpm) ** 2, rpm, system)
        return {b: float(v["whirl_mm"]) for b, v in r.items()}

    table = [whirl(float(w)) for w in grid]
    out = {}
    for b in table[0]:
        amp = np.array([row[b] for row in table])
        idx, _ = find_peaks(amp, prominence=PROMINENCE * float(amp.max()))
        peaks = []
        for i in idx:
            res = minimize_scalar(lambda w: -whirl(w)[b], bounds=(grid[i - 1], grid[i + 1]), method="bounded",
                                  options={"xatol": XTOL_RPM})
            peaks.append(float(res.x))
        out[b] = peaks
    return out
