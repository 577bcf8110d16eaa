"""``rotorcosim compare [SCENARIO] [--duration 2] [--unbalance 2850] --out DIR``: the paper's Table 6 experiment.

The same blade-loss system run twice over ``duration``: staggered (3 thermo-mechanical intervals of ``REVOLUTIONS``
(32) rotor revolutions in all, alternating with 2 thermal-only intervals, as the paper's section 4.2) and monolithic
(one thermo-mechanical interval). Writes ``DIR/table6.json``: ``results`` -> key -> {``staggered``,
``monolithic``, ``rel_error_pct``} for bearing #0, ``wall_time_s`` -> {``staggered``, ``monolithic``} and
``speedup`` (their ratio), ``cpu_time_s`` and ``speedup_cpu`` the same in the process's CPU time (on a loaded
machine the wall times also hold the other processes' share, unequally in two runs of 2 and 30 s), ``load_average``
-> {run: [before, after]} the machine's 1-minute load average around each timed run; each run's
own folder (``staggered/``, ``monolithic/``) has its summary, time series and figures.

What is timed: each run's simulation whole, as ``rotorcosim run`` times it (``wall_time_s`` of its summary: set-up
of the intervals, every step, the hold, the recorder writing ``timeseries.h5`` and the result observers), after
an untimed warm-up of the process. The figures are not: they are no part of the integration schemes' cost that
Table 6 compares, and on a 2-core machine the figure workers that ``rotorcosim run`` starts at once (to import
matplotlib while the run goes) took a share of the ~1 s staggered run (speed-up 7.9 with them, 11.9 without, at
1425 N, measured). So both runs go without figures and with nothing else of this process running beside them;
their figures (the same files as ``rotorcosim run`` draws) are drawn from each folder's time series after the
second timed run ends.

The staggered run (paper schedule) is timed ``--timing-runs`` times (default 6), half before and half after the
monolithic run (the first into ``staggered/``, the others into folders removed afterwards, each one's results
checked equal to the first's): ``wall_time_s``/``cpu_time_s`` of the staggered run are the MEAN of those timings
(not the least: that would bias the ratio), ``staggered_runs`` keeps every one. This machine's speed drifts by
+-20 % within seconds: the ~13 s monolithic run averages it, one ~1 s staggered run is one sample of it (the
same level's speed-up spread 11.5-14.0 with one timing on either side); the mean of several timings on either
side of the monolithic run follows the speed the monolithic run saw, and a linear drift cancels.
"""
from __future__ import annotations

import json
import math
import os
import sys
import tempfile
from pathlib import Path

from rotorcosim.master.schedule import budget
from rotorcosim.components.bounded_read import read_json
from rotorcosim.master.api import check_run, draw_figures
from rotorcosim.master.run.figure_pool import FigurePool
from rotorcosim.master.run.outputs import check_dpi, write_json
from rotorcosim.master.run.rundir import LOCK, check_folder, ensure_folder
from rotorcosim.master.schedule import Interval, Timeline, from_spec
from rotorcosim.master.scenario.cycle import constant_period, without_source

from rotorcosim.master.sweep import SweepInterrupted
from rotorcosim.master.sweep.folder import named_os_error
from rotorcosim.master.sweep.lock import FolderLock

from rotorcosim.master.cli.options import add_dpi, add_out, add_scenario
from rotorcosim.master.cli.run import add_edit_arguments, apply_edits, apply_unbalance, execute, parse_set, resolve
from rotorcosim.master import case

#: Table 6's rows (no rub power: there is no rub at 2850 N)
KEYS = ("whirl_amplitude_mm", "transmissibility", "max_contact_load_N", "max_contact_stress_MPa", "drag_power_W",
        "sfd_power_W", "T_inner_race_C", "T_ball_C", "T_outer_race_C", "T_sfd_oil_C")
