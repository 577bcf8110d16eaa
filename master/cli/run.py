"""``rotorcosim run [SCENARIO] [--level VALUE] [--duration S] [--schedule scenario|auto|monolithic]
[--set COMP.PARAM=VALUE]... [--swap COMP=IMPL|FILE.fmu]... [--record COMP.PORT,...] --out DIR``.

A thin layer over :func:`rotorcosim.simulate` (``master/api.py``).

Runs a scenario (a TOML file, a shipped scenario name, or an SSP archive) and writes into DIR:
``summary.json`` (the timeline used, the wall time, and the scenario's results, which its case extracts:
master/case.py), the time series (``timeseries.h5``, HDF5 readable by any HDF5 tool) and the figures. A diverging run stops with a clear error and keeps what it had recorded. A component
that asks to stop (an FMU's terminate request) ends the run at the time it asked for: ``status`` "stopped" in
the summary, with the component and the time under ``stopped``, and the command exits 0 with a one-line notice.
"""
from __future__ import annotations

import sys
from pathlib import Path

from rotorcosim.master.schedule import budget
from rotorcosim.master.run import checkpoint
from rotorcosim.master.run import watchdog
from rotorcosim.master.core.algorithm import SimulationFailed
from rotorcosim.master import case
from rotorcosim.master.api import DEFAULT_SCENARIO, SCHEDULES, ResultsFailed, load_scenario, simulate
from rotorcosim.master.cli.options import SCHEDULE_HELP, add_dpi, add_out, add_scenario
from rotorcosim.master.compiled.choice import ENGINES
from rotorcosim.master.scenario.overrides import apply_set, apply_swap, parse_set, parse_swap
from rotorcosim.master.scenario.build import Scenario

#: where a command-line change is said to come from, in error messages
CLI_ORIGIN = "the command line (--set/--swap)"


def add_arguments(p):
    """The options of ``rotorcosim run`` on the parser ``p``."""
    add_scenario(p, None, shown=DEFAULT_SCENARIO)
    case.add_level_option(p)
    p.add_argument("--duration", type=float, default=None, help="simulated duration [s] (cuts the timeline)")
    p.add_argument("--schedule", choices=sorted([*SCHEDULES, *case.schedule_aliases()]), default="scenario",
                   help=SCHEDULE_HELP)
    add_edit_arguments(p)
    p.add_argument("--record", default=None, metavar="COMP.PORT,...",
                   help="the ports to record, comma-separated (default: the scenario's [outputs] record; the "
                        "figures need the scenario's own)")
    p.add_argument("--tolerance", type=float, default=None, metavar="PCT",
                   help="with --schedule auto: the largest error of a result against the monolithic run that you "
                        "accept, in percent (a temperature's of its rise above the initial temperature); the "
                        "thermal-only intervals follow it and summary.json reports the estimated error achieved "
                        "(hold.estimated_error_pct; hold.advice where it is above)")
    add_out(p, "output folder (empty, or see --overwrite / --resume)")
    p.add_argument("--overwrite", action="store_true", help="replace the results of a previous run in --out")
    p.add_argument("--resume", action="store_true",
                   help="continue the interrupted run in --out from its last checkpoint (same command otherwise)")
    p.add_argument("--force", action="store_true",
                   help=f"run even if estimated above {budget.LIMIT_S / 3600:g} h of wall time")
    p.add_argument("--checkpoint-every", type=float, default=checkpoint.EVERY_S, metavar="S",
                   help=f"wall seconds between checkpoints inside an interval (default {checkpoint.EVERY_S:g}; "
                        f"an interval end is checkpointed when the last checkpoint is min(S, "
                        f"{checkpoint.END_GAP_S:g}) s old, and an interrupted run where it stops)")
    p.add_argument("--fmu-process", action="store_true",
                   help="run every FMU in a process of its own (a crashing or hanging FMU fails the run cleanly)")
    p.add_argument("--step-timeout", type=float, default=watchdog.STEP_TIMEOUT_S, metavar="S",
                   help=f"time limit of one component step in seconds (default {watchdog.STEP_TIMEOUT_S:g}; 0: none): "
                        "an FMU out of process is stopped and the run fails cleanly; in process the run is ended")
    p.add_argument("--engine", choices=ENGINES, default="auto",
                   help="thermo-mechanical intervals: auto (compiled when every component offers a kernel), python "
                        "(the generic loop) or compiled (an error when it cannot); the summary says which ran")
    p.add_argument("--no-figures", action="store_true", help="skip the PNG figures")
    add_dpi(p)
    p.add_argument("--quiet", action="store_true", help="no progress bar")


