"""What a run will cost before it starts, and the schedules that cannot mean anything.

The estimate counts the base steps of the schedule exactly and prices each from a declared step cost:
``MASTER_STEP_S`` for the master and observers plus ``COMPONENT_STEP_S`` per component. Both come from the
measured profile of the shipped case's nine-component system (``bench/``: master and observers ~100 us, the
components 3-35 us each per thermo-mechanical step; 150 000 TM steps took 41 s, i.e. ~270 us per step, and the
estimate gives 300 us). Components stepping at a multiple of the base step and
thermal-only intervals make the estimate an upper bound.

A run estimated above ``LIMIT_S`` of wall time is refused unless forced (a run on the automatic schedule is not:
its estimate, every step thermo-mechanical, is only an upper bound, often by a factor of a hundred where the
thermal-only intervals carry the hours: a rundown's hour of windmilling); a schedule with a thermo-mechanical
interval shorter than one communication step of a component, or than one base step, is refused always (the
interval would be silently stretched to a step: a 1e-13 s "run" would report results of a millisecond).
"""
from __future__ import annotations

import math

from rotorcosim.master.schedule.auto import AutoSchedule
from rotorcosim.master.schedule.timeline import Timeline, phases_of

MASTER_STEP_S = 30e-6
COMPONENT_STEP_S = 30e-6
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


def estimate(sc, schedule) -> dict:
    """``{"steps": base steps, "wall_s": estimated wall time}`` of ``schedule`` on scenario ``sc``."""
    n_comp = max(1, len(sc.components))
    per_step = MASTER_STEP_S + COMPONENT_STEP_S * n_comp
    if isinstance(schedule, Timeline):
        counts = [iv.duration / iv.step for iv in schedule.intervals]
    else:  # automatic: at most every step thermo-mechanical
        counts = [schedule.duration / schedule.step]
    if not all(n <= MAX_STEPS for n in counts) or sum(counts) > MAX_STEPS:
        # not a long run but no run: the time t0 + k h of a step k beyond 2^53 is not even representable
        raise BudgetError(f"the schedule asks for {sum(counts):.3g} steps, beyond the {MAX_STEPS:.3g} a step "
                          "counter holds exactly (a --duration in other units than seconds?)")
    steps = sum(math.ceil(n - 1e-9) for n in counts)
    return {"steps": steps, "wall_s": steps * per_step, "wall": hms(steps * per_step)}


def check(sc, schedule, force: bool = False) -> dict:
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
    est = estimate(sc, schedule)
    if isinstance(schedule, AutoSchedule):
        est["upper_bound"] = True
    elif est["wall_s"] > LIMIT_S and not force:
        raise BudgetError(f"this run would take {est['steps']:.3g} steps, about {est['wall']} of wall time "
                          f"(estimated at {(MASTER_STEP_S + COMPONENT_STEP_S * max(1, len(sc.components))) * 1e6:.0f} us "
                          f"per step), above the {hms(LIMIT_S)} limit: give --force to run it anyway, or a shorter "
                          "--duration")
    return est
