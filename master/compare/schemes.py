"""Staggered against monolithic for any scenario: one scenario run twice into one folder, timed, and tabulated.

:func:`compare_schemes` runs the scenario ``sc`` under a staggered schedule (the case chooses it: a timeline of
coupled and held intervals, or an automatic schedule) and under a monolithic one (one coupled interval over the
same simulated time), each into its own folder (``staggered/``, ``monolithic/``: summary, time series,
figures), and writes the table the caller's ``tabulate`` makes of the two summaries and their timings into
``out/<table_name>``. What a case compares (which results, which tolerance) is the case's; what this module
does is the same for every scenario:

- **Timing.** Each run is timed as ``rotorcosim run`` times it (``wall_time_s``, ``cpu_time_s`` of its summary:
  the simulation whole, no figures), after an untimed warm-up of the process (a few milliseconds through a
  coupled interval, a held one and a restart: kernels loaded, model matrices built, first calls). No figure
  worker runs beside a timed run: the figures are drawn from each folder's time series after both runs.
  ``timing_runs`` > 1 times the staggered run that often, half before and half after the monolithic run (the
  first into ``staggered/``, the others into folders removed afterwards, each checked to give the same
  results): its time is the mean, so that the speed drift of a shared machine cancels to first order.
- **The timings** handed to ``tabulate``: ``wall_time_s`` and ``cpu_time_s`` of each run, ``speedup`` (monolithic
  over staggered wall time), ``speedup_cpu`` (the same in CPU time), ``load_average`` (the machine's 1-minute
  load before and after each run), ``staggered_runs`` (each timing of the staggered run, or None).
- **Under faults.** One comparison at a time writes into ``out`` (a lock, ``.rotorcosim.lock``); a folder already
  holding a comparison is refused unless ``overwrite`` (replace) or ``resume`` (keep its complete runs, checked
  to be this comparison's: the same scenario, ``level``, duration and edits, and make the others); Ctrl-C or
  SIGTERM stops the run going on (its folder says ``interrupted``), keeps the complete ones and raises
  :class:`~rotorcosim.master.sweep.SweepInterrupted` saying which; a failed run raises its own error and keeps
  what it recorded; a full disk at the table names the folder and says to continue with ``--resume``. Every
  input is checked before a folder is made or anything runs (each run's schedule and budget too).
- **Reuse.** ``reuse``: the folder of a previous monolithic run of the same scenario, level and duration, used
  instead of running it again (then the staggered run is timed once).

Example (a toy of two components; any scenario works the same way)::

    from rotorcosim.master.api import load_scenario
    from rotorcosim.master.compare import compare_schemes, pair
    from rotorcosim.master.scenario.build import schedule_of
    sc = load_scenario("toy_thermomechanical")
    stag, mono = schedule_of(sc, "auto", 3.0), schedule_of(sc, "monolithic", 3.0)
    t = compare_schemes(sc, "cmp", stag, mono, table_name="compare.json",
                        tabulate=lambda runs, timing: {"speedup": timing["speedup"]})
"""
from __future__ import annotations

import contextlib
import copy
import io
import json
import os
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path
from typing import Callable

from rotorcosim.components.bounded_read import read_json
from rotorcosim.master.api import check_run, draw_figures, simulate
from rotorcosim.master.core.phases import Phases
from rotorcosim.master.run.figure_pool import FigurePool
from rotorcosim.master.run.outputs import check_dpi, write_json
from rotorcosim.master.run.rundir import LOCK, check_folder, ensure_folder
from rotorcosim.master.scenario.build import Scenario
from rotorcosim.master.schedule import Interval, Timeline, budget
from rotorcosim.master.sweep import SweepInterrupted
from rotorcosim.master.sweep.folder import named_os_error
from rotorcosim.master.sweep.lock import FolderLock

#: the prefix of the untimed warm-up's and the repeated timings' scratch folders inside --out (removed as they end;
#: one a killed comparison left is its own, not another command's file)
SCRATCH = ".scratch-"

