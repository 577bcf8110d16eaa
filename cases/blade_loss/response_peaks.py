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

A rundown asks for the damped critical speeds at each set of film temperatures its peaks had (cases/rundown/
modes.py), and for one peak at a time (:meth:`DampedPeaks.nearest`, which refines only the grid peaks that can be
the nearest). The films' temperatures change only their damping ``c_film``, a few entries of C between each
journal and its hub (:meth:`~rotorcosim.components.rotor.model.FullModel.coupled`), so :class:`FilmScan` solves
the grid once per speed for the engine at one set of films, A_0 x_0 = f and A_0 Y = P (P: the columns of those
DOFs D), and takes any other set as the low-rank update A = A_0 + P (i Omega dC_DD) P^T (Woodbury):

    x = x_0 - Y (I + i Omega dC_DD Y_D)^-1 i Omega dC_DD x_0,D,

a solve of the size of D per speed. Those grid responses equal the direct solve's to rounding; they only locate
the peaks, which are refined on the direct solve.
"""
from __future__ import annotations

import hashlib
import math

import numpy as np

from rotorcosim.cases.blade_loss import linear_engine
from rotorcosim.components.rotor import calibration
from rotorcosim.components.rotor.model import RPM

#: relative spacing of the speed grid: the damped peaks of the paper's engine are ~10 % wide at half height, so a
#: 1.5 % grid has several points on each; the refinement then locates the peak to ``XTOL_RPM``
STEP = 0.015
XTOL_RPM = 0.5
#: a local maximum counts as a peak when it stands out of its surroundings by this fraction of the largest
#: response in the range (below, grid ripples and shoulders of a neighbouring peak)
PROMINENCE = 0.01


def speed_grid(min_rpm: float, max_rpm: float) -> np.ndarray:
    """The geometric grid [rev/min] of the search from ``min_rpm`` to ``max_rpm``, ``STEP`` apart."""
    if not 0.0 < min_rpm < max_rpm:
        raise ValueError(f"damped critical speeds: need 0 < min_rpm < max_rpm, got {min_rpm:g} and {max_rpm:g}")
    n = max(int(np.ceil(np.log(max_rpm / min_rpm) / np.log1p(STEP))) + 1, 3)
    return np.geomspace(min_rpm, max_rpm, n)


class Whirl:
    """``whirl(rpm)``: per bearing id the whirl [mm] of the linear engine on supports ``sup`` under the unbalance
    growing with the square of the speed (direct solve), each speed solved once. The engine's matrices are built
    when a solve needs them and :meth:`release` frees them (a rundown keeps its searches for the process)."""

    def __init__(self, full, sup: dict, ref_rpm: float):
        self.full, self.sup, self.ref_rpm = full, sup, ref_rpm
        self._system = None
        self._seen: dict[float, dict[str, float]] = {}

    def __call__(self, rpm: float) -> dict[str, float]:
        out = self._seen.get(rpm)
        if out is None:
            if self._system is None:
                self._system = self.full.coupled(self.sup)
            r = linear_engine.response(self.full, self.sup, (rpm / self.ref_rpm) ** 2, rpm, self._system)
            out = self._seen[rpm] = {b: float(v["whirl_mm"]) for b, v in r.items()}
        return out

    def release(self) -> None:
        """Free the engine's matrices (built again by the next new speed)."""
        self._system = None


class DampedPeaks:
    """The damped critical speeds per bearing id of one set of supports: the peaks of ``table`` (per bearing id
    the whirl over ``grid``), each refined on ``whirl`` (:class:`Whirl`) when first asked for."""

    def __init__(self, grid: np.ndarray, table: dict[str, np.ndarray], whirl):
        # scipy.signal imports scipy.stats (~1 s of CPU): at the first search, not with the module
        from scipy.signal import find_peaks

        self.grid = grid
        self.whirl = whirl
        self.peaks = {}
        for b, amp in table.items():
            idx, _ = find_peaks(amp, prominence=PROMINENCE * float(amp.max()))
            self.peaks[b] = [int(i) for i in idx]
        self._speed: dict[tuple[str, int], float] = {}

    def speed(self, b: str, i: int) -> float:
        """The peak of bearing ``b`` at grid index ``i``, refined between its grid neighbours [rev/min]."""
        key = (b, i)
        if key not in self._speed:
            from scipy.optimize import minimize_scalar

            res = minimize_scalar(lambda w: -self.whirl(w)[b], bounds=(self.grid[i - 1], self.grid[i + 1]),
                                  method="bounded", options={"xatol": XTOL_RPM})
            self._speed[key] = float(res.x)
        return self._speed[key]

    def all(self) -> dict[str, list[float]]:
        """Every damped critical speed, per bearing id, ascending."""
        out = {b: [self.speed(b, i) for i in idx] for b, idx in self.peaks.items()}
        self.whirl.release()
        return out

    def nearest(self, b: str, rpm: float) -> float | None:
        """The damped critical speed of bearing ``b`` nearest to ``rpm`` (in ratio, |log(rpm / d)|; of two as near,
        the lower), None where ``b`` has none. Refines only the peaks that can be the nearest: a refined peak lies
        between its grid neighbours, so a peak whose bracket is farther than the nearest refined one is not."""
        def reach(i):
            lo, hi = self.grid[i - 1], self.grid[i + 1]
            return 0.0 if lo <= rpm <= hi else min(abs(math.log(rpm / lo)), abs(math.log(rpm / hi)))

        best = None
        for k, i in sorted(enumerate(self.peaks.get(b, [])), key=lambda ki: (reach(ki[1]), ki[0])):
            # the slack keeps a peak whose bound ties the best within rounding
            if best is not None and reach(i) > best[0] * (1.0 + 1e-9) + 1e-12:
                break
            d = self.speed(b, i)
            cand = (abs(math.log(rpm / d)), k, d)
            if best is None or cand[:2] < best[:2]:
                best = cand
        self.whirl.release()
        return None if best is None else best[2]


