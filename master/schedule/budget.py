"""What a run will cost before it starts, and the schedules that cannot mean anything.

The estimate counts the steps of the schedule exactly and prices each from what the scenario's components declare
(``step_cost_s`` / ``kernel_step_cost_s`` / ``setup_cost_s``, or ``step_cost(parameters, compiled)`` where the cost
follows a parameter, as the FE damper's mesh does; components/contract.py) plus the master's own costs below:

* a thermo-mechanical (TM) base step runs in the compiled loop when every component offers a kernel (and the
  engine is not ``python``), else in the generic Python loop, which adds ``LINK_STEP_S`` per component step;
  a component with a longer communication step costs its share (one step in ``m`` base steps);
* an FMU costs ``FMU_STEP_S`` per step on top of what it runs (the native component's cost when rotorcosim
  exported it, read from its model description; ``FMU_PROCESS_STEP_S`` more out of process); an SSP archive is
  its FMUs;
* a thermal-only (TO) step steps the components that take part in TO intervals, in Python, plus ``TO_STEP_S``
  of the hold;
* each interval costs ``INTERVAL_S`` (the hand-offs, the compiled loop's entry), a run ``RUN_SETUP_S`` plus its
  components' set-up.

The prices are CPU seconds of one core of a 2-core x86 machine of 2025, measured by ``bench/bench_estimate.py``
and held within a factor 2 of measured runs by ``tests/master/test_estimate.py`` (the FE damper, FMUs, an SSP
archive, the monolithic and the staggered schedule, both loops). A loaded machine takes longer; the automatic
schedule is priced as all TM (an upper bound).

A run estimated above ``LIMIT_S`` of wall time is refused unless forced (a run on the automatic schedule is not:
its estimate, every step thermo-mechanical, is only an upper bound, often by a factor of a hundred where the
thermal-only intervals carry the hours: an hour of a slowly turning rotor); a schedule with a thermo-mechanical
interval shorter than one communication step of a component, or than one base step, is refused always (the
interval would be silently stretched to a step: a 1e-13 s "run" would report results of a millisecond).
"""
from __future__ import annotations

import math

from rotorcosim.components.contract import COUPLED, HELD
from rotorcosim.master.schedule.auto import AutoSchedule
from rotorcosim.master.schedule.timeline import Timeline, phases_of

#: the generic loop's own cost per base step [s]
MASTER_STEP_S = 10e-6
#: the generic loop's cost per component step besides the component's own: its inputs and outputs moved and
#: checked [s]
LINK_STEP_S = 7e-6
#: the compiled loop's own cost per base step (recording included) [s]
COMPILED_STEP_S = 1.5e-6
#: an FMU's cost per step on top of the model it runs (fmpy's calls, the variables set and got) [s]
FMU_STEP_S = 30e-6
#: more per step for an FMU in a process of its own: one round trip, both processes working (the toy oscillator
#: FMU over 2000 steps: 125 us in the run's process and 185 us in the FMU's, both CPU, measured) [s]
FMU_PROCESS_STEP_S = 150e-6
#: starting an FMU's process: its interpreter and imports (0.16 s of its CPU for a 10-step run, measured) [s]
FMU_PROCESS_START_S = 0.15
#: the hold's cost per thermal-only step besides the thermal components' steps [s]
TO_STEP_S = 20e-6
#: per interval: the hand-off between phases, the compiled loop's entry [s]
INTERVAL_S = 0.005
#: per run: building the system and the first steps' imports [s]
RUN_SETUP_S = 0.05
#: the price of a component whose implementation cannot be looked up before it is built [s per step]
UNKNOWN_STEP_S = 30e-6
#: estimated wall time above which a run says so on stderr before it starts [s]
WARN_S = 60.0
#: wall time above which a run needs ``--force``
LIMIT_S = 24 * 3600.0
#: most base steps of any run, even forced: 2^53, beyond which float64 step times and counts are no longer exact
MAX_STEPS = 2.0 ** 53
class BudgetError(ValueError):
    """A run refused before it starts: too long without --force, or too short to mean anything."""


def hms(s: float) -> str:
    """A duration ``s`` [s] in words, in the unit that reads best.

    >>> hms(90), hms(5400), hms(36000)
    ('90 s', '90 min', '10.0 h')
    """
    if not math.isfinite(s):
        return "forever"
    if s < 120:
        return f"{s:.0f} s"
    if s < 7200:
        return f"{s / 60:.0f} min"
    if s < 3 * 86400:
        return f"{s / 3600:.1f} h"
    return f"{s / 86400:.3g} days"


def _fmu_inner(path: str):
    """The component class a rotorcosim-exported FMU runs (its vendor annotation), or None. The archive is read
    through the caps of every archive (an entry beyond them is refused here, as the build would refuse it)."""
    from rotorcosim.components import registry
    from rotorcosim.components.bounded_read import TooLarge, read_entry
    from rotorcosim.fmus.model_description import read_annotation
    from rotorcosim.fmus.safezip import ArchiveError, check_entries, open_zip

    try:
        with open_zip(path) as z:
            check_entries(z, str(path))
            impl = read_annotation(read_entry(z, "modelDescription.xml", str(path))).implementation
        return registry.lookup(impl) if impl else None
    except (TooLarge, ArchiveError):
        raise
    except Exception:  # noqa: BLE001 - any other FMU the estimate cannot read is priced as an unknown one
        return None