#: timings of the staggered run (--timing-runs): half before, half after the monolithic run. Measured at 2 850 N on
#: the shared 2-core VM, one ~1 s staggered run cost 0.79-1.12 s of CPU seconds apart (the same work, the same
#: bearing sub-steps); the mean of 6 narrows such a spread up to sqrt(6) = 2.4 times for ~5 s more per comparison
#: (the monolithic run takes ~13 s)
TIMING_RUNS = 6
#: rotor revolutions in all the staggered run's TM intervals (half in the first, which holds the blade loss, a
#: quarter in each of the other two). The paper's interval lengths are "decided on a trial and error basis"
#: (section 3.2); its 50 revolutions cap the speed-up at 2 / 0.1875 s = 10.7 whatever the implementation. Chosen by
#: the largest error of any Table 4 result against the monolithic run at the seven paper levels over 2 s (`python
#: bench/bench_table6_levels.py`; the acceptance is 2 %), measured per count (712 ... 14 252 N):
#:   40: 0.29 0.29 0.30 0.96 0.71 0.80 0.93 %   (largest 0.96)
#:   36: 0.31 0.30 0.33 1.06 0.80 1.06 1.27 %   (1.27)
#:   32: 0.28 0.34 0.50 1.28 0.93 1.00 1.25 %   (1.28)
#:   28: 0.42 0.61 0.67 1.60 1.20 1.03 1.18 %   (1.60)
#:   24: 0.63 0.97 3.70 4.46 1.67 2.13 2.26 %   (4.46: fails)
#: 32 is one step of 4 above the fewest that pass at every level (28), on the plateau that 36 shares; the cap on
#: the speed-up is then 400 000 / 24 000 TM steps = 16.7 (40: 13.4), which the run's fixed costs (~75 ms) and this
#: machine's +-20 % drift otherwise kept from showing >= 12 in every comparison
REVOLUTIONS = 32.0


def add_arguments(p):
    """The options of ``rotorcosim compare`` on the parser ``p``. A scenario whose case offers its own
    comparison (``COMPARE``, master/case.py: the rundown's) takes the options its function names; the Table 6
    defaults are filled in by :func:`run` so that an option given to a comparison it does not belong to is seen."""
    p.add_argument("--duration", type=float, default=None,
                   help="simulated duration [s] (default 2, as the paper; a rundown scenario: the rundown plus 10 "
                        "minutes of windmilling, cases/rundown/compare.py)")
    p.add_argument("--unbalance", type=float, default=None, help="blade-loss force [N] (default 2850; a rundown "
                                                                 "scenario: its own level)")
    add_scenario(p, "blade_loss", note="the levels' base file, F_u = 2850 N as in blade_loss_2850 that run uses; "
                                       "the runs' results carry its name. blade_loss_rundown: staggered against "
                                       "monolithic over a rundown, rundown_compare.json")
    add_out(p, "output folder")
    add_edit_arguments(p)
    p.add_argument("--revolutions", type=float, default=None,
                   help=f"Table 6: rotor revolutions in all thermo-mechanical intervals of the staggered run "
                        f"(default {REVOLUTIONS:g}; the paper: 50)")
    p.add_argument("--bearing", type=int, choices=(0, 5), default=None,
                   help="Table 6: bearing of the table (default 0)")
    p.add_argument("--no-figures", action="store_true",
                   help="skip the PNG figures of the two runs (they are drawn after both timed runs, untimed)")
    add_dpi(p)
    p.add_argument("--quiet", action="store_true", help="no line and progress bar per case")
    p.add_argument("--overwrite", action="store_true", help="replace the results of a previous comparison in --out")
    p.add_argument("--resume", action="store_true",
                   help="continue the interrupted comparison in --out: its complete runs are kept, the others run "
                        "again (same command otherwise)")
    p.add_argument("--schedule", choices=("paper", "auto"), default=None,
                   help="Table 6's staggered run: paper (3 TM + 2 TO intervals, the default) or auto (the "
                        "scenario's automatic schedule over --duration)")
    p.add_argument("--tolerance", type=float, default=None, metavar="PCT",
                   help="with --schedule auto: the largest Table 4 error accepted, percent (see rotorcosim run)")
    p.add_argument("--timing-runs", type=int, default=None, metavar="N",
                   help=f"Table 6: timings of the staggered run (paper schedule, monolithic run made here), half "
                        f"before and half after the monolithic run; its time in table6.json (wall_time_s, "
                        f"cpu_time_s) is their mean, each one kept in staggered_runs (default {TIMING_RUNS}; 1: a "
                        f"single timing)")
    p.add_argument("--monolithic", default=None, metavar="DIR",
                   help="Table 6: reuse the monolithic run in DIR (a previous comparison's monolithic/ folder of "
                        "the same scenario, unbalance and duration) instead of running it again")


