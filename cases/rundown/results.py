"""The results of a rundown: ``speeds``, ``crossings`` and ``energy`` of ``summary.json``.

The scenario's ``[results]`` (kind ``"rundown"``) names ``spools`` (the spool components, components/spool). The
crossings are those of the spool that turns the unbalance (the one driving ``rotor.Omega_pt``; else the first).
The locations read are the engine's co-simulated bearings, every id of the rotor's ``X_brg<ID>`` ports with a
``bearing<ID>`` component (``rotor.X_brg<ID>`` whirl, ``bearing<ID>.Q_max_step`` / ``sigma_max_step`` contact
load and inner-race stress, ``damper<ID>.F_journal`` transmitted force: film + centering spring, eq. (23)'s
numerator, and the film temperature the damper is fed), else the rotor's ``X_brg0`` port alone (a test rotor's
disk: ``"disk"``, whirl only).

* ``speeds``: per spool ``inertia_kgm2``, ``start_rpm``, ``end_rpm``, ``t_fuel_cut_s`` (None: a prescribed profile or no cut),
  ``stopped`` (it ended at 0 rev/min);
* ``crossings``: every resonance peak of the whirl against speed at any location (:func:`resonance_peaks` over the
  thermo-mechanical samples: the largest whirl per speed bin of ``SPEED_BIN``, the local maxima standing out by
  ``PROMINENCE`` of that location's largest whirl), labelled with the nearest critical speed of the linearised
  engine (:mod:`.modes`: the engine's damped critical speeds at that location at the film temperatures the run had
  at the peak, each the response peak of one mode; a test rotor: the scenario's ``critical_speeds_rpm``). No band
  around a critical speed decides whether a peak exists. One entry per mode, lowest first: ``spool`` (and
  ``spool_name``, the engine file's name of the spool it turns, cases/blade_loss/engine_names.py),
  ``critical_speed_rpm`` (the mode's undamped critical speed), ``damped_critical_speed_rpm`` (its damped one at
  ``film_temperature_C``, per bearing id; None for a test rotor), ``location`` (whose peak it is: the first
  location with a peak of that mode), ``peak_found``, ``t_s`` and ``peak_speed_rpm`` of the peak's largest sample,
  ``direction`` (``"down"`` / ``"up"``), ``speed_range_rpm`` (the peak's width at half its prominence),
  ``other_peaks_rpm`` (smaller peaks at that location labelled to the same mode: the beats after a fast passage),
  and per location ``peak_whirl_mm``, ``peak_contact_load_N``, ``peak_contact_stress_MPa``,
  ``peak_transmitted_force_N`` (keys without a signal are left out): the maxima over the width of that location's
  own peak of the mode, or over the defining peak's where it has none, and that ``speed_range_rpm``. A mode within
  the run's speeds without a peak anywhere gets ``peak_found`` false, a ``note`` and None for the speed, the time
  and the peaks;
* ``energy``: the spools' energy balance from the torques the components report (:mod:`.energy`);
* ``fatigue`` (a scenario that names ``[results] fatigue_loads``): the fatigue content of each load element over
  the run (:mod:`.fatigue`: the settings, per element ``del_N``, ``miner_damage``, ``cycles``).

The response is kept as maxima over bins of ``BIN_S`` of thermo-mechanical time, with the time and the speed of
each bin's largest whirl sample (``RundownTrack``), less the first revolutions of a TM interval that follows a
held one (:func:`restart_revolutions`): there the rotor resumes the orbit it was frozen on, at the speed of the
interval's start, and rings down to the present one; read as the response at the present speed, that transient
put a crossing's peak at the speed of a restart (a broken fuse's 5 581 rev/min crossing, held through: 5 588
against the settled response's top near 5 800 rev/min).
"""
from __future__ import annotations

import importlib
import math
from typing import NamedTuple

import numpy as np
from scipy.signal import find_peaks, peak_widths

from rotorcosim.components.contract import COUPLED, HELD
from rotorcosim.master.manipulator.restart import RESTART_CYCLES
from rotorcosim.master.observer.observer import Observer

from rotorcosim.cases.interface import results as interface

from rotorcosim.master.observer.held_cycles import LoadCycles

from . import fatigue, fuse_comparison
from .energy import SpoolEnergy