def component_costs(sc, engine: str = "auto") -> dict:
    """What each step of scenario ``sc`` costs [s]: ``{"compiled": bool, "components": {name: (TM cost, TO cost,
    phases, step)}, "setup_s": ..., "no_kernel": {name: reason}}`` (``phases``: the phases the component steps in,
    TO for a thermal-only update too; ``step``: its communication step or None; ``no_kernel``: the components
    stepping in TM intervals that can never run compiled, choice.class_why_not). Thermal-only steps run in
    Python."""
    from rotorcosim.components import registry
    from rotorcosim.master.compiled import choice

    classes, fmus = {}, {}
    for name, spec in sc.components.items():
        if spec.fmu is not None:
            fmus[name] = spec
            classes[name] = _fmu_inner(spec.fmu)
        else:
            try:
                classes[name] = registry.lookup(spec.implementation, spec.folder)
            except Exception:  # noqa: BLE001 - the build names the problem; the estimate prices it as unknown
                classes[name] = None
    why, coupled = {}, set()
    for name, cls in classes.items():
        if name in fmus:
            from rotorcosim.fmus.importer import FMUComponent

            why[name] = choice.class_why_not(name, FMUComponent)
        elif cls is not None:  # an unknown one: the build names it
            why[name] = choice.class_why_not(name, cls)
        if COUPLED in (cls.phases if cls is not None else {COUPLED}):
            coupled.add(name)
    compiled = engine != "python" and len(why) == len(classes) and not any(why.values())
    costs, setup = {}, RUN_SETUP_S
    for name, spec in sc.components.items():
        cls = classes[name]
        params = spec.parameters
        if cls is None:
            tm, to, phases = UNKNOWN_STEP_S, UNKNOWN_STEP_S, frozenset({COUPLED, HELD})
        else:
            tm, to = cls.step_cost(params, compiled), cls.step_cost(params, False)
            phases = cls.phases | ({HELD} if cls.holds_state_in_TO else set())
            setup += cls.setup_cost_s
        if name in fmus:
            own_process = bool(spec.options.get("process") or spec.options.get("step_timeout"))
            extra = FMU_STEP_S + (FMU_PROCESS_STEP_S if own_process else 0.0)
            tm, to = tm + extra, to + extra
            setup += FMU_PROCESS_START_S if own_process else 0.0
        costs[name] = (tm + (0.0 if compiled else LINK_STEP_S), to + LINK_STEP_S, phases, spec.step)
    return {"compiled": compiled, "components": costs, "setup_s": setup,
            "no_kernel": {n: r for n, r in why.items() if r is not None and n in coupled}}


def estimate(sc, schedule, engine: str = "auto") -> dict:
    """``{"steps": base steps, "wall_s": estimated wall time [s], "wall": the same in words, "engine": the loop
    TM intervals will take ("compiled" / "python"), "step_cost_us": {COUPLED, HELD}: the price of a base step of
    each phase's role [us]}`` of ``schedule`` on scenario ``sc`` (see the module's docstring)."""
    if isinstance(schedule, Timeline):
        phases = phases_of(sc.schedule)
        spans = [(phases.role(iv.phase), iv.duration, iv.step) for iv in schedule.intervals]
    else:  # automatic: at most every step thermo-mechanical
        spans = [(COUPLED, schedule.duration, schedule.step)]
    counts = [d / h for _, d, h in spans]
    if not all(n <= MAX_STEPS for n in counts) or sum(counts) > MAX_STEPS:
        # not a long run but no run: the time t0 + k h of a step k beyond 2^53 is not even representable
        raise BudgetError(f"the schedule asks for {sum(counts):.3g} steps, beyond the {MAX_STEPS:.3g} a step "
                          "counter holds exactly (a --duration in other units than seconds?)")
    c = component_costs(sc, engine)
    wall, steps, per = c["setup_s"], 0, {}
    for (phase, d, h), n in zip(spans, counts):
        n = math.ceil(n - 1e-9)
        steps += n
        if phase == COUPLED:
            own = COMPILED_STEP_S if c["compiled"] else MASTER_STEP_S
            # a component with a longer communication step steps once in every step/h base steps
            cost = own + sum(k / max(1.0, (s or h) / h) for k, _, ph, s in c["components"].values() if COUPLED in ph)
        else:  # TO: the thermal components and the thermal-only updates, in Python, at the interval's step
            cost = TO_STEP_S + sum(k for _, k, ph, _ in c["components"].values() if HELD in ph)
        per.setdefault(phase, cost)
        wall += INTERVAL_S + n * cost
    return {"steps": steps, "wall_s": wall, "wall": hms(wall), "engine": "compiled" if c["compiled"] else "python",
            "step_cost_us": {ph: 1e6 * v for ph, v in per.items()}}