def staggered_timeline(duration: float, step: float, thermal_step: float, speed_rpm: float,
                       revolutions: float = REVOLUTIONS, quantum: float = 1e-3) -> Timeline:
    """3 TM intervals with at most ``revolutions`` in all (the first, holding the blade loss, gets half) and 2 TO
    intervals sharing the rest of ``duration`` equally. TM lengths are whole multiples of ``quantum`` (the
    slowest component step inside TM intervals), rounded down."""
    tm_total = revolutions * 60.0 / speed_rpm
    if tm_total >= duration:
        raise ValueError(f"{revolutions} revolutions ({tm_total:.4g} s) do not fit in {duration} s")
    tm = [math.floor(f * tm_total / quantum + 1e-9) * quantum for f in (0.5, 0.25, 0.25)]
    if min(tm) <= 0.0:
        raise ValueError(f"{revolutions} revolutions are too few for 3 thermo-mechanical intervals of whole "
                         f"{quantum:g} s steps")
    to = 0.5 * (duration - sum(tm))
    ts = min(thermal_step, to)
    return Timeline([Interval("TM", tm[0], step), Interval("TO", to, ts), Interval("TM", tm[1], step),
                     Interval("TO", to, ts), Interval("TM", tm[2], step)])


def _plan(kind: str, scenario: str, unbalance: float, schedule: str, tolerance, duration: float, revolutions: float):
    """(scenario, schedule) of the ``kind`` run ("staggered" or "monolithic")."""
    sc = resolve(scenario)
    apply_unbalance(sc, unbalance)
    s = sc.schedule
    if kind == "staggered" and schedule == "auto":
        spec = {k: v for k, v in without_source(s).items() if k != "intervals"}
        spec["kind"] = "auto"
        if tolerance is not None:
            spec["tolerance"] = tolerance
        sch = from_spec(spec, duration, cycle=constant_period(s))
    elif kind == "staggered":
        sch = staggered_timeline(duration, float(s.get("step", 1e-5)), float(s.get("thermal_step", 0.1)),
                                 float(s["speed_rpm"]), revolutions, _quantum(sc))
    else:
        sch = Timeline([Interval("TM", duration, float(s.get("step", 1e-5)))])
    sc.name = f"{sc.name}_{kind}"
    return sc, sch


def _warm_up(scenario: str, out: Path, quantum: float) -> None:
    """A few milliseconds of the system through every path the timed runs take (a thermo-mechanical interval, a
    thermal-only one with the hold, a restart; the recorder's file and the result observers), untimed, so that
    neither timed run pays the one-off costs of the process (compiled kernels loaded, model matrices built and
    cached, first calls). Measured: the staggered run, timed first, paid ~0.3-0.6 s of CPU (of ~2 s) for what a
    1 ms warm-up without a thermal-only interval, recorder or results left to it."""
    sc = resolve(scenario)
    h = float(sc.schedule.get("step", 1e-5))
    tm = 2 * quantum
    with tempfile.TemporaryDirectory(dir=out) as tmp:
        execute(sc, Path(tmp), figures=False, checkpoint_every=None,
                schedule=Timeline([Interval("TM", tm, h), Interval("TO", 0.1, 0.05), Interval("TM", tm, h)]))


