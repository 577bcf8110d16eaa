"""The fatigue content of a rundown's loads: the scenario's keys, their defaults and sources, and the count of a
run's recorded loads over a span of time.

``[results]`` keys (the rundown case's own, ``RESULTS_KEYS``):

* ``fatigue_loads``: the loads counted, ``"comp.port"`` outputs (each element of a vector port counted on its own);
  default: the airframe's mount loads (``airframe.F_<mount>``) when the run has an airframe, else the force each
  damper transmits to the casing (``damper<ID>.F_journal``), those the run records;
* ``woehler_exponent`` ``m`` (default :data:`WOEHLER_EXPONENT` = 3) and ``reference_cycles`` ``N_ref`` (default
  :data:`REFERENCE_CYCLES` = 2e6) of the damage-equivalent loads: the slope of the fatigue strength curves of
  EN 1993-1-9 (Eurocode 3, *Fatigue*) for direct stress ranges up to 5e6 cycles, and the cycle count at which its
  detail categories are defined;
* ``sn_range_N`` ``S_c`` [N] and ``sn_cycles`` ``N_c`` (default 2e6, EN 1993-1-9's reference) of the S-N curve of
  the Miner damage, ``N(S) = N_c (S / S_c)^-m``: the load range the part endures ``N_c`` times. It belongs to the
  part (its section, material and detail): no default; without it the Miner damage is not computed (None).

The counting and the equations: master/observer/fatigue.py and held_cycles.py.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from rotorcosim.master.observer import fatigue as fg
from rotorcosim.master.observer import held_cycles as hc
from rotorcosim.master.observer.series import SeriesFile

#: EN 1993-1-9: the slope m of the fatigue strength curves (direct stress ranges, N <= 5e6) and the reference
#: cycle count N_C = 2e6 of the detail categories
WOEHLER_EXPONENT = 3.0
REFERENCE_CYCLES = 2.0e6
SN_CYCLES = 2.0e6
#: the keys of [results] and what the module reads from them
KEYS = ("fatigue_loads", "woehler_exponent", "reference_cycles", "sn_range_N", "sn_cycles")
#: the hold's window in turns when the scenario's [schedule] does not say (master/scenario/build.py's default)
HOLD_CYCLES = 5.0


def settings(sc) -> dict:
    """The scenario's fatigue keys with their defaults (module docstring)."""
    r = sc.extra.get("results", {})
    return {"woehler_exponent": float(r.get("woehler_exponent", WOEHLER_EXPONENT)),
            "reference_cycles": float(r.get("reference_cycles", REFERENCE_CYCLES)),
            "sn_range_N": float(r["sn_range_N"]) if r.get("sn_range_N") is not None else None,
            "sn_cycles": float(r.get("sn_cycles", SN_CYCLES))}


def loads_of(sc, recorded) -> list[str]:
    """The loads counted (module docstring) among the ``recorded`` names (a named load the run did not record is
    left out: the summary counts it as the run goes, a recorded series cannot)."""
    named = sc.extra.get("results", {}).get("fatigue_loads")
    if named:
        return [str(n) for n in named if str(n) in recorded]
    mounts = sorted(n for n in recorded if n.startswith("airframe.F_"))
    return mounts or sorted(n for n in recorded if n.startswith("damper") and n.endswith(".F_journal"))


def content(counts: fg.Counts, s: dict) -> dict:
    """``del_N`` and ``miner_damage`` of one load element's cycles with the settings ``s``."""
    m = s["woehler_exponent"]
    return {"del_N": fg.del_load(counts, m, s["reference_cycles"]),
            "miner_damage": fg.miner_damage(counts, m, s["sn_range_N"], s["sn_cycles"])
            if s["sn_range_N"] else None,
            "cycles": float(counts.n.sum())}


def recorded_counts(data, sc, t_from: float = 0.0) -> dict[str, fg.Counts]:
    """The cycles of each load element (``"comp.port[i]"``) of a run's recorded series ``data`` (a run folder's
    ``timeseries.h5`` as a mapping: master/observer/series.py, or the folder) from time ``t_from`` on: coupled
    samples as recorded, held intervals from the hold's window (held_cycles.py), the angle the integral of the
    scenario's cycle signal (``[schedule] cycle``'s speed, recorded)."""
    if isinstance(data, (str, Path)):
        data = SeriesFile(Path(data) / "timeseries.h5")
    t = np.asarray(data["time"], dtype=float)
    keep = t >= t_from
    cyc = sc.schedule.get("cycle") or {}
    speed = np.asarray(data[cyc["signal"]], dtype=float).reshape(t.size, -1)[:, 0] if "signal" in cyc else None
    if speed is None:
        raise ValueError("the load cycles of a held interval need the run's cycle: a [schedule] cycle signal")
    angle = hc.cycle_angle(t[keep], speed[keep])
    held = np.asarray(data["phase"])[keep] == 1
    turns = float(sc.schedule.get("hold_cycles", HOLD_CYCLES))
    out = {}
    for ref in loads_of(sc, list(data)):
        y = np.asarray(data[ref], dtype=float).reshape(t.size, -1)[keep]
        for i in range(y.shape[1]):
            key = f"{ref}[{i}]" if y.shape[1] > 1 else ref
            out[key] = hc.staggered_counts(y[:, i], held, angle, turns)
    return out


def check(sc, sim) -> None:
    """``[results] fatigue_loads`` names outputs of the run's components, and the S-N settings come with what they
    are about (``fatigue_loads``; ``sn_cycles`` with ``sn_range_N``): else a one-line ValueError naming the key."""
    comps = sim.system.components
    res = sc.extra.get("results", {})
    # a setting nothing reads would be taken for one that acted
    unused = [k for k in KEYS[1:] if k in res] if not res.get("fatigue_loads") else \
        (["sn_cycles"] if "sn_cycles" in res and res.get("sn_range_N") is None else [])
    if unused:
        needs = "fatigue_loads (the loads it is about)" if not res.get("fatigue_loads") else \
            "sn_range_N (the load range of the S-N curve it is the cycles of: no Miner damage without it)"
        raise ValueError(f"[results] {unused[0]}: given without [results] {needs}")
    for ref in res.get("fatigue_loads") or []:
        comp, _, port = str(ref).partition(".")
        if comp not in comps:
            raise ValueError(f"[results] fatigue_loads: {ref!r}: no component {comp!r}")
        if port not in comps[comp].y:
            raise ValueError(f"[results] fatigue_loads: {ref!r}: component {comp!r} has no output {port!r} "
                             f"(its outputs: {', '.join(sorted(comps[comp].y))})")


def observer(sc, cycle):
    """The run's :class:`~rotorcosim.master.observer.held_cycles.LoadCycles` of ``[results] fatigue_loads``, or
    None when the scenario names none."""
    named = sc.extra.get("results", {}).get("fatigue_loads")
    if not named:
        return None
    return hc.LoadCycles([str(n) for n in named], cycle, float(sc.schedule.get("hold_cycles", HOLD_CYCLES)))


def summary(obs, sc) -> dict:
    """summary.json ``fatigue``: the settings, and per load element its ``del_N``, ``miner_damage`` and
    ``cycles`` over the whole run."""
    s = settings(sc)
    return {**s, "loads": {k: content(c, s) for k, c in obs.counts().items()}}
