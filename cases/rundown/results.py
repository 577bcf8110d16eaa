"""The results of a rundown: ``speeds``, ``crossings`` and ``energy`` of ``summary.json``.

The scenario's ``[results]`` (kind ``"rundown"``) names ``spools`` (the spool components, components/spool; the
first is the one whose crossings are reported) and ``critical_speeds_rpm`` (the forward synchronous critical
speeds of the linear rotor, e.g. from ``rotorcosim critical-speeds``). The locations read are the engine's
bearings #0 and #5 (``rotor.X_brg{k}`` whirl, ``bearing{k}.Q_max_step`` / ``sigma_max_step`` contact load and
inner-race stress, ``damper{k}.F_journal`` transmitted force: film + centering spring, eq. (23)'s numerator)
when the system has them, else the rotor's ``X_brg0`` port alone (a test rotor's disk: ``"disk"``, whirl only).

* ``speeds``: per spool ``start_rpm``, ``end_rpm``, ``t_fuel_cut_s`` (None: a prescribed profile or no cut),
  ``stopped`` (it ended at 0 rev/min);
* ``crossings``: per critical speed, the resonance peak of the response against speed (:func:`resonance_peaks`
  over the thermo-mechanical samples: the largest whirl at the first location per speed bin of ``SPEED_BIN``,
  the local maxima that stand out by ``PROMINENCE`` of the largest whirl) assigned to it (:func:`assign_peaks`: one
  peak per critical speed, the nearest, at most ``MAX_SHIFT`` away): ``spool``, ``critical_speed_rpm``,
  ``peak_found``, ``t_s`` and ``peak_speed_rpm`` of the peak's largest sample, ``direction`` (``"down"`` /
  ``"up"``), ``speed_range_rpm`` (the peak's width at half its prominence) and per location ``peak_whirl_mm``,
  ``peak_contact_load_N``, ``peak_contact_stress_MPa``, ``peak_transmitted_force_N`` (keys without a signal are
  left out), the maxima over the width of that location's own whirl peak assigned to the critical speed, or over
  the first location's where it has none, and that ``speed_range_rpm``. A critical speed within the run's speeds
  that has no peak gets ``peak_found`` false, a ``note`` and None for the speed, the time and the peaks (not the
  edge of a band around it); one outside the run's speeds and without a peak has no entry;
* ``energy``: per spool its ``inertia_kg_m2``, ``kinetic_energy_lost_J``, the work of each torque
  ``work_J`` (drive, drag, rub, aero: the spool's own bookkeeping, components/spool/kernel.py) and
  ``residual_pct``: (kinetic energy lost - (drag + rub + aero - drive)) / kinetic energy lost, in percent.

The response is kept as maxima over bins of ``BIN_S`` of thermo-mechanical time (``RundownTrack``).
"""
from __future__ import annotations

import importlib
import math
from typing import NamedTuple

import numpy as np
from scipy.optimize import linear_sum_assignment
from scipy.signal import find_peaks, peak_widths

from rotorcosim.components.contract import COUPLED
from rotorcosim.master.observer.observers import Observer

#: time bins of the response track [s]: many per crossing (a crossing lasts ~0.1-1 s), few per hour of run
BIN_S = 2e-3
RPM = 30.0 / math.pi
#: the resonance search: relative width of its speed bins (the response's maximum per bin, at least a turn of the
#: rotor per bin at a rundown's rates), the prominence of a peak relative to the largest response (ripple of the
#: per-bin maximum and contact noise stay below it), the largest distance of a damped peak from its undamped
#: critical speed (the squeeze-film dampers put the engine's 7-12 % above: docs/explanation/rundown.md)
SPEED_BIN = 2e-3
PROMINENCE = 0.01
MAX_SHIFT = 0.25
#: the module that draws the figures (imported by name)
FIGURES_MODULE = "rotorcosim.cases.rundown.figures"


def _locations(components) -> dict[str, dict[str, str]]:
    """Per co-simulated bearing (every component bearing<ID> with its damper<ID>, in the system's order) the ports
    read; else the rotor's first bearing port alone (a test rotor's disk)."""
    ids = [n[len("bearing"):] for n in components if n.startswith("bearing") and f"damper{n[len('bearing'):]}" in
           components]
    if ids:
        out = {}
        for k in ids:
            b = components[f"bearing{k}"]
            q = "Q_max_step" if "Q_max_step" in b.y else "Q_max"
            s = "sigma_max_step" if "sigma_max_step" in b.y else "sigma_max"
            out[str(k)] = {"whirl": f"rotor.X_brg{k}", "load": f"bearing{k}.{q}", "stress": f"bearing{k}.{s}",
                           "force": f"damper{k}.F_journal"}
        return out
    return {"disk": {"whirl": "rotor.X_brg0"}}