def add_edit_arguments(p):
    """``--set`` and ``--swap``, for every command that runs a scenario."""
    p.add_argument("--set", action="append", default=[], metavar="COMP.PARAM=VALUE", dest="set_values",
                   help="set a component parameter (SI; repeatable), e.g. --set node.C=20")
    p.add_argument("--swap", action="append", default=[], metavar="COMP=IMPL|FILE.fmu",
                   help="give a component another implementation: a registry name (damper.fe), module:Class "
                        "or an FMU file (repeatable)")


def apply_edits(sc: Scenario, args) -> Scenario:
    """The scenario with the command line's ``--swap`` then ``--set`` applied (swaps first, so that a --set
    can give the new implementation's parameters)."""
    for text in getattr(args, "swap", []) or []:
        sc = apply_swap(sc, *parse_swap(text), origin=CLI_ORIGIN)
    values = {}
    for text in getattr(args, "set_values", []) or []:
        key, value = parse_set(text)
        if key in values:  # the last one was taken without a word (sweep --set refused it already)
            raise ValueError(f"--set {key} is given twice ({values[key]!r} and {value!r}): give it once")
        values[key] = value
    return apply_set(sc, values, origin=CLI_ORIGIN) if values else sc


def resolve(name: str | None) -> Scenario:
    """A shipped scenario name, a TOML file or an SSP archive (:func:`rotorcosim.load_scenario`)."""
    return load_scenario(name)


def execute(sc: Scenario, out: Path, schedule_kind: str | None = None, duration: float | None = None,
            figures: bool = True, quiet: bool = True, schedule=None, *, record=None, overwrite: bool = False,
            resume: bool = False, force: bool = False, checkpoint_every: float | None = checkpoint.EVERY_S,
            step_timeout: float = 0.0, engine: str = "auto", dpi: float | None = None) -> dict:
    """Run ``sc`` into ``out``; returns the summary (also written to out/summary.json). A thin layer over
    :func:`rotorcosim.simulate` (its docstring says the rest) kept for the other commands.

    ``schedule`` (a Timeline or AutoSchedule) overrides the scenario's; otherwise ``schedule_kind`` and
    ``duration`` adjust it."""
    if duration is not None and not (duration > 0 and duration < float("inf")):
        raise ValueError(f"--duration must be a positive number of seconds, got {duration}")
    if schedule is None:
        schedule = {None: "scenario"}.get(schedule_kind, schedule_kind)
    elif duration is not None:
        raise ValueError("give duration or a schedule object, not both")
    res = simulate(sc, duration=duration, schedule=schedule, out=out, figures=figures, progress=not quiet,
                   record=record, overwrite=overwrite, resume=resume, force=force, checkpoint_every=checkpoint_every,
                   step_timeout=step_timeout, engine=engine, dpi=dpi)
    return res.summary


def apply_level(sc: Scenario, args) -> None:
    """The command's level option (``args.level``, in the spelling ``args.level_option`` the user gave) applied
    to ``sc``, checked against its ``--set`` values (master/case.py)."""
    case.apply_level(sc, args.level, [parse_set(text)[0] for text in getattr(args, "set_values", None) or []],
                     getattr(args, "level_option", None))


def parse_record(text: str | None) -> list[str] | None:
    """``--record "a.x, b.y"`` -> ``["a.x", "b.y"]`` (None: not given)."""
    if text is None:
        return None
    refs = [r.strip() for r in text.split(",") if r.strip()]
    if not refs:
        raise ValueError("--record: no port given (write comp.port,comp.port,...)")
    return refs