#: the two runs, in the order they run, and their folders
KINDS = ("staggered", "monolithic")
#: what must be equal in every timing of the staggered run (a run is deterministic): what the hold measured, the
#: intervals it ran and the components' step counts; a case adds its results' keys (``same``)
SAME = ("hold", "timeline", "component_steps")


@dataclass(frozen=True)
class LevelValue:
    """The level a comparison is made at, as the runs' summaries record it: ``key`` in summary.json (e.g.
    the case's level key), its ``value`` and ``unit`` (for messages). A kept or reused run at another level is
    refused."""

    key: str
    value: float
    unit: str = ""

    def of(self, summary: dict) -> str:
        """`` at VALUE UNIT`` of ``summary``'s level, for a message."""
        return f" at {summary.get(self.key)} {self.unit}".rstrip()

    def says(self) -> str:
        """`` at VALUE UNIT`` of this level, for a message."""
        return f" at {self.value} {self.unit}".rstrip()

    def holds(self, summary: dict) -> bool:
        """Whether ``summary`` was run at this level."""
        return _close(summary.get(self.key), self.value)


def quantum(sc: Scenario) -> float:
    """The slowest component step inside coupled intervals [s]: a coupled interval's length is a whole multiple
    of it."""
    return max([c.step for c in sc.components.values() if c.step] + [float(sc.schedule.get("step", 1e-5))])


def load_average() -> float | None:
    """The machine's 1-minute load average (None where the system does not give it)."""
    try:
        return os.getloadavg()[0]
    except (OSError, AttributeError):
        return None


def draw(out: Path, scenarios: dict, quiet: bool = True, dpi: float | None = None) -> None:
    """The figures of the runs ``scenarios`` (kind -> scenario) in ``out/<kind>``, drawn from their time series:
    a figure pool per run, all started at once so that the second run's workers import matplotlib while the
    first run's draw."""
    pools = {kind: FigurePool() for kind in scenarios}
    try:
        for kind, sc in scenarios.items():
            names = draw_figures(sc, out / kind, pool=pools[kind], dpi=dpi)
            if not quiet:
                print(f"{kind}: {len(names)} figures drawn", file=sys.stderr, flush=True)
    finally:
        for p in pools.values():
            p.close()


def edits_of(edits) -> list | None:
    """A scenario's edits (``--set`` / ``--swap`` / the case's level; run/provenance.py) without where they came from,
    as JSON: what makes two runs of one scenario the same run."""
    if not isinstance(edits, list):
        return None
    return json.loads(json.dumps([{k: v for k, v in dict(e).items() if k != "origin"} for e in edits]))


def kept_run(folder: Path, name: str | None = None, duration: float | None = None, level: LevelValue | None = None,
             edits: list | None = None) -> dict | None:
    """The summary of a complete run in ``folder``, else None (absent, damaged, interrupted, failed). With
    ``name``, a complete run of another scenario, ``level``, ``duration`` or ``edits`` (a scenario's edits) is an
    error: ``--resume`` continues the same comparison."""
    try:
        summary = read_json(folder / "summary.json", "summary")
    except (OSError, ValueError):
        return None
    if not isinstance(summary, dict) or summary.get("status") != "complete":
        return None
    if name is None:
        return summary
    at = level.of(summary) if level is not None else ""
    if summary.get("scenario") != name or (level is not None and not level.holds(summary)) \
            or not _close(summary.get("t_end_s"), duration):
        said = level.says() if level is not None else ""
        raise ValueError(f"--resume: {folder} holds a run of {summary.get('scenario')!r}{at} over "
                         f"{summary.get('t_end_s')} s, not {name!r}{said} over {duration} s: give the same command, "
                         "or another folder")
    ran = (summary.get("provenance") or {}).get("edits")
    if edits is not None and edits_of(ran) != edits_of(edits):
        raise ValueError(f"--resume: {folder} holds a run made with other edits (--set/--swap/the level: {ran}): "
                         "give the same command, or another folder")
    return summary