def compare(out: Path, duration=2.0, unbalance=2850.0, scenario="blade_loss", revolutions=REVOLUTIONS, bearing=0,
            quiet=True, figures=True, overwrite=False, schedule="paper", tolerance=None, monolithic=None,
            timing_runs=None, dpi=None, resume=False) -> dict:
    """Run the comparison into the folder ``out`` and return the table written to ``out/table6.json`` (see the
    module's docstring).

    ``duration`` [s] simulated; ``unbalance`` [N]; ``scenario`` (a name or file); ``revolutions``: rotor
    revolutions [-] of the staggered run's TM intervals in all; ``bearing``: 0 or 5, the table's; ``quiet``: no
    progress; ``figures``: draw each run's figures; ``overwrite``: replace a previous comparison in ``out``;
    ``schedule``: "paper" or "auto" for the staggered run, ``tolerance`` [%] for "auto"; ``monolithic``: a
    folder with a monolithic run to reuse; ``timing_runs``: how often the staggered run is timed (default 6);
    ``dpi``: the figures' resolution (None: the default); ``resume``: continue the comparison in ``out``: its
    runs that are complete are kept (checked to be this comparison's), the others run again.

    Under faults: one comparison at a time writes into ``out`` (a lock, ``.rotorcosim.lock``, removed at the
    end); Ctrl-C or SIGTERM stops the run going on (its folder says ``interrupted``), keeps the complete ones and
    raises :class:`~rotorcosim.master.sweep.SweepInterrupted` saying which; a full disk stops it with the run's
    own error."""
    dpi = check_dpi(dpi)
    if not (duration > 0 and duration < float("inf")):
        raise ValueError(f"--duration must be a positive number of seconds, got {duration}")
    if not (revolutions > 0 and revolutions < float("inf")):
        raise ValueError(f"--revolutions must be a positive number of rotor revolutions, got {revolutions}")
    if timing_runs is not None and (isinstance(timing_runs, bool) or not isinstance(timing_runs, int)
                                    or timing_runs < 1):
        raise ValueError(f"--timing-runs must be a whole number of timings >= 1, got {timing_runs!r}")
    if resume and (overwrite or monolithic is not None):
        raise ValueError("--resume continues the comparison in --out: it excludes --overwrite and --monolithic")
    if timing_runs is not None and (schedule != "paper" or monolithic is not None):
        raise ValueError("--timing-runs applies to the paper schedule with the monolithic run made here (the "
                         "staggered timings bracket it); the other comparisons time the staggered run once")
    out = check_folder(out)   # made only once every input is checked (ensure_folder, below)
    if schedule not in ("paper", "auto"):
        raise ValueError(f"--schedule must be 'paper' or 'auto', got {schedule!r}")
    if tolerance is not None and (schedule != "auto" or not 0.0 < tolerance < float("inf")):
        raise ValueError("--tolerance is a positive percentage and applies to --schedule auto only")
    runs = {}
    sc = resolve(scenario)
    if sc.extra.get("results", {}).get("kind") != "blade_loss":  # before any run: Table 6 is bearing results
        raise ValueError(f"compare: scenario {sc.name!r} has no bearing results to compare ([results] kind = "
                         "\"blade_loss\" in the blade-loss scenarios)")
    kinds_run = [k for k in ("staggered", "monolithic") if not (k == "monolithic" and monolithic is not None)]
    held = [k for k in kinds_run if (out / k).is_dir() and any(p.name != LOCK for p in (out / k).iterdir())]
    if held and not overwrite and not resume:  # before the warm-up
        raise ValueError(f"--out {out} already holds a comparison ({', '.join(held)}): results are never mixed; "
                         "give --overwrite to replace it, --resume to continue it, or another folder")
    if resume and not held:
        raise ValueError(f"--resume: {out} holds no comparison to continue")
    if monolithic is not None:
        mono = resolve(scenario)
        apply_unbalance(mono, unbalance)
        runs["monolithic"] = _reuse(Path(monolithic), unbalance, duration, f"{mono.name}_monolithic", bearing)
    kinds = ("staggered", "monolithic")
    plans = {kind: _plan(kind, scenario, unbalance, schedule, tolerance, duration, revolutions)
             for kind in kinds if kind not in runs}
    # a run's own checks (duration, budget) for both, before anything runs; then the comparison's whole budget:
    # the staggered run is timed --timing-runs times
    ests = {kind: check_run(sc_k, sch) for kind, (sc_k, sch) in plans.items()}
    kept = {kind: _kept(out / kind, plans[kind][0].name, unbalance, duration) for kind in held} if resume else {}
    kept = {k: v for k, v in kept.items() if v is not None}
    # a kept monolithic run cannot be bracketed by the staggered timings: timed once, as with --monolithic
    n_timed = 1 if monolithic is not None or "monolithic" in kept or schedule != "paper" else timing_runs or TIMING_RUNS
    total = sum(e["wall_s"] * (n_timed if kind == "staggered" else 1) for kind, e in ests.items())
    if total > budget.LIMIT_S:
        raise budget.BudgetError(f"this comparison would take about {budget.hms(total)} of wall time ("
                                 f"{n_timed} timing(s) of the staggered run, estimated "
                                 f"{budget.hms(ests['staggered']['wall_s'])} each), above the "
                                 f"{budget.hms(budget.LIMIT_S)} limit: give fewer --timing-runs or a shorter "
                                 "--duration")
    ensure_folder(out)  # every input checked: only now is a folder made (the runs' messages, rundir.py)
    with FolderLock(out, "comparison"):
        try:
            return _compare(out, duration, unbalance, scenario, revolutions, bearing, quiet, figures, overwrite,
                            schedule, tolerance, monolithic, timing_runs, resume, sc, runs, kept, plans, dpi)
        except KeyboardInterrupt:
            said = [f"{k} complete (kept in {out / k})" if _kept(out / k, None, None, None) is not None
                    else f"{k} not complete" for k in ("staggered", "monolithic")]
            raise SweepInterrupted(f"interrupted: {', '.join(said)}; continue with --resume") from None


