"""``rotorcosim run [SCENARIO] [--unbalance N] [--duration S] [--schedule paper|auto|monolithic] --out DIR``.

Runs a scenario (a TOML file, a shipped scenario name, or an SSP archive) and writes into DIR:
``summary.json`` (the timeline used, the wall time, and the scenario's results: for the blade-loss scenarios
the paper's Table 4 for bearings 0 and 5), the time series (``timeseries.h5``, HDF5 readable by any HDF5
tool) and the figures. A diverging run stops with a clear error and keeps what it had recorded. A component
that asks to stop (an FMU's terminate request) ends the run at the time it asked for: ``status`` "stopped" in
the summary, with the component and the time under ``stopped``, and the command exits 0 with a one-line notice.
"""
from __future__ import annotations

import contextlib
import importlib
import os
import sys
import time
from pathlib import Path

from rotorcosim import scenarios
from rotorcosim.master import budget, checkpoint, watchdog
from rotorcosim.master.algorithm import SimulationDiverged
from rotorcosim.master.observers import Progress, Recorder
from rotorcosim.master.outputs import write_json
from rotorcosim.master.rundir import RunFolder
from rotorcosim.master.scenario import Scenario, build_simulation, load_scenario, schedule_of
from rotorcosim.master.schedule import Timeline

DEFAULT_SCENARIO = "blade_loss_2850"
SCHEDULES = {"paper": None, "auto": "auto", "monolithic": "monolithic"}


def add_arguments(p):
    p.add_argument("scenario", nargs="?", default=None,
                   help=f"scenario TOML file, shipped scenario name or .ssp archive (default: {DEFAULT_SCENARIO})")
    p.add_argument("--unbalance", type=float, default=None, help="blade-loss unbalance force F_u [N]")
    p.add_argument("--duration", type=float, default=None, help="simulated duration [s] (cuts the timeline)")
    p.add_argument("--schedule", choices=sorted(SCHEDULES), default="paper",
                   help="paper: the scenario's timeline; auto: switch TM/TO automatically; monolithic: one TM interval")
    p.add_argument("--out", required=True, help="output folder (empty, or see --overwrite / --resume)")
    p.add_argument("--overwrite", action="store_true", help="replace the results of a previous run in --out")
    p.add_argument("--resume", action="store_true",
                   help="continue the interrupted run in --out from its last checkpoint (same command otherwise)")
    p.add_argument("--force", action="store_true",
                   help=f"run even if estimated above {budget.LIMIT_S / 3600:g} h of wall time")
    p.add_argument("--checkpoint-every", type=float, default=checkpoint.EVERY_S, metavar="S",
                   help=f"wall seconds between checkpoints inside an interval (default {checkpoint.EVERY_S:g}; "
                        "interval ends are always checkpointed)")
    p.add_argument("--fmu-process", action="store_true",
                   help="run every FMU in a process of its own (a crashing or hanging FMU fails the run cleanly)")
    p.add_argument("--step-timeout", type=float, default=watchdog.STEP_TIMEOUT_S, metavar="S",
                   help=f"time limit of one component step in seconds (default {watchdog.STEP_TIMEOUT_S:g}; 0: none): "
                        "an FMU out of process is stopped and the run fails cleanly; in process the run is ended")
    p.add_argument("--no-figures", action="store_true", help="skip the PNG figures")
    p.add_argument("--quiet", action="store_true", help="no progress bar")


def resolve(name: str | None) -> Scenario:
    if name is None:
        return load_scenario(scenarios.path(DEFAULT_SCENARIO))
    p = Path(name)
    if p.suffix.lower() == ".ssp":
        from rotorcosim.fmus.ssp import read_ssp

        return read_ssp(p)
    if p.exists() or p.suffix:
        return load_scenario(p)
    return load_scenario(scenarios.path(name))


def apply_unbalance(sc: Scenario, force: float) -> None:
    if not (force >= 0.0) or force != force or force == float("inf"):
        raise ValueError(f"--unbalance must be a finite force >= 0 N, got {force}")
    ref = sc.extra.get("results", {}).get("unbalance_parameter")
    if not ref:
        raise ValueError(f"scenario {sc.name!r} has no [results] unbalance_parameter: --unbalance does not apply")
    comp, _, param = ref.partition(".")
    if comp not in sc.components:
        raise ValueError(f"[results] unbalance_parameter {ref!r}: no component {comp!r}")
    old = sc.components[comp].parameters.get(param)
    sc.components[comp].parameters[param] = float(force)
    if old is None or float(old) != float(force):
        # the run's name says what was run (the shipped level files are named blade_loss_<F_u>)
        sc.name = f"{sc.name.rsplit('_', 1)[0] if sc.name.rsplit('_', 1)[-1].isdigit() else sc.name}_{force:g}"