def reused_monolithic(folder: Path, duration: float, name: str | None = None, level: LevelValue | None = None,
                      check: Callable[[dict, Path], None] | None = None, coupled: str = Phases().coupled) -> dict:
    """A previous monolithic run's summary in ``folder``, checked to be the one a comparison needs: complete,
    one ``coupled`` interval over ``duration`` [s], at ``level``, of the scenario ``name`` (the monolithic run's
    name this comparison would give it); ``check(summary, file)`` raises ValueError for what the case needs
    besides (its results)."""
    f = folder / "summary.json"
    try:
        summary = read_json(f, "summary")
    except (OSError, ValueError) as exc:
        raise ValueError(f"--monolithic {folder}: no readable summary.json ({exc})") from None
    if not isinstance(summary, dict):
        raise ValueError(f"--monolithic {f}: not a run's summary (a JSON {type(summary).__name__})")
    for key in ("t_end_s", *((level.key,) if level is not None else ()), "wall_time_s"):
        if not isinstance(summary.get(key), (int, float)) or isinstance(summary.get(key), bool):
            raise ValueError(f"--monolithic {f}: {key} is {summary.get(key)!r}, not a number (damaged summary)")
    if check is not None:
        check(summary, f)
    tl = summary.get("timeline") or []
    if summary.get("status", "complete") != "complete" or not isinstance(tl, list) or len(tl) != 1 \
            or not isinstance(tl[0], dict) or tl[0].get("phase") != coupled:
        raise ValueError(f"--monolithic {f}: not a complete monolithic run (one {coupled} interval)")
    if not _close(summary.get("t_end_s"), duration):
        raise ValueError(f"--monolithic {f}: it simulated {summary.get('t_end_s')} s, not --duration {duration} s")
    if level is not None and not level.holds(summary):
        raise ValueError(f"--monolithic {f}: its level {level.key} is {summary.get(level.key)} {level.unit}, not "
                         f"{level.value} {level.unit}")
    if name is not None and summary.get("scenario") != name:
        raise ValueError(f"--monolithic {f}: a run of scenario {summary.get('scenario')!r}, not {name!r}")
    return summary