#: time bins of the response track [s]: many per crossing (a crossing lasts ~0.1-1 s), few per hour of run
BIN_S = 2e-3
RPM = 30.0 / math.pi
KELVIN = 273.15
#: the resonance search: relative width of its speed bins (the response's maximum per bin, at least a turn of the
#: rotor per bin at a rundown's rates), the prominence of a peak relative to the location's largest response
#: (ripple of the per-bin maximum and contact noise stay below it)
SPEED_BIN = 2e-3
PROMINENCE = 0.01
#: the module that draws the figures (imported by name)
FIGURES_MODULE = "rotorcosim.cases.rundown.figures"
#: the kinds of a location's columns in the track, in order: the whirl's maximum, the time and the crossing spool's
#: speed at that sample, the other maxima, the film temperature at the bin's end
KINDS = ("whirl", "t_at", "w_at", "load", "stress", "force", "film")


def _locations(sim) -> dict[str, dict[str, str]]:
    """Per location (bearing id, or "disk"), kind -> the output read (module docstring)."""
    comps = sim.system.components
    rotor = comps.get("rotor")
    ids = [n[len("X_brg"):] for n in (rotor.y if rotor is not None else ()) if n.startswith("X_brg")]
    ids = [k for k in ids if f"bearing{k}" in comps]
    if not ids:
        return {"disk": {"whirl": "rotor.X_brg0"}}
    by_dst = {c.dst: c.src for c in sim.system.connections}
    out = {}
    for k in ids:
        b = comps[f"bearing{k}"]
        d = {"whirl": f"rotor.X_brg{k}"}
        for kind, names in (("load", ("Q_max_step", "Q_max")), ("stress", ("sigma_max_step", "sigma_max"))):
            port = next((n for n in names if n in b.y), None)
            if port is not None:
                d[kind] = f"bearing{k}.{port}"
        if f"damper{k}" in comps and "F_journal" in comps[f"damper{k}"].y:
            d["force"] = f"damper{k}.F_journal"
        film = by_dst.get(f"damper{k}.T_oil")
        if film is not None:
            d["film"] = film
        out[k] = d
    return out


def _layout(locations) -> list[tuple[str, str, str | None]]:
    """The track's location columns: (location, kind, output read; None for t_at / w_at), in KINDS order."""
    cols = []
    for loc, d in locations.items():
        for kind in KINDS:
            if kind in ("t_at", "w_at"):
                cols.append((loc, kind, None))
            elif kind in d:
                cols.append((loc, kind, d[kind]))
    return cols


def fold(a: np.ndarray, n_spools: int, cols) -> np.ndarray:
    """Rows of per-step (or already folded) samples into one row per bin of BIN_S: the time and the spools' speeds
    at the bin's end, per location the largest whirl with the time and speed of its sample, the largest load,
    stress and force, the film temperature at the bin's end."""
    if not len(a):
        return a
    b = np.floor(a[:, 0] / BIN_S).astype(np.int64)
    starts = np.concatenate([[0], np.flatnonzero(np.diff(b)) + 1])
    if len(starts) == len(a):
        return a
    ends = np.concatenate([starts[1:], [len(a)]])
    out = np.maximum.reduceat(a, starts)
    out[:, :1 + n_spools] = a[ends - 1, :1 + n_spools]
    idx = np.arange(len(a))
    seg = np.repeat(np.arange(len(starts)), np.diff(np.concatenate([starts, [len(a)]])))
    for c, (_, kind, _) in enumerate(cols, start=1 + n_spools):
        if kind == "whirl":
            at = np.minimum.reduceat(np.where(a[:, c] == out[seg, c], idx, len(a)), starts)
            out[:, c + 1] = a[at, c + 1]
            out[:, c + 2] = a[at, c + 2]
        elif kind == "film":
            out[:, c] = a[ends - 1, c]
    return out


def restart_revolutions(sc) -> float:
    """Revolutions of a TM interval after a held one that the response track and figure leave out: the
    restart's ramp (``[schedule] restart_cycles``, master/manipulator/restart.py) and the steady window after it
    (``[results] cycles``), in which the hold reads the settled mechanics."""
    from rotorcosim.cases.blade_loss.results import window_cycles

    return math.ceil(float(sc.schedule.get("restart_cycles", RESTART_CYCLES)) - 1e-9) + window_cycles(sc)