def _compare(out, duration, unbalance, scenario, revolutions, bearing, quiet, figures, overwrite, schedule,
             tolerance, monolithic, timing_runs, resume, sc, runs, kept, plans, dpi=None) -> dict:
    """The comparison's runs and table, in its locked folder (:func:`compare` has checked every input)."""
    kinds = ("staggered", "monolithic")
    # --overwrite replaces the runs: the previous table goes now, so that an interrupted comparison never leaves
    # it beside runs it does not describe
    (out / "table6.json").unlink(missing_ok=True)
    _warm_up(scenario, out, _quantum(sc))
    scenarios, loads = {}, {}
    # the staggered run's timings (its own, then the repeats): half of them before the monolithic run
    repeats = 1 if monolithic is not None or "monolithic" in kept or schedule != "paper" else timing_runs or TIMING_RUNS
    before = (repeats + 1) // 2
    timings = []
    for i, kind in enumerate(kinds, 1):
        if kind in runs and kind not in kept:
            continue
        sc, sch = plans[kind]
        # figures drawn from the time series file after both timed runs; a run recorded otherwise (CSV, nothing
        # recorded) draws its own in process, after its timing and without workers (api.simulate)
        later = figures and sc.outputs.get("format", "h5") == "h5" and bool(sc.outputs.get("record"))
        if later:
            scenarios[kind] = sc
        if not quiet and kind not in kept:  # a line per case, and its own progress bar (time left from its step cost)
            what = f"{len(sch.intervals)} interval(s)" if hasattr(sch, "intervals") else "automatic schedule"
            print(f"[{i}/{len(kinds)}] {kind}: {sch.duration:g} s simulated, {what}",
                  file=sys.stderr, flush=True)
        # not checkpointed: an interrupted run is run again whole (--resume keeps complete runs only), and a save of
        # the whole state at every interval end (0.2 s each, measured) is no part of the integration schemes' cost
        # the table compares; no figures (and so no figure workers) during a timed run: drawn below, after both
        load = _load()
        if kind in kept:  # --resume: a complete run of this comparison, kept
            runs[kind], loads[kind] = kept[kind], [None, None]
            if not quiet:
                print(f"[{i}/{len(kinds)}] {kind}: complete in {out / kind}, kept", file=sys.stderr, flush=True)
        else:
            runs[kind] = execute(sc, out / kind, figures=figures and not later, quiet=quiet, schedule=sch,
                                 overwrite=overwrite or resume, checkpoint_every=None, dpi=dpi)
            loads[kind] = [load, _load()]
        if not quiet and kind not in kept:
            print(f"[{i}/{len(kinds)}] {kind}: done in {runs[kind]['wall_time_s']:.3g} s", file=sys.stderr, flush=True)
        if kind == "staggered":
            again = (sc, sch)
            timings.append((runs[kind], loads[kind]))
            timings += _time_again(out, sc, sch, before - 1, len(timings), repeats, quiet)
    repeat = None
    if repeats > 1:
        timings += _time_again(out, *again, repeats - before, len(timings), repeats, quiet)
        repeat = _timings(timings, before)
    if scenarios:
        _draw(out, scenarios, quiet, dpi)
    results = {}
    for key in KEYS:
        a = runs["staggered"]["bearings"][str(bearing)][key]
        b = runs["monolithic"]["bearings"][str(bearing)][key]
        err = None if b in (None, 0) or a is None else 100.0 * abs(a - b) / abs(b)
        results[key] = {"staggered": a, "monolithic": b, "rel_error_pct": err}
    wall = {k: runs[k]["wall_time_s"] for k in runs}
    cpu = {k: runs[k].get("cpu_time_s") for k in runs}
    if repeat is not None:  # the staggered run's time: the mean of its timings before and after the monolithic one
        wall["staggered"] = sum(repeat["wall_time_s"]) / len(repeat["wall_time_s"])
        if None not in repeat["cpu_time_s"]:
            cpu["staggered"] = sum(repeat["cpu_time_s"]) / len(repeat["cpu_time_s"])
    table = {"bearing": bearing, "duration_s": duration, "unbalance_N": unbalance, "revolutions_tm": revolutions,
             "results": results, "wall_time_s": wall, "speedup": wall["monolithic"] / wall["staggered"],
             # the machine's 1-minute load average before and after each timed run: on a shared machine the wall
             # times hold the other processes' share (and the CPU times some of it), so a reader can judge them
             "load_average": loads,
             "cpu_time_s": cpu, "speedup_cpu": (cpu["monolithic"] / cpu["staggered"]
                                                if cpu["monolithic"] and cpu["staggered"] else None),
             "largest_error_pct": max((v["rel_error_pct"] or 0.0) for v in results.values()),
             # each timing of the staggered run (the first ``before_monolithic`` before the monolithic run, the others
             # after it) and whether they all gave the same results (they must: a run is deterministic); None where
             # it ran once
             "staggered_runs": repeat,
             "schedule": schedule, "tolerance_pct": tolerance, "hold": runs["staggered"].get("hold"),
             "monolithic_reused_from": str(monolithic) if monolithic is not None else None,
             "timeline_staggered": runs["staggered"]["timeline"]}
    try:
        write_json(out / "table6.json", table)
    except OSError as exc:  # the runs are complete and kept: a --resume writes the table
        (out / "table6.json.part").unlink(missing_ok=True)
        raise named_os_error(exc, out, "writing table6.json") from None
    return table


