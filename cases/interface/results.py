"""The engine-to-airframe interface of a run: ``interface`` of ``summary.json``.

A scenario whose engine hangs from an airframe (an ``airframe.modal`` component, components/airframe; its name
``[results] airframe``, else the component named ``airframe``) reports, read at every coupled step by
:class:`InterfaceTrack`:

* per mount NAME (``mounts.NAME``): ``peak_N`` (x, y, z), the largest magnitude of each component of the mount's
  load on the airframe (``airframe.F_NAME``) over every thermo-mechanical step of the run (the blade-loss event,
  the rundown, the windmilling's coupled intervals), with the time ``peak_t_s`` and the speed ``peak_speed_rpm`` of
  the crossing spool (None for a constant-speed run) at which each was reached; ``windmilling_N`` (x, y, z), the
  amplitude (largest magnitude) of each component over the last :data:`CYCLES` turns of the last
  thermo-mechanical interval of the run (at most its second half): the steady windmilling level when the run ends
  windmilling; ``peak_Nm`` and ``windmilling_Nm`` the same for the moment (``airframe.M_NAME``) of a mount with a
  rotation spring; ``del_N`` and ``miner_damage`` (x, y, z), the damage-equivalent load and the Miner damage of
  each component over the whole run, when the run counts the mount's load (``[results] fatigue_loads``,
  cases/rundown/fatigue.py);
* per response point P (``points.P``): ``peak_g``, ``peak_t_s``, ``peak_speed_rpm``, ``windmilling_g``: the same
  for its acceleration (``airframe.a_P``) in units of g (:data:`G`);
* ``windmilling``: the window of the windmilling levels, ``t_s`` [start, end] and the crossing spool's speed at its
  end ``speed_rpm``.

In a held (thermal-only) interval the airframe is frozen: its loads are those the coupled intervals reach.
"""
from __future__ import annotations

import math

import numpy as np

from rotorcosim.components.contract import COUPLED
from rotorcosim.master.observer.observer import Observer

#: standard gravity [m/s^2] (the accelerations in g)
G = 9.80665
RPM = 30.0 / math.pi
#: the windmilling level: over this many turns at the end of the last coupled interval
CYCLES = 5
#: the components' names, in the order of the outputs
AXES = ("x", "y", "z")
#: the implementation that makes a scenario "installed"
IMPLEMENTATION = "airframe.modal"


def airframe_of(sc) -> str | None:
    """The airframe component of a scenario (module docstring), or None."""
    named = sc.extra.get("results", {}).get("airframe")
    if named:
        return str(named)
    if "airframe" in sc.components:
        return "airframe"
    hits = [n for n, c in sc.components.items() if c.implementation == IMPLEMENTATION]
    return hits[0] if len(hits) == 1 else None


def check(sc, sim) -> None:
    """A scenario's ``[results] airframe`` names one of its components of :data:`IMPLEMENTATION`: else a one-line
    ValueError naming the key."""
    named = sc.extra.get("results", {}).get("airframe")
    if not named:
        return
    spec = sc.components.get(str(named))
    if spec is None or str(named) not in sim.system.components:
        raise ValueError(f"[results] airframe: no component {named!r}")
    if spec.implementation != IMPLEMENTATION:
        raise ValueError(f"[results] airframe: component {named!r} is a {spec.implementation!r}, not an airframe "
                         f"({IMPLEMENTATION!r})")