class RundownTrack(Observer):
    """Per bin of BIN_S of thermo-mechanical time: its end time, each spool's speed, and per location the largest
    whirl radius (with the time and the crossing spool's speed of that sample), contact load, inner-race stress
    and transmitted force, and the film temperature (:func:`fold`). Of a TM interval that follows a held one, the
    samples of its first ``skip`` revolutions (of the crossing spool) are left out; of one that ends before,
    all but its last revolution."""

    def __init__(self, spools, crossing_spool: str | None = None, skip: float = 0.0):
        self.spools = list(spools)
        self.crossing_spool = crossing_spool or (self.spools[0] if self.spools else None)
        self.skip = float(skip)
        self.rows: list[np.ndarray] = []
        self.start_speed: dict[str, float] = {}
        self._phase = None
        # while a restart's first revolutions are skipped: the revolutions since it, the last sample's time and
        # the last revolution's rows (None, None, []: not skipping)
        self._turns, self._t_last, self._tail = None, None, []

    def start(self, sim, schedule):
        self.locations = _locations(sim)
        self.cols = _layout(self.locations)
        for sp in self.spools:
            self.start_speed[sp] = float(sim.value(f"{sp}.Omega")[0])

    def interval_start(self, sim, phase, step):
        self.active = phase == COUPLED
        restart = self.active and self._phase == HELD and self.skip > 0.0 and bool(self.spools)
        self._phase = phase
        self._turns, self._t_last, self._tail = (0.0, float(sim.t), []) if restart else (None, None, [])

    def interval_end(self, sim, used):
        if self._turns is not None and self._tail:
            # shorter than the skip: its last revolution, the closest it came to settling
            self.rows.append(fold(np.vstack(self._tail)[:, :-1], len(self.spools), self.cols))
        self._turns, self._tail = None, []

    def _take(self, rows: np.ndarray) -> np.ndarray:
        """The per-step ``rows`` a restart's first revolutions leave (all of them outside those)."""
        if self._turns is None:
            return rows
        w = np.abs(rows[:, 1 + self.spools.index(self.crossing_spool)])
        t = rows[:, 0]
        turns = self._turns + np.cumsum(w * np.diff(np.concatenate([[self._t_last], t]))) / (2.0 * math.pi)
        self._turns, self._t_last = float(turns[-1]), float(t[-1])
        keep = turns >= self.skip
        if keep.any():
            self._turns, self._tail = None, []
            return rows[keep]
        # the last revolution's rows (with their turns): all an interval that ends before the skip gives
        tail = np.vstack(self._tail + [np.column_stack([rows, turns])])
        self._tail = [tail[tail[:, -1] > self._turns - 1.0]]
        return rows[:0]

    def block_signals(self, sim):
        refs = [f"{sp}.Omega" for sp in self.spools] + [ref for _, _, ref in self.cols if ref is not None]
        return list(dict.fromkeys(refs))

    def _rows(self, ts, value) -> np.ndarray:
        """Per-step rows (columns as :meth:`table`'s) from ``value(ref)``: one row per step of ``ts``."""
        n = len(ts)
        cols = [np.asarray(ts, dtype=float)]
        cols += [np.asarray(value(f"{sp}.Omega")).reshape(n, -1)[:, 0] for sp in self.spools]
        w = cols[1 + self.spools.index(self.crossing_spool)] if self.spools else np.zeros(n)
        for _, kind, ref in self.cols:
            if kind == "t_at":
                cols.append(cols[0])
            elif kind == "w_at":
                cols.append(w)
            else:
                v = np.asarray(value(ref)).reshape(n, -1)
                if kind in ("whirl", "force"):
                    cols.append(np.hypot(v[:, 0], v[:, 1]))
                else:
                    cols.append(v[:, 0])    # load: inner race of [inner, outer]; stress: the inner race; film
        return np.column_stack(cols)

    def step_block(self, sim, ks, ts, data):
        if not self.active or not len(ts):
            return
        rows = self._take(self._rows(ts, lambda ref: data[ref]))
        if len(rows):
            self.rows.append(fold(rows, len(self.spools), self.cols))

    def step(self, sim, t):
        if not getattr(self, "active", False):
            return
        rows = self._take(self._rows([t], lambda ref: np.asarray(sim.value(ref))[None, :]))
        if len(rows):
            self.rows.append(rows)

    def table(self) -> np.ndarray:
        """All bins: columns t, the spools' speeds [rad/s], then per location its columns in KINDS order (whirl [m],
        t_at [s], w_at [rad/s], load [N], stress [Pa], force [N], film [K]; those it has)."""
        n = 1 + len(self.spools) + len(self.cols)
        if not self.rows:
            return np.zeros((0, n))
        return fold(np.vstack(self.rows), len(self.spools), self.cols)