def _time_again(out: Path, sc, sch, count: int, done: int, total: int, quiet: bool) -> list:
    """``count`` more timings of the staggered run, each into a folder removed afterwards: [(summary, [load before,
    after])]. The VM's speed drifts by +-20 % within seconds (the same run measured 0.61-1.39 s in one hour on a
    quiet machine), so one timing of a ~1 s run against one of a ~13 s run made the speed-up a single sample
    spread 9.6-14.4 at one level: the mean of several timings on either side of the monolithic run follows the
    machine's speed during the monolithic run (a linear drift cancels)."""
    out_runs = []
    for j in range(count):
        if not quiet:
            print(f"staggered again: timing {done + j + 1} of {total}", file=sys.stderr, flush=True)
        load = _load()
        with tempfile.TemporaryDirectory(dir=out) as tmp:
            summary = execute(sc, Path(tmp) / "staggered", figures=False, quiet=quiet, schedule=sch,
                              checkpoint_every=None)
        out_runs.append((summary, [load, _load()]))
    return out_runs


#: what must be equal in every timing of the staggered run (a run is deterministic): its Table 4 results, what
#: the hold measured, the intervals it ran and the components' step counts
SAME = ("bearings", "hold", "timeline", "component_steps")


def _same(a: dict, b: dict) -> bool:
    """Equal to the bit in every SAME entry (as JSON text: Python writes a float's shortest exact form, and a NaN
    equals itself there)."""
    return all(json.dumps(a.get(k), sort_keys=True) == json.dumps(b.get(k), sort_keys=True) for k in SAME)