class InterfaceTrack(Observer):
    """Peaks and the last coupled interval's levels of the airframe's interface loads and accelerations."""

    def __init__(self, airframe: str, speed_ref: str | None):
        self.airframe = airframe
        self.speed_ref = speed_ref

    def start(self, sim, schedule):
        comp = sim.system.components[self.airframe]
        self.refs: dict[str, tuple[str, str, str]] = {}
        for m in comp.mounts.values():
            self.refs[f"{self.airframe}.F_{m.name}"] = ("mounts", m.name, "N")
            if m.moment:
                self.refs[f"{self.airframe}.M_{m.name}"] = ("mounts", m.name, "Nm")
        for p in comp.model.response:
            self.refs[f"{self.airframe}.a_{p}"] = ("points", p, "g")
        self.peak = {r: np.zeros(3) for r in self.refs}
        self.peak_t = {r: np.full(3, math.nan) for r in self.refs}
        self.peak_w = {r: np.full(3, math.nan) for r in self.refs}
        self.level: dict | None = None
        self.tail: list = []
        self.active = False

    def interval_start(self, sim, phase, step):
        self.active = phase == COUPLED
        self.tail = []

    def block_signals(self, sim):
        return list(self.refs) + ([self.speed_ref] if self.speed_ref else [])

    def _take(self, ts, value) -> None:
        ts = np.asarray(ts, dtype=float)
        n = len(ts)
        w = (np.asarray(value(self.speed_ref), dtype=float).reshape(n, -1)[:, 0] if self.speed_ref
             else np.full(n, math.nan))
        block = {"t": ts.copy(), "w": w.copy()}
        for r in self.refs:
            v = np.abs(np.asarray(value(r), dtype=float).reshape(n, 3))
            j = np.argmax(v, axis=0)
            top = v[j, np.arange(3)]
            better = top > self.peak[r]
            self.peak[r] = np.where(better, top, self.peak[r])
            self.peak_t[r] = np.where(better, ts[j], self.peak_t[r])
            self.peak_w[r] = np.where(better, w[j], self.peak_w[r])
            block[r] = v
        self.tail.append(block)

    def step_block(self, sim, ks, ts, data):
        if self.active and len(ts):
            self._take(ts, lambda ref: data[ref])

    def step(self, sim, t):
        if self.active:
            self._take([t], lambda ref: np.asarray(sim.value(ref))[None, :])

    def interval_end(self, sim, used):
        if not (self.active and self.tail):
            return
        t = np.concatenate([b["t"] for b in self.tail])
        w = np.concatenate([b["w"] for b in self.tail])
        span = t[-1] - t[0]
        window = span / 2.0
        if np.isfinite(w[-1]) and w[-1] > 0.0:
            window = min(window, CYCLES * 2.0 * math.pi / w[-1])
        sel = t >= t[-1] - window
        self.level = {"t_s": [float(t[sel][0]), float(t[-1])],
                      "speed_rpm": float(w[-1]) * RPM if np.isfinite(w[-1]) else None,
                      "amplitude": {r: np.concatenate([b[r] for b in self.tail])[sel].max(axis=0)
                                    for r in self.refs}}
        self.tail = []

    def summary(self) -> dict:
        """The ``interface`` entry (module docstring)."""
        out: dict = {"mounts": {}, "points": {}}
        for r, (group, name, unit) in self.refs.items():
            scale = 1.0 / G if unit == "g" else 1.0
            entry = out[group].setdefault(name, {})
            entry[f"peak_{unit}"] = dict(zip(AXES, (self.peak[r] * scale).tolist()))
            if unit != "Nm":
                entry["peak_t_s"] = dict(zip(AXES, _floats(self.peak_t[r])))
                entry["peak_speed_rpm"] = dict(zip(AXES, _floats(self.peak_w[r] * RPM)))
            lv = self.level["amplitude"][r] * scale if self.level else None
            entry[f"windmilling_{unit}"] = dict(zip(AXES, lv.tolist())) if lv is not None else None
        out["windmilling"] = ({"t_s": self.level["t_s"], "speed_rpm": self.level["speed_rpm"]} if self.level
                              else None)
        return out


def _floats(a) -> list:
    return [float(v) if math.isfinite(v) else None for v in a]


def observers(sc, speed_ref: str | None) -> list[Observer]:
    """The interface's observer of an installed scenario (none for an engine on the ground)."""
    af = airframe_of(sc)
    return [InterfaceTrack(af, speed_ref)] if af is not None else []


def extract(obs: list, fatigue: dict | None = None) -> dict:
    """``{"interface": ...}`` from the observers :func:`observers` made (empty for none). ``fatigue``: the run's
    summary ``fatigue`` (cases/rundown/fatigue.py), whose counted mount loads (``airframe.F_NAME[i]``) give each
    mount's ``del_N`` and ``miner_damage`` (x, y, z; absent for a component not counted)."""
    track = next((o for o in obs if isinstance(o, InterfaceTrack)), None)
    if track is None:
        return {}
    out = track.summary()
    loads = (fatigue or {}).get("loads", {})
    for name, entry in out["mounts"].items():
        ref = f"{track.airframe}.F_{name}"
        rows = {ax: loads.get(f"{ref}[{i}]") for i, ax in enumerate(AXES)}
        if any(r is not None for r in rows.values()):
            for key in ("del_N", "miner_damage"):
                entry[key] = {ax: (r or {}).get(key) for ax, r in rows.items()}
    return {"interface": out}


def result_paths(sc) -> list[str]:
    """The dotted paths of summary.json this module reports for ``sc`` (the mounts and points known after the
    run: ``interface.`` and any path below it)."""
    return ["interface."] if airframe_of(sc) is not None else []