def compare_schemes(sc: Scenario, out: str | Path, staggered, monolithic, *,
                    tabulate: Callable[[dict, dict], dict], table_name: str, quiet: bool = True,
                    figures: bool = True, overwrite: bool = False, resume: bool = False, dpi: float | None = None,
                    timing_runs: int = 1, reuse: str | Path | None = None,
                    reuse_check: Callable[[dict, Path], None] | None = None, level: LevelValue | None = None,
                    check_edits: bool = True, warm_up: bool = True, same: tuple = ()) -> dict:
    """Run ``sc`` under the schedule ``staggered`` and under ``monolithic`` (Timeline, AutoSchedule or
    Monolithic objects over the same simulated time) into ``out``; write ``tabulate(runs, timing)`` (``runs``:
    kind -> summary; ``timing``: the module's timings) to ``out/<table_name>`` and return it. The runs are named
    ``<sc.name>_staggered`` and ``<sc.name>_monolithic``.

    ``quiet``: no progress lines; ``figures``: draw each run's figures (after both runs, untimed); ``overwrite``:
    replace a previous comparison in ``out``; ``resume``: keep its complete runs (checked to be this
    comparison's: scenario, ``level``, duration, and with ``check_edits`` the scenario's edits) and make the
    others (a kept run without its figures gets them); ``dpi``: the figures' resolution; ``timing_runs``: timings of the staggered run, half before and
    half after the monolithic one, each checked to give the same summary entries :data:`SAME` and ``same`` (the
    case's results); ``reuse``: a previous monolithic run's folder (:func:`reused_monolithic`,
    with the case's ``reuse_check``); ``warm_up``: a few untimed milliseconds first.

    Raises ValueError for a bad input (before anything runs), budget.BudgetError for a comparison above the
    time limit, :class:`~rotorcosim.master.sweep.SweepInterrupted` on Ctrl-C / SIGTERM, and a run's own error
    when it fails (its folder keeps what it recorded)."""
    dpi = check_dpi(dpi)
    if resume and (overwrite or reuse is not None):
        raise ValueError("--resume continues the comparison in --out: it excludes --overwrite and --monolithic")
    if isinstance(timing_runs, bool) or not isinstance(timing_runs, int) or timing_runs < 1:
        raise ValueError(f"--timing-runs must be a whole number of timings >= 1, got {timing_runs!r}")
    out = check_folder(out)   # made only once every input is checked (ensure_folder, below)
    runs = {}
    kinds_run = [k for k in KINDS if not (k == "monolithic" and reuse is not None)]
    held = [k for k in kinds_run if (out / k).is_dir() and any(p.name != LOCK for p in (out / k).iterdir())]
    # a comparison's folder holds its two runs and its table only: another command's files beside them (a run's
    # summary.json) made a folder of both, whatever the options
    ours = {*KINDS, table_name, table_name + ".part", LOCK}
    foreign = sorted(p.name for p in out.iterdir() if p.name not in ours and not p.name.startswith(SCRATCH)) \
        if out.is_dir() else []
    if foreign:
        raise ValueError(f"--out {out} holds files that are not a comparison's ({', '.join(foreign[:5])}"
                         f"{', ...' if len(foreign) > 5 else ''}): results are never mixed; choose another folder")
    if (out / table_name).is_file() and not held:
        held = [table_name]   # a table without its runs is a previous comparison's too: not dropped unasked
    if held and not overwrite and not resume:  # before the warm-up
        raise ValueError(f"--out {out} already holds a comparison ({', '.join(held)}): results are never mixed; "
                         "give --overwrite to replace it, --resume to continue it, or another folder")
    if resume and not held:
        raise ValueError(f"--resume: {out} holds no comparison to continue")
    duration = float(monolithic.duration)
    coupled = Phases.from_spec(sc.schedule.get("phases")).coupled
    if reuse is not None:
        runs["monolithic"] = reused_monolithic(Path(reuse), duration, f"{sc.name}_monolithic", level, reuse_check,
                                               coupled)
    plans = {}
    for kind, sch in zip(KINDS, (staggered, monolithic)):
        if kind not in runs:
            s = copy.deepcopy(sc)
            s.name = f"{sc.name}_{kind}"
            plans[kind] = (s, sch)
    # each run's own checks (schedule, budget) before anything runs; then the comparison's whole budget
    ests = {kind: check_run(s, sch) for kind, (s, sch) in plans.items()}
    edits = sc.edits if check_edits else None
    kept = {kind: kept_run(out / kind, plans[kind][0].name, duration, level, edits) for kind in held
            if kind in plans} if resume else {}
    kept = {k: v for k, v in kept.items() if v is not None}
    # a kept or reused monolithic run cannot be bracketed by the staggered timings: timed once
    repeats = 1 if reuse is not None or "monolithic" in kept else timing_runs
    total = sum(e["wall_s"] * (repeats if kind == "staggered" else 1) for kind, e in ests.items())
    if total > budget.LIMIT_S:
        more = (f" ({repeats} timing(s) of the staggered run, estimated {budget.hms(ests['staggered']['wall_s'])} "
                "each)" if repeats > 1 else "")
        raise budget.BudgetError(f"this comparison would take about {budget.hms(total)} of wall time{more}, above "
                                 f"the {budget.hms(budget.LIMIT_S)} limit: give a shorter --duration"
                                 + (" or fewer --timing-runs" if repeats > 1 else ""))
    made = not out.exists()
    ensure_folder(out)  # every input checked: only now is a folder made (the runs' messages, rundir.py)
    try:
        with FolderLock(out, "comparison"):
            try:
                return _compare(out, sc, plans, runs, kept, repeats, tabulate, table_name, quiet, figures,
                                overwrite or resume, dpi, warm_up, SAME + tuple(same))
            except KeyboardInterrupt:
                said = [f"{k} complete (kept in {out / k})" if kept_run(out / k) is not None else f"{k} not complete"
                        for k in KINDS]
                raise SweepInterrupted(f"interrupted: {', '.join(said)}; continue with --resume") from None
    except BaseException:
        # refused at set-up (a bad --set value: the warm-up's components say so first): a folder made here for
        # nothing goes again, as a run's does (rundir.py)
        if made and out.is_dir() and not any(out.iterdir()):
            out.rmdir()
        raise