class RundownTrack(Observer):
    """Per bin of BIN_S of thermo-mechanical time: its end time, each spool's speed, and per location the largest
    whirl radius, contact load, inner-race stress and transmitted force."""

    def __init__(self, spools):
        self.spools = list(spools)
        self.rows: list[np.ndarray] = []
        self.start_energy: dict[str, list[float]] = {}

    def start(self, sim, schedule):
        self.locations = _locations(sim.system.components)
        self.cols = [(loc, kind, ref) for loc, d in self.locations.items() for kind, ref in d.items()]
        for sp in self.spools:
            self.start_energy[sp] = [float(x) for x in sim.value(f"{sp}.energy")]
            self.start_energy[sp].append(float(sim.value(f"{sp}.Omega")[0]))

    def interval_start(self, sim, phase, step):
        self.active = phase == COUPLED

    def block_signals(self, sim):
        return [f"{sp}.Omega" for sp in self.spools] + [ref for _, _, ref in self.cols]

    def step_block(self, sim, ks, ts, data):
        if not self.active or not len(ts):
            return
        bins = np.floor(np.asarray(ts) / BIN_S).astype(np.int64)
        edges = np.flatnonzero(np.diff(bins)) + 1
        starts = np.concatenate([[0], edges])
        ends = np.concatenate([edges, [len(ts)]])
        cols = [np.asarray(ts)[ends - 1]]
        cols += [np.asarray(data[f"{sp}.Omega"])[ends - 1, 0] for sp in self.spools]
        for _, kind, ref in self.cols:
            v = np.asarray(data[ref])
            if kind in ("whirl", "force"):
                v = np.hypot(v[:, 0], v[:, 1])
            else:
                v = v[:, 0]                     # load: inner race of [inner, outer]; stress: the inner race
            cols.append(np.maximum.reduceat(v, starts))
        self.rows.append(np.column_stack(cols))

    def step(self, sim, t):
        if not getattr(self, "active", False):
            return
        row = [t] + [float(sim.value(f"{sp}.Omega")[0]) for sp in self.spools]
        for _, kind, ref in self.cols:
            v = np.asarray(sim.value(ref))
            row.append(float(np.hypot(v[0], v[1])) if kind in ("whirl", "force") else float(v[0]))
        self.rows.append(np.array([row]))

    def table(self) -> np.ndarray:
        """All bins: columns t, the spools' speeds [rad/s], then per location its (whirl, load, stress, force)."""
        n = 1 + len(self.spools) + len(self.cols)
        if not self.rows:
            return np.zeros((0, n))
        a = np.vstack(self.rows)
        # the step() path gives one row per step: fold it into bins like step_block's
        b = np.floor(a[:, 0] / BIN_S).astype(np.int64)
        if len(np.unique(b)) == len(b):
            return a
        starts = np.concatenate([[0], np.flatnonzero(np.diff(b)) + 1])
        ends = np.concatenate([starts[1:], [len(b)]])
        out = np.maximum.reduceat(a, starts)
        out[:, :1 + len(self.spools)] = a[ends - 1, :1 + len(self.spools)]
        return out


def _spools(sc) -> list[str]:
    r = sc.extra.get("results", {})
    spools = r.get("spools") or [n for n, c in sc.components.items() if c.implementation == "spool.speed"]
    return list(spools)


def _case_blade_loss(sc) -> bool:
    return all(f"bearing{k}" in sc.components for k in (0, 5))


def observers(sc, cycle):
    obs = [RundownTrack(_spools(sc))]
    if _case_blade_loss(sc):
        from rotorcosim.cases.blade_loss import results as bl
        obs += bl.observers(sc, cycle)
    return obs


def check(sc, sim) -> None:
    spools = _spools(sc)
    if not spools:
        raise ValueError(f"scenario {sc.name!r}: [results] kind = 'rundown' needs a spool component (spool.speed)")
    for sp in spools:
        if sp not in sim.system.components:
            raise ValueError(f"[results] spools: no component {sp!r}")


class Peak(NamedTuple):
    """A resonance peak of a response against speed: the sample where it is largest (its index into the samples
    given, its speed and amplitude) and the speeds of its width at half its prominence."""
    index: int
    speed: float
    amplitude: float
    lo: float
    hi: float