def _spools(sc) -> list[str]:
    r = sc.extra.get("results", {})
    spools = r.get("spools") or [n for n, c in sc.components.items() if c.implementation == "spool.speed"]
    return list(spools)


def _crossing_spool(sc, spools) -> str | None:
    """The spool that turns the unbalance: the one connected to ``rotor.Omega_pt`` (else the first)."""
    for c in sc.connections:
        if c.dst == "rotor.Omega_pt" and c.src.partition(".")[0] in spools:
            return c.src.partition(".")[0]
    return spools[0] if spools else None


def _case_blade_loss(sc) -> bool:
    from rotorcosim.cases.blade_loss.results import bearing_ids
    return bool(bearing_ids(sc.components))


def observers(sc, cycle):
    spools = _spools(sc)
    crossing = _crossing_spool(sc, spools)
    obs = [RundownTrack(spools, crossing, restart_revolutions(sc)), SpoolEnergy(spools)]
    cycles = fatigue.observer(sc, cycle)
    if cycles is not None:
        obs.append(cycles)
    # an engine on an airframe: its interface loads (cases/interface), last so that the blade-loss case's
    # observers keep their places
    tail = interface.observers(sc, f"{crossing}.Omega" if crossing else None)
    if _case_blade_loss(sc):
        from rotorcosim.cases.blade_loss import results as bl
        obs += bl.observers(sc, cycle)
    return obs + tail + fuse_comparison.observers(sc)


def check(sc, sim) -> None:
    spools = _spools(sc)
    if not spools:
        raise ValueError(f"scenario {sc.name!r}: [results] kind = 'rundown' needs a spool component (spool.speed)")
    for sp in spools:
        if sp not in sim.system.components:
            raise ValueError(f"[results] spools: no component {sp!r}")
    fatigue.check(sc, sim)
    interface.check(sc, sim)
    fuse_comparison.check(sc)


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


class Candidate(NamedTuple):
    """A resonance peak at one location labelled with a mode: its location, the peak, its row in the table, the
    mode's undamped and damped critical speeds [rev/min] and the film temperatures [C] at its sample."""
    location: str
    peak: Peak
    row: int
    undamped: float
    damped: float | None
    film_C: dict
    #: the configuration in force at the peak (its index in the modes' stages: 0 before any event)
    stage: int = 0


def _nearest(x: float, values) -> int:
    return int(np.argmin([abs(math.log(x / v)) for v in values]))


def label(loc: str, speed_rpm: float, temps: dict, modes) -> tuple[float, float | None]:
    """The mode of a peak at ``loc`` and ``speed_rpm``: the nearest of the damped critical speeds the linearised
    engine has at that location at the film temperatures ``temps`` (``modes.damped_near``: it and the undamped
    critical speed of its mode), or, where it has none there, the nearest undamped critical speed. (undamped,
    damped)."""
    hit = modes.damped_near(loc, speed_rpm, temps)
    if hit is not None:
        d, u = hit
        return u, d
    und = modes.undamped
    return und[_nearest(speed_rpm, und)], None