def postprocessor(sc: Scenario):
    """The module that turns a run into the scenario's results (``[results] kind``), or None."""
    kind = sc.extra.get("results", {}).get("kind")
    if not kind:
        return None
    try:
        return importlib.import_module(f"rotorcosim.master.results_{kind}")
    except ModuleNotFoundError as exc:
        raise ValueError(f"[results] kind {kind!r}: no such result extraction ({exc})") from None


def execute(sc: Scenario, out: Path, schedule_kind: str | None = None, duration: float | None = None,
            figures: bool = True, quiet: bool = True, schedule=None, *, overwrite: bool = False,
            resume: bool = False, force: bool = False, checkpoint_every: float = checkpoint.EVERY_S,
            step_timeout: float = 0.0) -> dict:
    """Run ``sc`` into ``out``; returns the summary (also written to out/summary.json).

    ``schedule`` (a Timeline or AutoSchedule) overrides the scenario's; otherwise ``schedule_kind`` and
    ``duration`` adjust it. ``out`` must be empty (or hold a previous run's results and ``overwrite``, or an
    interrupted run and ``resume``: rundir.py); the run is refused before it starts if it is estimated above
    budget.LIMIT_S of wall time (unless ``force``). The summary's ``status`` says how it ended: ``complete``,
    ``interrupted`` (SIGINT/SIGTERM: resume it with ``resume=True``) or ``failed``; on anything but
    ``complete`` the error is raised after the summary and the time series are written."""
    if duration is not None and not (duration > 0 and duration < float("inf")):
        raise ValueError(f"--duration must be a positive number of seconds, got {duration}")
    if schedule is None:
        schedule = schedule_of(sc, schedule_kind, duration)
    estimate = budget.check(sc, schedule, force)
    if not quiet and estimate["wall_s"] > 60:
        print(f"{sc.name}: {estimate['steps']:,} steps, estimated {estimate['wall']} of wall time", file=sys.stderr)
    total = schedule.duration
    post = postprocessor(sc)
    o = sc.outputs
    record = list(o.get("record", []))
    fmt = o.get("format", "h5")
    if fmt not in ("h5", "csv"):
        raise ValueError(f"[outputs] format {fmt!r} not in ('h5', 'csv')")
    speed = sc.schedule.get("speed_rpm")
    if post is not None and not speed:
        raise ValueError(f"scenario {sc.name!r}: [results] needs schedule.speed_rpm (steady windows in rotor cycles)")
    key = checkpoint.fingerprint(sc.name, sc.components, sc.connections, sc.inputs, sc.algorithm, sc.schedule,
                                 sc.outputs, sc.extra, schedule)
    with RunFolder(out, overwrite=overwrite, resume=resume) as folder, checkpoint.StopRequest() as stop:
        out = folder.path
        point = checkpoint.load(out / checkpoint.CHECKPOINT, key) if resume else None
        series = out / f"timeseries.{fmt}"
        observers = []
        if record:
            observers.append(Recorder(series, record, float(o.get("record_step", 1e-4))))
        post_obs = post.observers(sc, speed) if post is not None else []
        observers += post_obs
        observers.append(Progress(total, disable=quiet, desc=sc.name))
        saver = checkpoint.Checkpointer(out / checkpoint.CHECKPOINT, stop, checkpoint_every, key)
        observers.append(saver)  # last: it sees every other observer done with the step
        sim = build_simulation(sc, observers)
        head = {"scenario": sc.name, "source": str(sc.source) if sc.source else None,
                "schedule": schedule_kind or sc.schedule.get("kind", "monolithic"), "duration_s": total,
                "estimate": estimate}
        write_json(out / "summary.json", {**head, "status": "running", "pid": os.getpid(),
                                          "resumed_from_t_s": point.t if point else None})
        t_wall = time.perf_counter()
        error = None

        def hung(msg: str) -> None:  # the watchdog's last act before it ends the process
            write_json(out / "summary.json", {**head, "status": "failed", "error": msg, "t_end_s": sim.t,
                                              "checkpoint": checkpoint.CHECKPOINT if saver.saved else None})

        guard = watchdog.Watchdog(step_timeout, hung, "rotorcosim run") if step_timeout > 0 else contextlib.nullcontext()
        try:
            with guard:
                report = checkpoint.resume(sim, schedule, point) if point else sim.run(schedule)
            status = report.status  # "complete", or "stopped" (a component asked to stop)
        except checkpoint.RunInterrupted as exc:
            error, status = exc, "interrupted"
        except BaseException as exc:  # diverged, disk full, a component's failure: summary first, then raise
            error, status = exc, ("interrupted" if isinstance(exc, KeyboardInterrupt) else "failed")
        report = sim.report
        summary = {
            **head,
            "status": status,
            "t_end_s": report.t_end,
            "timeline": [u.as_dict() for u in report.timeline],
            "hold": report.hold.as_dict() if report.hold is not None else None,
            "wall_time_s": time.perf_counter() - t_wall,
            "resumed_from_t_s": point.t if point else None,
            "component_steps": report.component_steps,
            "timeseries": series.name if record else None,
            # "complete", "stopped" (a component asked to stop: "stopped" names it and the time), "interrupted"
            # (SIGINT/SIGTERM: --resume continues it) or "failed"
            "stopped": report.stopped,
            "checkpoint": (checkpoint.CHECKPOINT if status in ("interrupted", "failed") and saver.saved else None),
            "checkpoint_note": saver.disabled,
            "error": None if error is None else f"{type(error).__name__}: {error}",
        }
        try:
            if post is not None:
                summary.update(post.extract(sc, sim, post_obs, report))
                if figures and status in ("complete", "stopped"):
                    summary["figures"] = post.figures(sc, series if record else None, out)
            else:
                summary["final_outputs"] = {f"{n}.{k}": v for n, c in sim.system.components.items()
                                            for k, v in c.y.items()}
        except Exception as exc:
            if error is None:
                raise
            summary["results_error"] = f"{type(exc).__name__}: {exc}"
        try:
            write_json(out / "summary.json", summary)
        except OSError:
            if error is None:
                raise
        if status in ("complete", "stopped"):
            (out / checkpoint.CHECKPOINT).unlink(missing_ok=True)
        if error is not None:
            raise error
    return summary


