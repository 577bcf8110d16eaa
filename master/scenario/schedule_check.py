"""The scenario schema's checks of ``[schedule]`` against itself and the components: the cycle source (a period
or a signal), the phases' names, the intervals, and what the thermo-mechanical intervals must hold (two steps a
cycle, the hold's window, the restart's ramp, each component's step)."""
from __future__ import annotations

from typing import Mapping

from rotorcosim.components.contract import COUPLED, HELD, ContractError
from rotorcosim.master.core.phases import Phases
from rotorcosim.master.manipulator.restart import RESTART_CYCLES
from rotorcosim.master.scenario.checkers import did_you_mean, positive
from rotorcosim.master.scenario.tables import CYCLE, INTERVAL, PHASES


def known_component(c, table: str, key: str, ref: str, names) -> None:
    """``ref`` ("component.port") names one of the components ``names``, else ``c``'s error."""
    comp = ref.partition(".")[0]
    if comp not in names:
        raise c.fail(table, key, f"{ref!r}: no component {comp!r}{did_you_mean(comp, names)}; "
                                 f"components: {', '.join(names)}")


def _cycle(c, s: Mapping, comps: Mapping) -> tuple[float | None, str]:
    """The cycle source's constant period [s] (None: none, or a signal's) and how messages say it."""
    speed, cyc = s.get("speed_rpm"), s.get("cycle")
    if cyc is None:
        return (60.0 / speed if speed else None), f"at {speed:g} rev/min" if speed else ""
    if speed is not None:
        raise c.fail("schedule", "cycle", "give speed_rpm or cycle, not both (both say the cycle's period)")
    c.table("schedule.cycle", cyc, CYCLE)
    if ("period" in cyc) == ("signal" in cyc):
        raise c.fail("schedule.cycle", None, "give exactly one of period (s) or signal (\"component.port\")")
    if "period" in cyc:
        for key in ("unit", "angle"):
            if key in cyc:
                raise c.fail("schedule.cycle", key, f"is the {key} of a signal's cycle; a constant period counts "
                                                    "in seconds")
        return cyc["period"], f"of {cyc['period']:g} s"
    known_component(c, "schedule.cycle", "signal", cyc["signal"], list(comps))
    if "angle" in cyc:
        known_component(c, "schedule.cycle", "angle", cyc["angle"], list(comps))
    return None, ""


def _phases(c, s: Mapping) -> Phases:
    """``[schedule.phases]``: the scenario's names of its coupled and held phases (master/core/phases.py)."""
    spec = s.get("phases", {})
    if not isinstance(spec, Mapping):
        raise c.fail("schedule", "phases", f"must be a table {{coupled = NAME, held = NAME}}, got {spec!r}")
    c.table("schedule.phases", spec, PHASES)
    try:
        return Phases.from_spec(spec)
    except ContractError as exc:
        raise c.fail("schedule", "phases", str(exc)) from None


def check_schedule(c, s: Mapping, comps: Mapping) -> list[float]:
    """``[schedule]`` ``s`` of a scenario of components ``comps`` against itself and them, through ``c`` (the
    schema's :class:`~rotorcosim.master.scenario.schema.Checker`): the cycle source, the phases, the intervals,
    a cycle sampled by two steps at least, the hold's window and the restart's ramp within the thermo-mechanical
    intervals, each component's step within and a whole multiple of them. Returns the thermo-mechanical steps
    [s] (the schedule's ``step`` and each TM interval's own)."""
    raw = s.get("intervals")
    tm_durations = []
    step = s.get("step", 1e-5)
    period, per = _cycle(c, s, comps)
    phases = _phases(c, s)
    if raw is not None:
        if not isinstance(raw, list) or not raw:
            raise c.fail("schedule", "intervals", "must be a non-empty list of {phase, duration} tables")
        for i, iv in enumerate(raw):
            w = f"schedule.intervals #{i + 1}"
            c.table(w, iv, INTERVAL)
            names = f"{phases.coupled!r} or {phases.held!r}"
            if "phase" not in iv:
                raise c.fail(w, "phase", f"missing: each interval needs phase = {names}")
            if iv["phase"] not in phases.names:
                raise c.fail(w, "phase", f"{iv['phase']!r} is not a phase of the scenario: {names} "
                                         "([schedule.phases])" + did_you_mean(iv["phase"], phases.names))
            if ("duration" in iv) == ("cycles" in iv):
                raise c.fail(w, "duration", "give exactly one of duration (s) or cycles (rotor revolutions)")
            if "cycles" in iv and not period:
                raise c.fail(w, "cycles", "an interval in rotor cycles needs schedule.speed_rpm (or a cycle "
                                          "of constant period, schedule.cycle = { period = S })")
            d = iv["duration"] if "duration" in iv else iv["cycles"] * period
            if phases.role(iv["phase"]) == COUPLED:
                tm_durations.append((w, d, iv.get("step", step)))
    elif s.get("kind", "monolithic") == "monolithic" and "duration" in s:
        tm_durations.append(("schedule", s["duration"], step))
    if s.get("kind") == "auto" and "tm_min" in s:
        tm_durations.append(("schedule", s["tm_min"], step))
    speed, cycles = s.get("speed_rpm"), s.get("hold_cycles")
    if period:
        # the hold's windows, the restart and the results are counted in cycles sampled at the TM step: a
        # cycle must span two steps at least (Nyquist); 1e12 rev/min ran with windows of one sample
        h = max([step] + [hh for _, _, hh in tm_durations])
        if period < 2.0 * h:
            if speed:
                raise c.fail("schedule", "speed_rpm", f"{speed:g} rev/min turns once in {period:.3g} s, less "
                             f"than two thermo-mechanical steps ({h:g} s): no cycle can be sampled (speeds are in "
                             "rev/min)")
            raise c.fail("schedule.cycle", "period", f"{period:g} s is less than two thermo-mechanical steps "
                         f"({h:g} s): no cycle can be sampled")
    held = tm_durations
    if period and cycles and s.get("kind") == "auto":
        from rotorcosim.master.schedule.auto import AutoSchedule

        # the automatic schedule's TM intervals last at most tm_max (1e308 cycles overflowed the hold's buffers)
        held = [("schedule", s.get("tm_max", AutoSchedule.tm_max), step)]
    if period and cycles and held:
        # the hold averages the last hold_cycles cycles of a TM interval (and sizes its buffers by them): a
        # window longer than every TM interval never fills; 1e12 cycles asked for terabytes (out of memory)
        window, longest = (cycles * 60.0 / speed if speed else cycles * period), max(d for _, d, _ in held)
        if window > longest * (1 + 1e-9):
            raise c.fail("schedule", "hold_cycles", f"{cycles:g} cycles {per} last {window:.4g} s, "
                         f"longer than the longest thermo-mechanical interval ({longest:.4g} s): the hold's window "
                         "could never fill")
    _restart(c, s, raw, period, per, phases)
    for name, spec in comps.items():
        cs = spec.get("step")
        if cs is None:
            continue
        for w, d, h in tm_durations:
            if cs > d * (1 + 1e-12):
                raise c.fail(f"components.{name}", "step",
                             f"{cs} s is longer than the thermo-mechanical interval [{w}] of {d} s "
                             "(the interval would be stretched to one step of this component)")
            m = cs / h
            if m < 1 - 1e-9 or abs(m - round(m)) > 1e-6 * m:
                raise c.fail(f"components.{name}", "step",
                             f"{cs} s is not a whole multiple of the thermo-mechanical step {h} s")
    return sorted({float(step)} | {float(h) for _, _, h in tm_durations})