def damped_critical_speeds(full, sup: dict, min_rpm: float, max_rpm: float, ref_rpm: float) -> dict[str, list[float]]:
    """Per co-simulated bearing (the keys of :func:`linear_engine.response`), the speeds [rev/min] between
    ``min_rpm`` and ``max_rpm`` at which the rotor's whirl there peaks under an unbalance growing with the square
    of the speed (its level at ``ref_rpm`` does not matter: the system is linear)."""
    grid = speed_grid(min_rpm, max_rpm)
    whirl = Whirl(full, sup, ref_rpm)
    return DampedPeaks(grid, direct_table(grid, whirl), whirl).all()


def direct_table(grid: np.ndarray, whirl) -> dict[str, np.ndarray]:
    """Per bearing id the whirl [mm] at each speed of ``grid`` [rev/min] from ``whirl`` (:class:`Whirl`)."""
    rows = [whirl(float(w)) for w in grid]
    return {b: np.array([row[b] for row in rows]) for b in rows[0]}


class FilmScan:
    """The linear engine's whirl per bearing id over the speed ``grid`` [rev/min] for any film damping (module
    docstring): the engine on supports ``sup`` solved once per grid speed, another ``c_film`` of its supports a
    low-rank update."""

    def __init__(self, full, sup: dict, grid: np.ndarray, ref_rpm: float):
        self.full, self.grid, self.ref_rpm = full, grid, ref_rpm
        base = full.coupled(sup)
        moved = np.zeros(base["C"].shape[0], bool)
        for h, s in sup.items():
            dC = full.coupled({**sup, h: {**s, "c_film": s["c_film"] + 1.0}})["C"] - base["C"]
            moved |= (dC != 0.0).any(axis=0) | (dC != 0.0).any(axis=1)
        self.D = D = np.flatnonzero(moved)
        self.out = {h[1:]: np.asarray(full.ports[f"brg{h[1:]}"][:2]) for h in sup}
        # x_0 and Y at every grid speed, kept at the whirl's DOFs and D only; by sparse LU (SuperLU): the engine's
        # matrices are a few per cent full, and these solves only locate peaks
        from scipy.sparse import csc_matrix
        from scipy.sparse.linalg import splu

        n = base["C"].shape[0]
        rows = np.concatenate([*self.out.values(), D])
        R = np.zeros((n, 1 + len(D)), complex)
        ux, uy = full.ports["unbalance"]
        R[ux, 0], R[uy, 0] = 1.0, -1j
        R[D, 1 + np.arange(len(D))] = 1.0
        mats = {k: csc_matrix(base[k]) for k in ("K", "M", "C", "G_pt", "G_gg")}
        sol = np.stack([splu(csc_matrix(calibration.harmonic_matrix(full, mats, w * RPM))).solve(R)[rows]
                        for w in grid])
        self._x0, self._Y = sol[:, :, 0], sol[:, :, 1:]
        # what a film-only change leaves as it is (kept as digests: the scan lives as long as the process)
        self._C0 = base["C"]
        self._fixed = _digests(base)

    def table(self, sup: dict) -> dict[str, np.ndarray] | None:
        """Per bearing id the whirl [mm] over the grid on supports ``sup``; None when ``sup`` differs from the
        scan's supports in more than the films' damping (solve it directly then)."""
        s = self.full.coupled(sup)
        if _digests(s) != self._fixed:
            return None
        D = self.D
        dC = s["C"] - self._C0
        dCD = dC[np.ix_(D, D)]
        if np.count_nonzero(dC) != np.count_nonzero(dCD):
            return None
        W = self.grid * RPM
        nd = len(self.out) * 2
        x0D, YD = self._x0[:, nd:], self._Y[:, nd:, :]
        B = 1j * W[:, None, None] * dCD[None, :, :]
        z = np.linalg.solve(np.eye(len(D))[None] + B @ YD, (B @ x0D[:, :, None]))
        x = (self._x0[:, :nd] - (self._Y[:, :nd, :] @ z)[:, :, 0]) * ((self.grid / self.ref_rpm) ** 2)[:, None]
        return {b: 1e3 * calibration.orbit_semi_axis(x[:, 2 * k], x[:, 2 * k + 1])
                for k, b in enumerate(self.out)}


def _digests(system: dict) -> tuple:
    """Digests of the matrices of a linear engine that its films' damping does not enter."""
    return tuple(hashlib.sha256(np.ascontiguousarray(system[k]).tobytes()).digest()
                 for k in ("K", "M", "G_pt", "G_gg"))
