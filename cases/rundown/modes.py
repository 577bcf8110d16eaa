"""The critical speeds a rundown's resonance peaks are labelled with.

For an engine with co-simulated bearings, the linearised engine of the run (cases/blade_loss/linear_engine.py:
the ball contacts at the preloaded rest, the journal body, the O-ring, the film linearised about the centred
journal): its forward synchronous critical speeds (undamped, rotorcosim.components.rotor.critical) and, at given
film temperatures, its damped critical speeds (cases/blade_loss/response_peaks.py: the speeds at which its
unbalance response peaks, per bearing id). Each damped critical speed is one mode's: the one whose undamped
critical speed is nearest to it (the films move the engine's peaks 5-12 %, less than half the distance between
its modes). The film's damping follows the oil's viscosity, so the damped speeds are computed per set of film
temperatures (each bearing's damper its own, rounded to ``TEMPERATURE_STEP_C``), once each per run, on one speed
grid solved once for them all (response_peaks.FilmScan), each damped critical speed refined only when it can be
the one nearest to a run's peak (response_peaks.DampedPeaks); the search covers the speeds of the peaks found
(``prepare``) widened by ``SEARCH_MARGIN``. All of it is kept per process (the runs of a sweep or of a comparison
share it).

A test rotor without co-simulated bearings (the Jeffcott check case) has the scenario's ``[results]
critical_speeds_rpm`` (undamped; no damped speeds).

A run whose support fuses break (an engine file's ``[fuse.ID]``; the run's ``events`` of kind ``break``) changes
its engine there: its peaks are labelled with the critical speeds of the configuration in force at their time
(:class:`StagedModes`): the engine with every fuse intact, then after each break with each fuse at the stage its
own breaks reached so far (cases/blade_loss/linear_engine.py ``fuse_stage``, per fuse id).

The figures' dashed lines (:func:`marked_critical_speeds`) are the scenario's ``[results] critical_speeds_rpm``
when it gives them, else the engine's: the forward synchronous critical speeds that the figures' spool excites,
of the linear engine ``rotorcosim check-engine`` lists them of (the scenario's bearings and dampers linearised
where the engine file attaches them), up to the run's top speed.
"""
from __future__ import annotations

import math

#: film temperatures [C] are rounded to this before the damped critical speeds are computed (and cached): the
#: paper engine's damped speeds move by ~40 rev/min per C (docs/explanation/rundown.md), 10 per 0.25 C
TEMPERATURE_STEP_C = 0.25
#: the damped search spans the peaks' speeds divided and multiplied by this (a peak's mode lies within it)
SEARCH_MARGIN = 1.3
#: how many forward critical speeds of the linear engine are listed
COUNT = 8
#: the damped search's range is widened to multiples of this [rev/min]
RANGE_STEP_RPM = 500.0
#: per process: (model digest, reference speed, bearing and damper specifications, top speed) -> (supports,
#: undamped critical speeds, {("scan", range): its FilmScan, (range, film temperatures): their DampedPeaks})
_ENGINES: dict[tuple, tuple] = {}
KELVIN = 273.15


#: the figures mark the engine's critical speeds up to this times the run's highest speed of their spool
MARK_SPAN = 1.1


def marked_critical_speeds(sc, spool: str, top_rpm: float) -> list[float]:
    """The critical speeds [rev/min] the rundown figures mark (module docstring) for the spool component
    ``spool`` whose highest speed in the run is ``top_rpm``: ``[results] critical_speeds_rpm`` when the scenario
    gives them; else the engine's forward synchronous critical speeds excited by that spool up to
    :data:`MARK_SPAN` x ``top_rpm``; [] for a scenario without a rotor engine the linear engine can take (a
    test rotor without the key, an engine without dampers at its bearings)."""
    given = sc.extra.get("results", {}).get("critical_speeds_rpm")
    if given:
        return [float(c) for c in given]
    rotor = sc.components.get("rotor")
    if rotor is None or not (math.isfinite(top_rpm) and top_rpm > 0.0):
        return []
    from rotorcosim.cases.blade_loss import linear_engine
    from rotorcosim.components.airframe.installed import installed_model
    from rotorcosim.components.rotor import critical, engine_check

    try:
        m = installed_model(rotor.parameters.get("model_file") or "")
        ops = engine_check.operating_speeds(m.data) if m.data.get("spool") else {}
        name = sc.components[spool].parameters.get("spool", "pt") if spool in sc.components else None
        excited = ops[name][0] / next(iter(ops.values()))[0] if name in ops else 1.0
        every = critical.every_synchronous_critical_speed(m, linear_engine.supports(sc, data=m.data),
                                                          MARK_SPAN * top_rpm, excited=excited)
    except (ValueError, KeyError, ZeroDivisionError):
        return []
    return [r["rpm"] for r in every if r["whirl"] == "forward"]