def check(sc, schedule, force: bool = False, engine: str = "auto") -> dict:
    """Raise :class:`BudgetError` for a schedule too short to hold a step, or estimated beyond ``LIMIT_S``
    (unless ``force``); returns the estimate."""
    steps = {n: c.step for n, c in sc.components.items() if c.step}
    if isinstance(schedule, Timeline):
        if not schedule.intervals:
            raise BudgetError("the schedule is empty (a --duration too short for one step?)")
        coupled = phases_of(sc.schedule).coupled
        for i, iv in enumerate(schedule.intervals):
            if iv.phase != coupled:
                continue
            base = sc.schedule.get("step")
            if base and iv.step == iv.duration and iv.duration < base * (1 - 1e-9):
                raise BudgetError(f"thermo-mechanical interval #{i + 1} lasts {iv.duration:.6g} s, shorter than one "
                                  f"step of the schedule ({base:g} s): give a longer --duration")
            for name, h in steps.items():
                if iv.duration < h * (1 - 1e-9):
                    raise BudgetError(f"thermo-mechanical interval #{i + 1} lasts {iv.duration:.6g} s, shorter than "
                                      f"one communication step of {name} ({h:g} s): give a longer --duration")
    elif isinstance(schedule, AutoSchedule):
        longest = max(steps.values(), default=schedule.step)
        if schedule.duration < max(longest, schedule.step):
            raise BudgetError(f"duration {schedule.duration:.6g} s is shorter than one step ({max(longest, schedule.step):g} s)")
        for name, h in steps.items():
            if schedule.tm_min < h * (1 - 1e-9):
                raise BudgetError(f"schedule: tm_min = {schedule.tm_min:g} s is shorter than one communication step "
                                  f"of {name} ({h:g} s): a thermo-mechanical interval holds at least one")
    if engine == "compiled" and (not isinstance(schedule, Timeline) or any(
            iv.phase == phases_of(sc.schedule).coupled for iv in schedule.intervals)):
        from rotorcosim.master.compiled import choice

        choice.check_request(component_costs(sc, engine)["no_kernel"], engine)
    est = estimate(sc, schedule, engine)
    if isinstance(schedule, AutoSchedule):
        est["upper_bound"] = True
    elif est["wall_s"] > LIMIT_S and not force:
        cost = max(est["step_cost_us"].values())
        raise BudgetError(f"this run would take {est['steps']:.3g} steps, about {est['wall']} of wall time "
                          f"(estimated at {cost:.0f} us per step), above the {hms(LIMIT_S)} limit: give --force "
                          "to run it anyway, or a shorter --duration")
    return est


def check_many(run_s: float, runs: int, workers: int, what: str, shorten: str, force: bool = False,
               upper_bound: bool = False) -> dict:
    """The wall time of ``runs`` runs of about ``run_s`` [s] each (:func:`check`'s estimate of one), ``workers``
    at a time, in whole waves: ``{"runs", "run_s", "workers", "wall_s", "wall", "upper_bound"}``. Beyond
    ``LIMIT_S`` it is refused unless ``force`` (or ``upper_bound``: a run on the automatic schedule, priced all
    thermo-mechanical), the refusal saying the estimate and how to shorten it (``shorten``: "fewer samples..."). A
    study or sweep prints :func:`many_line` before its first run.

    >>> check_many(10.0, 64, 2, "uq", "fewer samples")["wall"]
    '5 min'
    """
    workers = max(1, int(workers))
    wall = math.ceil(runs / workers) * run_s
    est = {"runs": runs, "run_s": run_s, "workers": workers, "wall_s": wall, "wall": hms(wall),
           "upper_bound": upper_bound}
    if wall > LIMIT_S and not force and not upper_bound:
        raise BudgetError(f"{what}: {runs} runs of about {_each(run_s)} each, {workers} at a time, would take "
                          f"about {hms(wall)} of wall time, above the {hms(LIMIT_S)} limit: give --force to run it "
                          f"anyway, or {shorten}")
    return est


def many_line(est: dict, what: str) -> str:
    """The line a study or sweep prints before its first run: its estimate (:func:`check_many`; ``runs_at_most``
    in it: the run count is a bound, as a calibration's)."""
    runs = "at most " if est.get("runs_at_most") else ""    # a search that may stop early
    each = "at most " if est["upper_bound"] else "about "   # a run on the automatic schedule
    total = "at most " if runs or est["upper_bound"] else "about "
    return (f"{what}: {runs}{est['runs']} runs of {each}{_each(est['run_s'])} each, {est['workers']} at a time: "
            f"{total}{est['wall']} of wall time (estimated)")


def _each(s: float) -> str:
    """One run's price in words: ``hms``, with two digits below 10 s (a study's runs are often under a second)."""
    return f"{s:.2g} s" if s < 10 else hms(s)