def resonance_peaks(speed, amplitude, bin_rel: float = SPEED_BIN, prominence: float = PROMINENCE) -> list[Peak]:
    """The resonance peaks of ``amplitude`` against ``speed`` (any unit, any order: a rundown, a run-up or both),
    lowest speed first.

    The samples at speeds > 0 are put into bins of relative width ``bin_rel`` (geometric: bin k holds
    (1 + bin_rel)^k <= speed < (1 + bin_rel)^(k+1)), each bin keeping its largest sample; a peak is a local maximum
    of the bins' maxima, in speed order over the bins that have samples, whose prominence (scipy.signal.find_peaks:
    its height above the higher of the lowest points between it and a higher bin on either side) is at least
    ``prominence`` times the largest amplitude. The first and last bin are never peaks: a response that still
    rises at the edge of the speeds run through has not peaked there."""
    w = np.asarray(speed, dtype=float).ravel()
    a = np.asarray(amplitude, dtype=float).ravel()
    if w.shape != a.shape:
        raise ValueError(f"speed and amplitude differ in length ({len(w)} and {len(a)})")
    idx = np.flatnonzero((w > 0.0) & np.isfinite(w) & np.isfinite(a))
    if len(idx) < 3:
        return []
    b = np.floor(np.log(w[idx]) / math.log1p(bin_rel)).astype(np.int64)
    # per bin: its largest sample (ties: the first in the input's order)
    order = np.lexsort((-a[idx], b))
    b, idx = b[order], idx[order]
    first = np.concatenate([[True], np.diff(b) != 0])
    best = idx[first]
    y = a[best]
    top = float(y.max())
    if not top > 0.0:
        return []
    pk, props = find_peaks(y, prominence=prominence * top)
    if not len(pk):
        return []
    _, _, left, right = peak_widths(y, pk, rel_height=0.5, prominence_data=(props["prominences"],
                                                                           props["left_bases"],
                                                                           props["right_bases"]))
    ws = w[best]
    grid = np.arange(len(ws))
    return [Peak(int(best[j]), float(ws[j]), float(y[j]), float(np.interp(lo, grid, ws)),
                 float(np.interp(hi, grid, ws))) for j, lo, hi in zip(pk, left, right)]


def assign_peaks(criticals, peaks: list[Peak], max_shift: float = MAX_SHIFT) -> list[Peak | None]:
    """Each critical speed's resonance peak (None: none), one peak per critical speed and one critical speed per
    peak, the nearest in |ln(peak / critical)| and at most ``max_shift`` (relative) away; where peaks compete
    the assignment with the most pairs, then the least total distance (scipy.optimize.linear_sum_assignment).

    The nearest peak of each critical speed on its own is not enough: the engine's damped peaks at bearing #0 lie
    at 9 100 and 11 400 rev/min, its critical speeds at 8 500 and 10 200, and 9 100 is the nearer of the two to
    10 200 as well."""
    crit = [float(c) for c in criticals]
    out: list[Peak | None] = [None] * len(crit)
    if not crit or not peaks:
        return out
    lim = math.log1p(max_shift)
    d = np.abs(np.log(np.array([p.speed for p in peaks])[None, :] / np.array(crit)[:, None]))
    # a pair beyond the limit costs more than any set of allowed pairs: the most pairs within it win
    cost = np.where(d <= lim, d, lim * (len(crit) + len(peaks) + 1))
    for i, j in zip(*linear_sum_assignment(cost)):
        if d[i, j] <= lim:
            out[i] = peaks[j]
    return out