class ScenarioModes:
    """The scenario's critical speeds, undamped only."""

    def __init__(self, undamped):
        self.undamped = sorted(float(c) for c in undamped)

    def prepare(self, lo_rpm: float, hi_rpm: float) -> None:
        """Nothing to prepare."""

    def damped_near(self, loc: str, speed_rpm: float, temps: dict) -> None:
        """No damped critical speeds."""
        return None


class EngineModes:
    """The linearised engine's critical speeds (module docstring): ``undamped`` [rev/min], ``damped_near``: the
    damped critical speed at a bearing nearest to a peak's speed, at the film temperatures of the peak."""

    def __init__(self, sc, rotor, dampers: dict, max_rpm: float, fuse_stage: int | dict = 0):
        from rotorcosim.cases.blade_loss import linear_engine
        from rotorcosim.components.rotor import critical

        from rotorcosim.components.airframe.installed import on_airframe

        self.full = on_airframe(rotor.full_model(), rotor.p["model_file"])
        self.dampers = dampers
        self.ref_rpm = float(rotor.p["omega_pt"]) * 30.0 / math.pi
        # per process, the linear engine of a model and of the bearings' and dampers' specifications (a sweep's
        # or a comparison's runs share it)
        specs = repr(sorted((n, c.implementation, sorted(c.parameters.items())) for n, c in sc.components.items()
                            if n.startswith(("bearing", "damper"))))
        stage_key = tuple(sorted(fuse_stage.items())) if isinstance(fuse_stage, dict) else fuse_stage
        self._key = (self.full.digest, self.ref_rpm, specs, max_rpm, stage_key)
        if self._key not in _ENGINES:
            sup = linear_engine.supports(sc, data=self.full.data, fuse_stage=fuse_stage)
            crit = critical.synchronous_critical_speeds(self.full, sup, n=COUNT, max_rpm=max_rpm)
            _ENGINES[self._key] = (sup, [float(c) for c in crit["forward_synchronous_rpm"]], {})
        self.sup, self.undamped, self._cache = _ENGINES[self._key]
        self.range = None

    def prepare(self, lo_rpm: float, hi_rpm: float) -> None:
        """Search the damped critical speeds over [lo / SEARCH_MARGIN, hi * SEARCH_MARGIN] [rev/min], widened to
        whole RANGE_STEP_RPM (runs whose peaks differ a little share the search)."""
        self.range = (math.floor(lo_rpm / SEARCH_MARGIN / RANGE_STEP_RPM) * RANGE_STEP_RPM,
                      math.ceil(hi_rpm * SEARCH_MARGIN / RANGE_STEP_RPM) * RANGE_STEP_RPM)

    def damped_near(self, loc: str, speed_rpm: float, temps: dict) -> tuple[float, float] | None:
        """The damped critical speed at bearing id ``loc`` nearest to ``speed_rpm`` at the film temperatures
        ``temps`` (bearing id -> C) and the undamped one of its mode (nearest to it), [rev/min]; None where the
        engine's response does not peak at ``loc``."""
        d = self._peaks(temps).nearest(loc, speed_rpm)
        if d is None:
            return None
        return d, min(self.undamped, key=lambda u: abs(math.log(d / u)))

    def _peaks(self, temps: dict):
        """The damped critical speeds (response_peaks.DampedPeaks) at the film temperatures ``temps``, rounded
        to TEMPERATURE_STEP_C; one search per range and rounded temperatures, its grid shared with the other
        temperatures' (response_peaks.FilmScan)."""
        from rotorcosim.cases.blade_loss import linear_engine, response_peaks

        step = TEMPERATURE_STEP_C
        rounded = {k: round(float(t) / step) * step for k, t in temps.items() if math.isfinite(t)}
        key = (self.range, tuple(sorted(rounded.items())))
        out = self._cache.get(key)
        if out is None:
            sup = {}
            for h, s in self.sup.items():
                k = h[1:]
                s = dict(s)
                if k in rounded and k in self.dampers:
                    s["c_film"] = linear_engine.film_damping(self.dampers[k], rounded[k])
                    s["oil_temperature_C"] = rounded[k]
                sup[h] = s
            lo, hi = self.range or (0.5 * self.undamped[0], 1.5 * self.undamped[-1])
            scan = self._cache.get(("scan", lo, hi))
            if scan is None:
                grid = response_peaks.speed_grid(lo, hi)
                scan = self._cache[("scan", lo, hi)] = response_peaks.FilmScan(self.full, self.sup, grid, self.ref_rpm)
            whirl = response_peaks.Whirl(self.full, sup, self.ref_rpm)
            table = scan.table(sup)
            if table is None:
                table = response_peaks.direct_table(scan.grid, whirl)
            out = self._cache[key] = response_peaks.DampedPeaks(scan.grid, table, whirl)
        return out