def _timings(timings: list, before: int) -> dict:
    """table6.json's ``staggered_runs`` from [(summary, [load before, after])], the first the run reported."""
    first = timings[0][0]
    same = all(_same(s, first) for s, _ in timings[1:])
    if not same:
        print("compare: WARNING: the staggered run gave other results in another timing (a run must be "
              "deterministic); the first run's are reported", file=sys.stderr, flush=True)
    repeats = [load for _, load in timings[1:]]
    return {"wall_time_s": [s["wall_time_s"] for s, _ in timings],
            "cpu_time_s": [s.get("cpu_time_s") for s, _ in timings],
            "before_monolithic": before,
            # the 1-minute load before the first repeated timing and after the last (each: load_average_each)
            "load_average": [repeats[0][0], repeats[-1][1]],
            "load_average_each": [load for _, load in timings],
            "identical_results": same}


def _draw(out: Path, scenarios: dict, quiet: bool, dpi: int | None = None) -> None:
    """The figures of the runs made here (not of a reused monolithic run), after the timing: a figure pool per
    run, all started at once so that the second run's workers import matplotlib while the first run's draw."""
    pools = {kind: FigurePool() for kind in scenarios}
    try:
        for kind, sc in scenarios.items():
            names = draw_figures(sc, out / kind, pool=pools[kind], dpi=dpi)
            if not quiet:
                print(f"{kind}: {len(names)} figures drawn", file=sys.stderr, flush=True)
    finally:
        for p in pools.values():
            p.close()


def _load() -> float | None:
    try:
        return os.getloadavg()[0]
    except (OSError, AttributeError):  # not available on this system
        return None


def _quantum(sc) -> float:
    """The slowest component step inside TM intervals: TM interval lengths are whole multiples of it."""
    return max([c.step for c in sc.components.values() if c.step] + [float(sc.schedule.get("step", 1e-5))])


def _kept(folder: Path, name: str | None, unbalance: float | None, duration: float | None) -> dict | None:
    """The summary of a complete run in ``folder``, else None (absent, damaged, interrupted, failed); with
    ``name``, a complete run of another scenario, unbalance or duration is an error (--resume continues the same
    comparison)."""
    try:
        summary = read_json(folder / "summary.json", "summary")
    except (OSError, ValueError):
        return None
    if not isinstance(summary, dict) or summary.get("status") != "complete":
        return None
    if name is not None:
        ran = (summary.get("scenario"), summary.get("unbalance_N"), summary.get("t_end_s"))
        if ran[0] != name or not _close(ran[1], unbalance) or not _close(ran[2], duration):
            raise ValueError(f"--resume: {folder} holds a run of {ran[0]!r} at {ran[1]} N over {ran[2]} s, not "
                             f"{name!r} at {unbalance} N over {duration} s: give the same command, or another folder")
    return summary


def _close(a, b) -> bool:
    return isinstance(a, (int, float)) and abs(float(a) - b) <= 1e-9 * max(1.0, abs(b))