def check_record_step(c, record_step, steps: list[float]) -> None:
    """``[outputs] record_step`` against the thermo-mechanical ``steps``: a run samples a TM interval every whole
    number of its steps, and the time series file says so (``sampling_interval_s``); a record_step below a step,
    or between two multiples of it, would be recorded at another interval than the file states."""
    if record_step is None or positive(record_step) is not None:
        return
    for h in steps:
        m = record_step / h
        if m < 1 - 1e-9:
            raise c.fail("outputs", "record_step", f"{record_step:g} s is shorter than the thermo-mechanical step "
                         f"{h:g} s: a run samples once a step at most (give {h:g} s or a whole multiple of it)")
        # (a record_step longer than any run, 1e308, samples each interval's start: whole-multiple is moot)
        if m < 2.0 ** 52 and abs(m - round(m)) > 1e-6 * m:
            raise c.fail("outputs", "record_step", f"{record_step:g} s is not a whole multiple of the "
                         f"thermo-mechanical step {h:g} s (the samples would come every "
                         f"{max(1, round(m)) * h:g} s)")


def _restart(c, s: Mapping, raw, period: float | None, per: str, phases: Phases) -> None:
    """restart_cycles against the thermo-mechanical time a restart's ramp has (master/manipulator/restart.py): it starts
    at a TO -> TM change and goes on through the TM intervals that follow, until the next TO interval. A ramp
    longer than the shortest such run never ends: the hand-backs would stay a blend of held and live values for
    the whole run. Under the automatic schedule a TM interval after a TO one lasts at
    most tm_max."""
    speed, cycles = s.get("speed_rpm"), s.get("restart_cycles")
    if not period or not cycles:
        return
    ramp = cycles * 60.0 / speed if speed else cycles * period
    runs, run, after_to = [], 0.0, False
    if isinstance(raw, list) and s.get("kind", "timeline") != "auto":
        for iv in raw:
            d = iv["duration"] if "duration" in iv else iv["cycles"] * period
            if phases.role(iv["phase"]) == HELD:
                if after_to and run > 0.0:
                    runs.append(run)
                run, after_to = 0.0, True
            elif after_to:
                run += d
        if after_to and run > 0.0:
            runs.append(run)
        what = "the shortest run of thermo-mechanical intervals after a thermal-only one"
    elif s.get("kind") == "auto":
        from rotorcosim.master.schedule.auto import AutoSchedule

        runs = [s.get("tm_max", AutoSchedule.tm_max)]
        what = "tm_max, the longest thermo-mechanical interval of the automatic schedule"
    if runs and ramp > min(runs) * (1 + 1e-9):
        raise c.fail("schedule", "restart_cycles", f"{cycles:g} cycles {per} last {ramp:.4g} s, "
                     f"longer than {what} ({min(runs):.4g} s): the restart's ramp would never end (the default is "
                     f"{RESTART_CYCLES:g} cycles)")