class StagedModes:
    """The critical speeds of each configuration of a run: ``stages`` [(t_from [s], label, modes)], in time order,
    the first from -inf (label None: the run's initial configuration)."""

    def __init__(self, stages):
        self.stages = list(stages)
        self._t = [t for t, _, _ in self.stages]

    def index(self, t: float) -> int:
        """The configuration in force at ``t`` [s]."""
        return max(i for i, t0 in enumerate(self._t) if t0 <= t)

    def index_array(self, t):
        """:meth:`index` of each time of the array ``t``."""
        import numpy as np

        return np.searchsorted(np.asarray(self._t[1:]), np.asarray(t), side="right")

    def tag(self, entry: dict, k: int) -> dict:
        """A crossing ``entry`` with the ``configuration`` it was labelled in (a run with events only)."""
        if len(self.stages) > 1:
            entry["configuration"] = self.stages[k][1] or "initial"
        return entry


def fuse_breaks(events, comps) -> list[tuple[float, dict, str]]:
    """(t [s], every fuse's stage from then on ({fuse id: stage}, the id of component ``fuse<ID>``), a label) of
    each break of a support fuse among a run's ``events``."""
    out = []
    stages: dict[str, int] = {}
    for e in events or ():
        c = comps.get(e.get("component"))
        if e.get("kind") != "break" or c is None or "k_intact" not in getattr(c, "p", {}):
            continue
        stage = int(e.get("values", {}).get("stage", 1))
        stages[str(e["component"]).removeprefix("fuse")] = stage
        out.append((float(e["t_s"]), dict(stages), f"after {e['component']} break at {e['t_s']:.6g} s (stage {stage})"))
    return out


def modes_of(sc, sim, locations: dict, events=()):
    """The critical speeds of a run: the linearised engine's when the run has co-simulated bearings the engine
    file attaches (``locations`` keyed by bearing id), else the scenario's ``critical_speeds_rpm``; with the
    breaks of support fuses among ``events``, a :class:`StagedModes` of the engine before and after each."""
    comps = sim.system.components
    given = sc.extra.get("results", {}).get("critical_speeds_rpm", [])
    if "disk" in locations or "rotor" not in comps:
        return ScenarioModes(given)
    dampers = {k: comps[f"damper{k}"] for k in locations if f"damper{k}" in comps}
    top = float(comps["rotor"].p["omega_pt"]) * 30.0 / math.pi
    try:
        first = EngineModes(sc, comps["rotor"], dampers, 2.0 * top)
        breaks = fuse_breaks(events, comps)
        if not breaks:
            return first
        return StagedModes([(-math.inf, None, first)]
                           + [(t, text, EngineModes(sc, comps["rotor"], dampers, 2.0 * top, fuse_stage=stage))
                              for t, stage, text in breaks])
    except ValueError:
        # an engine the linear engine cannot take (no damper for an attached bearing): the scenario's speeds
        return ScenarioModes(given)