def _reuse(folder: Path, unbalance: float, duration: float, name: str | None = None, bearing: int = 0) -> dict:
    """A previous monolithic run's summary, checked to be the one this comparison needs (``name``: the
    monolithic run's scenario name this comparison would give it)."""
    f = folder / "summary.json"
    try:
        summary = read_json(f, "summary")
    except (OSError, ValueError) as exc:
        raise ValueError(f"--monolithic {folder}: no readable summary.json ({exc})") from None
    if not isinstance(summary, dict):
        raise ValueError(f"--monolithic {f}: not a run's summary (a JSON {type(summary).__name__})")
    for key in ("t_end_s", "unbalance_N", "wall_time_s"):
        if not isinstance(summary.get(key), (int, float)) or isinstance(summary.get(key), bool):
            raise ValueError(f"--monolithic {f}: {key} is {summary.get(key)!r}, not a number (damaged summary)")
    res = (summary.get("bearings") or {}).get(str(bearing)) if isinstance(summary.get("bearings"), dict) else None
    if not isinstance(res, dict) or any(not isinstance(res.get(k), (int, float, type(None))) for k in KEYS):
        raise ValueError(f"--monolithic {f}: no results of bearing #{bearing} (damaged summary, or not a "
                         "blade-loss run)")
    tl = summary.get("timeline") or []
    if summary.get("status", "complete") != "complete" or not isinstance(tl, list) or len(tl) != 1 \
            or not isinstance(tl[0], dict) or tl[0].get("phase") != "TM":
        raise ValueError(f"--monolithic {f}: not a complete monolithic run (one thermo-mechanical interval)")
    if abs(float(summary.get("t_end_s", -1.0)) - duration) > 1e-9 * max(1.0, duration):
        raise ValueError(f"--monolithic {f}: it simulated {summary.get('t_end_s')} s, not --duration {duration} s")
    if summary.get("unbalance_N") is None or abs(float(summary["unbalance_N"]) - unbalance) > 1e-9 * max(1.0, unbalance):
        raise ValueError(f"--monolithic {f}: its unbalance is {summary.get('unbalance_N')} N, not {unbalance} N")
    if name is not None and summary.get("scenario") != name:
        raise ValueError(f"--monolithic {f}: a run of scenario {summary.get('scenario')!r}, not {name!r}")
    return summary


def run(args) -> int:
    """Run the command ``args`` (parsed): a scenario whose case offers its own comparison (``COMPARE``) goes to
    it with ``--set`` / ``--swap`` / ``--unbalance`` applied; otherwise Table 6, which prints the speed-up and the
    largest error. Returns 0."""
    sc = resolve(args.scenario)
    own = case.attribute(sc.extra.get("results", {}).get("kind"), "COMPARE")
    if own is not None:
        sc = apply_edits(sc, args)
        if args.unbalance is not None:
            apply_unbalance(sc, args.unbalance, [parse_set(text)[0] for text in args.set_values or []])
        return int(own(args, sc) or 0)
    if args.set_values or args.swap:
        raise ValueError("compare: --set / --swap apply to a case's own comparison (blade_loss_rundown); Table 6 "
                         "compares the scenario as it is (give --unbalance for its level)")
    t = compare(Path(args.out), 2.0 if args.duration is None else args.duration,
                2850.0 if args.unbalance is None else args.unbalance, args.scenario,
                REVOLUTIONS if args.revolutions is None else args.revolutions,
                0 if args.bearing is None else args.bearing,
                quiet=args.quiet, figures=not args.no_figures, overwrite=args.overwrite,
                schedule=args.schedule or "paper", tolerance=args.tolerance, monolithic=args.monolithic,
                timing_runs=args.timing_runs, resume=args.resume, dpi=args.dpi)
    est = (t.get("hold") or {}).get("estimated_error_pct")
    cpu = f" (CPU time {t['speedup_cpu']:.1f})" if t.get("speedup_cpu") else ""
    print(f"Table 6 (bearing #{t['bearing']}, {t['duration_s']} s, {t['schedule']} schedule): speed-up "
          f"{t['speedup']:.1f}{cpu}, largest relative error {t['largest_error_pct']:.2f} %"
          + (f" (estimated by the staggered run: {est:.2f} %)" if est is not None else "") + f"; {args.out}/table6.json")
    return 0