def crossings(table: np.ndarray, spool: str, criticals_rpm, locations: dict, n_spools: int) -> list[dict]:
    """The crossings of the first spool's speed through each critical speed (module docstring): the resonance
    peaks of the whirl at the first location over the rows of ``table`` (RundownTrack.table); each location's
    values over its own whirl's peak for that critical speed, or over the first location's peak where it has none
    (its ``speed_range_rpm`` says which)."""
    out = []
    if not len(table):
        return out
    crit = sorted(float(c) for c in criticals_rpm)
    w = table[:, 1] * RPM
    names = {"whirl": ("peak_whirl_mm", 1e3), "load": ("peak_contact_load_N", 1.0),
             "stress": ("peak_contact_stress_MPa", 1e-6), "force": ("peak_transmitted_force_N", 1.0)}
    cols, col = {}, 1 + n_spools
    for loc, d in locations.items():
        cols[loc] = col                     # its whirl first, then the other kinds in d's order
        col += len(d)
    own = {loc: assign_peaks(crit, resonance_peaks(w, table[:, c])) for loc, c in cols.items()}
    first = next(iter(locations))
    running = w[w > 0.0]
    w_lo, w_hi = (float(running.min()), float(running.max())) if len(running) else (math.nan, math.nan)
    dw = np.gradient(w) if len(w) > 1 else np.zeros(len(w))
    for i, c in enumerate(crit):
        pk = own[first][i]
        if pk is None and not w_lo <= c <= w_hi:
            continue                        # never reached
        entry = {"spool": spool, "critical_speed_rpm": c, "peak_found": pk is not None}
        if pk is None:
            entry.update(t_s=None, peak_speed_rpm=None, direction=None, speed_range_rpm=None,
                         note=f"no resonance peak of the whirl at {first} within {MAX_SHIFT:.0%} of this critical "
                              f"speed (the whirl against speed has no local maximum standing out by "
                              f"{PROMINENCE:.0%} of its largest value there)")
            entry["bearings"] = {loc: {names[kind][0]: None for kind in d} for loc, d in locations.items()}
            out.append(entry)
            continue
        j = pk.index
        entry.update(t_s=float(table[j, 0]), peak_speed_rpm=float(w[j]), direction="up" if dw[j] > 0 else "down",
                     speed_range_rpm=[pk.lo, pk.hi])
        entry["bearings"] = {}
        for loc, d in locations.items():
            p = own[loc][i] or pk
            sel = np.flatnonzero((w >= p.lo) & (w <= p.hi))
            r = {names[kind][0]: float(table[sel, cols[loc] + k].max()) * names[kind][1] for k, kind in enumerate(d)}
            r["speed_range_rpm"] = [p.lo, p.hi]
            entry["bearings"][loc] = r
        out.append(entry)
    return out


def extract(sc, sim, obs, report) -> dict:
    track = obs[0]
    table = track.table()
    comps = sim.system.components
    speeds, energy = {}, {}
    for i, sp in enumerate(track.spools):
        c = comps[sp]
        cut = c.p.get("t_fuel_cut", -1.0)
        speeds[sp] = {"inertia_kgm2": float(c.J), "start_rpm": track.start_energy[sp][5] * RPM,
                      "end_rpm": float(c.y["Omega"][0]) * RPM,
                      "t_fuel_cut_s": float(cut) if c.p.get("profile") == "torque" and cut >= 0.0 else None,
                      # a stopped spool is a legal end state (friction, or a profile to 0 rev/min)
                      "stopped": float(c.y["Omega"][0]) == 0.0}
        e0, e1 = track.start_energy[sp][:5], [float(x) for x in c.y["energy"]]
        lost = e0[0] - e1[0]
        work = {k: e1[n] - e0[n] for n, k in enumerate(("drive", "drag", "rub", "aero"), start=1)}
        balance = work["drag"] + work["rub"] + work["aero"] - work["drive"]
        energy[sp] = {"inertia_kg_m2": float(c.J), "kinetic_energy_lost_J": lost, "work_J": work,
                      "residual_pct": 100.0 * (lost - balance) / lost if lost else 0.0}
    crit = sc.extra.get("results", {}).get("critical_speeds_rpm", [])
    out = {"speeds": speeds, "energy": energy,
           "crossings": crossings(table, track.spools[0], crit, track.locations, len(track.spools))
           if track.spools else []}
    if _case_blade_loss(sc):
        from rotorcosim.cases.blade_loss import results as bl
        out.update(bl.extract(sc, sim, obs[1:], report))
    return out


def result_paths(sc) -> list[str]:
    """The results :func:`extract` reports for scenario ``sc``, as dotted paths into summary.json (``crossings.``
    ending in a dot: any path below it, the crossings found being known only after the run)."""
    out = []
    for sp in _spools(sc):
        out += [f"speeds.{sp}.{k}" for k in ("start_rpm", "end_rpm", "t_fuel_cut_s", "stopped",
                                                             "inertia_kgm2")]
        out += [f"energy.{sp}.{k}" for k in ("inertia_kg_m2", "kinetic_energy_lost_J", "residual_pct")]
        out += [f"energy.{sp}.work_J.{k}" for k in ("drive", "drag", "rub", "aero")]
    out.append("crossings.")
    if _case_blade_loss(sc):
        from rotorcosim.cases.blade_loss import results as bl
        out += bl.result_paths(sc)
    return out


def figures(sc, data, out, pool=None, dpi: int | None = None) -> list[str]:
    """The rundown figures (:mod:`rotorcosim.cases.rundown.figures`) from the run's series, drawn here at ``dpi``
    (None: the default)."""
    return importlib.import_module(FIGURES_MODULE).figures(sc, data, out, dpi=dpi)