def run(args) -> int:
    sc = resolve(args.scenario)
    if args.unbalance is not None:
        apply_unbalance(sc, args.unbalance)
    if not (0 <= args.step_timeout < float("inf")):
        raise ValueError(f"--step-timeout must be a number of seconds >= 0 (0: no limit), got {args.step_timeout}")
    for spec in sc.components.values():
        if spec.fmu is not None and args.fmu_process:
            spec.options["process"] = True
            if args.step_timeout > 0:
                spec.options.setdefault("step_timeout", args.step_timeout)
    if not (args.checkpoint_every > 0):
        raise ValueError(f"--checkpoint-every must be a positive number of seconds, got {args.checkpoint_every}")
    try:
        summary = execute(sc, args.out, SCHEDULES[args.schedule], args.duration,
                          figures=not args.no_figures, quiet=args.quiet, overwrite=args.overwrite,
                          resume=args.resume, force=args.force, checkpoint_every=args.checkpoint_every,
                          step_timeout=args.step_timeout)
    except SimulationDiverged as exc:
        print(f"rotorcosim run: the simulation diverged: {exc}; what was recorded is in {args.out} "
              "(summary.json has the error)", file=sys.stderr)
        return 1
    except KeyboardInterrupt as exc:
        print(f"rotorcosim run: interrupted ({exc or 'SIGINT'}); the time series and summary.json in {args.out} "
              f"hold what was computed; continue with the same command and --resume", file=sys.stderr)
        return 130
    stop = summary.get("stopped")
    if stop:
        print(f"rotorcosim run: {stop['component']} asked to stop the simulation at t = {stop['t_s']:.9g} s; "
              f"the run ended there (status \"stopped\")")
    print(f"{sc.name}: {summary['t_end_s']:.4g} s simulated in {summary['wall_time_s']:.3g} s wall time; "
          f"results in {args.out}/summary.json")
    return 0