def _compare(out, sc, plans, runs, kept, repeats, tabulate, table_name, quiet, figures, overwrite, dpi,
             warm_up, same) -> dict:
    """The runs and the table, in the locked folder (:func:`compare_schemes` has checked every input)."""
    # --overwrite replaces the runs: the previous table goes now, so that an interrupted comparison never leaves
    # it beside runs it does not describe
    (out / table_name).unlink(missing_ok=True)
    if warm_up and len(kept) < len(plans):
        _warm_up(sc, out)
    later, loads = {}, {}
    before = (repeats + 1) // 2
    timings, again = [], None
    for i, kind in enumerate(KINDS, 1):
        if kind in runs:  # reused
            continue
        s, sch = plans[kind]
        # figures from the time series after both timed runs; a run recorded otherwise (CSV, nothing recorded)
        # draws its own in process, after its timing and without workers (api.simulate)
        # (a scenario without a case draws none)
        draw_later = figures and s.outputs.get("format", "h5") == "h5" and bool(s.outputs.get("record")) \
            and bool(s.extra.get("results", {}).get("kind"))
        if draw_later and not (kind in kept and kept[kind].get("figures")):
            later[kind] = s
        if kind in kept:
            runs[kind], loads[kind] = kept[kind], [None, None]
            if not quiet:
                print(f"[{i}/{len(KINDS)}] {kind}: complete in {out / kind}, kept", file=sys.stderr, flush=True)
        else:
            if not quiet:
                what = f"{len(sch.intervals)} interval(s)" if hasattr(sch, "intervals") else "automatic schedule"
                print(f"[{i}/{len(KINDS)}] {kind}: {sch.duration:g} s simulated, {what}", file=sys.stderr,
                      flush=True)
            load = load_average()
            # not checkpointed: an interrupted run is run again whole (--resume keeps complete runs only), and a
            # save of the whole state at every interval end is no part of the schemes' cost the table compares
            runs[kind] = simulate(s, schedule=sch, out=out / kind, figures=figures and not draw_later,
                                  progress=not quiet, overwrite=overwrite, checkpoint_every=None, dpi=dpi).summary
            loads[kind] = [load, load_average()]
            if not quiet:
                print(f"[{i}/{len(KINDS)}] {kind}: done in {runs[kind]['wall_time_s']:.3g} s", file=sys.stderr,
                      flush=True)
        if kind == "staggered":
            again = (s, sch)
            timings.append((runs[kind], loads[kind]))
            timings += _time_again(out, s, sch, before - 1, len(timings), repeats, quiet)
    repeat = None
    if repeats > 1:
        timings += _time_again(out, *again, repeats - before, len(timings), repeats, quiet)
        repeat = _timings(timings, before, same)
    if later:
        draw(out, later, quiet, dpi)
    wall = {k: runs[k].get("wall_time_s") for k in KINDS}
    cpu = {k: runs[k].get("cpu_time_s") for k in KINDS}
    if repeat is not None:  # the staggered run's time: the mean of its timings before and after the monolithic one
        wall["staggered"] = sum(repeat["wall_time_s"]) / len(repeat["wall_time_s"])
        if None not in repeat["cpu_time_s"]:
            cpu["staggered"] = sum(repeat["cpu_time_s"]) / len(repeat["cpu_time_s"])
    timing = {"wall_time_s": wall, "cpu_time_s": cpu,
              "speedup": wall["monolithic"] / wall["staggered"] if wall["staggered"] else None,
              "speedup_cpu": cpu["monolithic"] / cpu["staggered"] if cpu["monolithic"] and cpu["staggered"] else None,
              # the machine's 1-minute load average before and after each timed run: on a shared machine the wall
              # times hold the other processes' share (and the CPU times some of it), so a reader can judge them
              "load_average": loads,
              # each timing of the staggered run and whether they all gave the same results; None where it ran once
              "staggered_runs": repeat}
    table = tabulate(runs, timing)
    try:
        write_json(out / table_name, table)
    except OSError as exc:  # the runs are complete and kept: a --resume writes the table
        (out / (table_name + ".part")).unlink(missing_ok=True)
        raise named_os_error(exc, out, f"writing {table_name}") from None
    return table