def crossings(table: np.ndarray, spool: str, modes, locations: dict, n_spools: int) -> list[dict]:
    """The crossings of ``spool``'s speed through the critical speeds (module docstring) over the rows of
    ``table`` (RundownTrack.table, its location columns as :func:`_layout` of ``locations``). ``modes``: the
    critical speeds (:mod:`.modes`: ``undamped`` [rev/min] and ``damped_near(location, speed, temperatures)``;
    ``prepare(lo, hi)`` with the speed range [rev/min] of the peaks found is called first), or a :class:`.modes.StagedModes`: the
    critical speeds of each configuration a run's events put in force (a support fuse's break), each peak
    labelled with those in force at its time, each entry with its ``configuration``."""
    from .modes import StagedModes

    staged = modes if isinstance(modes, StagedModes) else StagedModes([(-math.inf, None, modes)])
    if not len(table) or not any(m.undamped for _, _, m in staged.stages):
        return []
    cols, c = {}, 1 + n_spools
    for loc, kind, _ in _layout(locations):
        cols.setdefault(loc, {})[kind] = c
        c += 1
    names = {"whirl": ("peak_whirl_mm", 1e3), "load": ("peak_contact_load_N", 1.0),
             "stress": ("peak_contact_stress_MPa", 1e-6), "force": ("peak_transmitted_force_N", 1.0)}
    found = {loc: resonance_peaks(table[:, cc["w_at"]] * RPM, table[:, cc["whirl"]]) for loc, cc in cols.items()}
    speeds = [p.speed for pk in found.values() for p in pk]
    if speeds:
        for _, _, m in staged.stages:
            m.prepare(min(speeds), max(speeds))

    def temps(j):
        return {loc: float(table[j, cc["film"]]) - KELVIN for loc, cc in cols.items() if "film" in cc}

    cands: list[Candidate] = []
    for loc, pk in found.items():
        for p in pk:
            j = p.index
            T = temps(j)
            k = staged.index(float(table[j, cols[loc]["t_at"]]))
            u, d = label(loc, p.speed, T, staged.stages[k][2])
            cands.append(Candidate(loc, p, j, u, d, T, k))
    order = list(cols)
    t_run = table[:, cols[order[0]]["t_at"]]
    w_all = table[:, cols[order[0]]["w_at"]] * RPM
    out = []
    keys = {(k, u) for k, (_, _, m) in enumerate(staged.stages) for u in m.undamped}
    for k, u in sorted(keys | {(cd.stage, cd.undamped) for cd in cands}):
        mine = [cd for cd in cands if (cd.stage, cd.undamped) == (k, u)]
        if not mine:
            # the speeds the run had while this configuration was in force
            w_run = w_all[(w_all > 0.0) & (staged.index_array(t_run) == k)]
            w_lo, w_hi = (float(w_run.min()), float(w_run.max())) if len(w_run) else (math.nan, math.nan)
            if not w_lo <= u <= w_hi:
                continue                    # never reached
            entry = {"spool": spool, "critical_speed_rpm": u, "damped_critical_speed_rpm": None,
                     "film_temperature_C": None, "location": None, "peak_found": False, "t_s": None,
                     "peak_speed_rpm": None, "direction": None, "speed_range_rpm": None,
                     "note": f"no resonance peak of the whirl at any location labelled with this mode (no local "
                             f"maximum of the whirl against speed standing out by {PROMINENCE:.0%} of its largest "
                             "value nearer to it than to another mode)"}
            entry["bearings"] = {loc: {names[x][0]: None for x in d if x in names} for loc, d in locations.items()}
            out.append(staged.tag(entry, k))
            continue
        # the defining peak: at the first location (in the engine's order) with one, its largest there
        loc = min({cd.location for cd in mine}, key=order.index)
        at = sorted((cd for cd in mine if cd.location == loc), key=lambda cd: -cd.peak.amplitude)
        best = at[0]
        cc = cols[loc]
        j = best.row
        t_j = float(table[j, cc["t_at"]])
        # the direction: the crossing spool's speed over the bins around the sample
        w_loc = table[:, cc["w_at"]]
        dw = float(w_loc[min(j + 1, len(w_loc) - 1)] - w_loc[max(j - 1, 0)])
        entry = {"spool": spool, "critical_speed_rpm": u, "damped_critical_speed_rpm": best.damped,
                 "film_temperature_C": best.film_C or None, "location": loc, "peak_found": True,
                 "t_s": t_j, "peak_speed_rpm": best.peak.speed, "direction": "up" if dw > 0 else "down",
                 "speed_range_rpm": [best.peak.lo, best.peak.hi]}
        if len(at) > 1:
            entry["other_peaks_rpm"] = sorted(cd.peak.speed for cd in at[1:])
        entry["bearings"] = {}
        for l2, d in locations.items():
            own = sorted((cd for cd in mine if cd.location == l2), key=lambda cd: -cd.peak.amplitude)
            p = own[0].peak if own else best.peak
            w2 = table[:, cols[l2]["w_at"]] * RPM
            sel = np.flatnonzero((w2 >= p.lo) & (w2 <= p.hi))
            r = {names[k][0]: float(table[sel, cols[l2][k]].max()) * names[k][1] if len(sel) else None
                 for k in KINDS if k in names and k in cols[l2]}
            r["speed_range_rpm"] = [p.lo, p.hi]
            entry["bearings"][l2] = r
        out.append(staged.tag(entry, k))
    return out