def run(args) -> int:
    """Run the command ``args`` (parsed); returns the exit status."""
    if args.duration is not None and not (args.duration > 0 and args.duration < float("inf")):
        raise ValueError(f"--duration must be a positive number of seconds, got {args.duration}")
    sc = apply_edits(resolve(args.scenario), args)
    if args.level is not None:
        apply_level(sc, args)
    if not (0 <= args.step_timeout < float("inf")):
        raise ValueError(f"--step-timeout must be a number of seconds >= 0 (0: no limit), got {args.step_timeout}")
    for spec in sc.components.values():
        if spec.fmu is not None and args.fmu_process:
            spec.options["process"] = True
            if args.step_timeout > 0:
                spec.options.setdefault("step_timeout", args.step_timeout)
    if args.tolerance is not None:
        if args.schedule != "auto":
            raise ValueError("--tolerance applies to --schedule auto only")
        if not (0.0 < args.tolerance < float("inf")):
            raise ValueError(f"--tolerance must be a positive percentage, got {args.tolerance}")
        sc.schedule["tolerance"] = float(args.tolerance)
    if not (args.checkpoint_every > 0):
        raise ValueError(f"--checkpoint-every must be a positive number of seconds, got {args.checkpoint_every}")
    out = Path(args.out)
    try:
        res = simulate(sc, duration=args.duration, schedule=args.schedule, out=args.out,
                       record=parse_record(args.record), figures=not args.no_figures, progress=not args.quiet,
                       overwrite=args.overwrite, resume=args.resume, force=args.force,
                       checkpoint_every=args.checkpoint_every, step_timeout=args.step_timeout,
                       engine=args.engine, dpi=args.dpi)
    except SimulationFailed as exc:   # diverged, a component failed, a step timed out, a process crashed
        print(f"rotorcosim run: {exc.line()}; what was recorded is in {out} (summary.json has the error)",
              file=sys.stderr)
        return 1
    except ResultsFailed as exc:   # the steps ended; their results or figures could not be made
        print(f"rotorcosim run: {exc}; the time series is kept in {out} (summary.json has the error)",
              file=sys.stderr)
        print("written: " + ", ".join(str(f) for f in exc.result.files))
        return 1
    except KeyboardInterrupt as exc:
        print(f"rotorcosim run: interrupted ({exc or 'SIGINT'}); the time series and summary.json in {out} "
              f"hold what was computed; continue with the same command and --resume", file=sys.stderr)
        return 130
    s = res.summary
    stop = s.get("stopped")
    if stop:
        print(f"rotorcosim run: {stop['component']} asked to stop the simulation at t = {stop['t_s']:.9g} s; "
              f"the run ended there (status \"stopped\")")
    est = (s.get("hold") or {}).get("estimated_error_pct")
    # the result the estimate is largest on, as its case names it for a reader (else its key path)
    e = s.get("estimated_error") or {}
    which = e.get("largest_label") or e.get("largest")
    print(f"{sc.name}: {s['t_end_s']:.4g} s simulated in {s['wall_time_s']:.3g} s wall time "
          f"({s['engine'] or 'no'} engine)" + estimate_text(est, which))
    note = (s.get("hold") or {}).get("advice")
    if note:
        print(f"rotorcosim run: {note}")
    # the last line: every file the run wrote
    print("written: " + ", ".join(str(f) for f in res.files))
    return 0


def estimate_text(est: float | None, which: str | None) -> str:
    """What the run's line says of the staggered scheme's estimated error ``est`` [%] (None: none) on the result
    ``which``: two decimals, or one significant digit below 0.005 % (a long run's estimate often is), never
    "0.00 %" for an estimate that is not zero."""
    if est is None:
        return ""
    pct = f"{est:.2f}" if est == 0.0 or est >= 0.005 else f"{est:.1g}"
    return f"; estimated error of the staggered scheme {pct} %" + (f" ({which})" if which else "")