def _warm_up(sc: Scenario, out: Path) -> None:
    """A few milliseconds of the system through every path the timed runs take (a coupled interval, a held one
    with the hold, a restart; the recorder's file and the result observers), untimed, so that neither timed run
    pays the one-off costs of the process (compiled kernels loaded, model matrices built and cached, first
    calls). Measured on the shipped engine: the staggered run, timed first, paid ~0.3-0.6 s of CPU (of ~2 s) for
    what a warm-up without a held interval, recorder or results left to it. The held interval is 2 steps over
    5 ms: a held interval over a time event (the shipped engine's at 0.01 s) would end at it and run the rest
    coupled (master/core/events.py), 90 ms for nothing. What the warm-up prints (its events, the warnings of an
    event time after its end) is not the comparison's: left out (an error still raises)."""
    s = copy.deepcopy(sc)
    h = float(s.schedule.get("step", 1e-5))
    tm = 2 * quantum(s)
    ph = Phases.from_spec(s.schedule.get("phases"))
    with tempfile.TemporaryDirectory(dir=out, prefix=SCRATCH) as tmp, contextlib.redirect_stderr(io.StringIO()):
        simulate(s, schedule=Timeline([Interval(ph.coupled, tm, h), Interval(ph.held, 0.005, 0.0025),
                                       Interval(ph.coupled, tm, h)]),
                 out=Path(tmp), figures=False, checkpoint_every=None)


def _time_again(out: Path, sc, sch, count: int, done: int, total: int, quiet: bool) -> list:
    """``count`` more timings of the staggered run, each into a folder removed afterwards: [(summary, [load
    before, after])]. A shared machine's speed drifts by +-20 % within seconds: the mean of several timings on
    either side of the monolithic run follows its speed during the monolithic run (a linear drift cancels)."""
    out_runs = []
    for j in range(count):
        if not quiet:
            print(f"staggered again: timing {done + j + 1} of {total}", file=sys.stderr, flush=True)
        load = load_average()
        with tempfile.TemporaryDirectory(dir=out, prefix=SCRATCH) as tmp:
            summary = simulate(sc, schedule=sch, out=Path(tmp) / "staggered", figures=False, progress=not quiet,
                               checkpoint_every=None).summary
        out_runs.append((summary, [load, load_average()]))
    return out_runs


def _same(a: dict, b: dict, keys) -> bool:
    """Equal to the bit in every entry ``keys`` (as JSON text: Python writes a float's shortest exact form, and a
    NaN equals itself there)."""
    return all(json.dumps(a.get(k), sort_keys=True) == json.dumps(b.get(k), sort_keys=True) for k in keys)


def _timings(timings: list, before: int, keys) -> dict:
    """``staggered_runs`` from [(summary, [load before, after])], the first the run reported."""
    first = timings[0][0]
    same = all(_same(s, first, keys) for s, _ in timings[1:])
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


def _close(a, b) -> bool:
    return isinstance(a, (int, float)) and isinstance(b, (int, float)) and abs(float(a) - b) <= 1e-9 * max(1.0, abs(b))