def extract(sc, sim, obs, report) -> dict:
    from .modes import modes_of

    track, energy = obs[0], obs[1]
    table = track.table()
    comps = sim.system.components
    speeds = {}
    for sp in track.spools:
        c = comps[sp]
        cut = c.p.get("t_fuel_cut", -1.0)
        speeds[sp] = {"inertia_kgm2": float(c.J), "start_rpm": track.start_speed[sp] * RPM,
                      "end_rpm": float(c.y["Omega"][0]) * RPM,
                      "t_fuel_cut_s": float(cut) if c.p.get("profile") == "torque" and cut >= 0.0 else None,
                      # a stopped spool is a legal end state (friction, or a profile to 0 rev/min)
                      "stopped": float(c.y["Omega"][0]) == 0.0}
    out = {"speeds": speeds, "energy": energy.summary(sim), "crossings": []}
    if track.crossing_spool is not None and len(table):
        modes = modes_of(sc, sim, track.locations, report.events)
        out["crossings"] = crossings(table, track.crossing_spool, modes, track.locations, len(track.spools))
        from rotorcosim.cases.blade_loss.engine_names import spool_name
        name = spool_name(sc, track.crossing_spool)
        for c in out["crossings"]:
            c["spool_name"] = name
    force = [o for o in obs if isinstance(o, fuse_comparison.CasingForce)]
    rest = [o for o in obs[2:] if not isinstance(o, (interface.InterfaceTrack, fuse_comparison.CasingForce))]
    if rest and isinstance(rest[0], LoadCycles):
        out["fatigue"] = fatigue.summary(rest[0], sc)
        rest = rest[1:]
    if _case_blade_loss(sc):
        from rotorcosim.cases.blade_loss import results as bl
        out.update(bl.extract(sc, sim, rest, report))
    out.update(interface.extract(obs, out.get("fatigue")))
    if force:
        out["casing_force_peak_N"] = dict(force[0].peak)
    if sc.extra.get("results", {}).get("without_fuse"):
        out["fuse_comparison"] = fuse_comparison.compare(sc, float(sim.t), out)
    return out


def result_paths(sc) -> list[str]:
    """The results :func:`extract` reports for scenario ``sc``, as dotted paths into summary.json (``crossings.``
    ending in a dot: any path below it, the crossings found being known only after the run)."""
    out = []
    for sp in _spools(sc):
        out += [f"speeds.{sp}.{k}" for k in ("inertia_kgm2", "start_rpm", "end_rpm", "t_fuel_cut_s", "stopped")]
        # energy.py's summary, held equal to it by tests/cases/test_result_paths.py
        out += [f"energy.{sp}.{k}" for k in ("inertia_kg_m2", "kinetic_energy_lost_J", "residual_J", "residual_pct",
                                             "residual_of_lost_pct", "rub_dissipated_J", "rub_whirl_share_J",
                                             "drag_dissipated_J")]
        out += [f"energy.{sp}.work_J.{k}" for k in ("drive", "drag", "rub", "aero")]
    out.append("crossings.")
    if sc.extra.get("results", {}).get("fatigue_loads"):
        out.append("fatigue.")
    if _case_blade_loss(sc):
        from rotorcosim.cases.blade_loss import results as bl
        out += bl.result_paths(sc)
    res = sc.extra.get("results", {})
    if res.get("casing_force_peak") or res.get("without_fuse"):
        out.append("casing_force_peak_N.")
    if res.get("without_fuse"):
        out.append("fuse_comparison.")
    return out + interface.result_paths(sc)


def figures(sc, data, out, pool=None, dpi: int | None = None) -> list[str]:
    """The rundown figures (:mod:`rotorcosim.cases.rundown.figures`) from the run's series, drawn here at ``dpi``
    (None: the default)."""
    return importlib.import_module(FIGURES_MODULE).figures(sc, data, out, dpi=dpi)
