"""summary.json's dict, made from a run's report: while it runs, when it ends, when its step hangs.

Every key is described in docs/reference/outputs.md. The functions take plain values (the run's head, its report,
its status and error), so that the summary of a run is the same whichever caller makes it.
"""
from __future__ import annotations

import json
import sys

from rotorcosim.master.run import checkpoint
from rotorcosim.master.run.outputs import plain_json
from rotorcosim.master.simulation import engine_summary

#: the statuses of a run that ended by itself ("stopped": a component asked to stop); its results are whole
ENDED = ("complete", "stopped")


def peak_memory_mb() -> float | None:
    """This process's peak resident memory so far [MB] (``getrusage``'s high-water mark), None where unknown.

    >>> peak_memory_mb() > 0    # doctest: +SKIP
    True"""
    try:
        import resource
    except ImportError:  # not on this system (Windows)
        return None
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    return peak / (1 << 20) if sys.platform == "darwin" else peak / 1024   # bytes on macOS, KiB on Linux


def head(sc, kind: str | None, duration: float, estimate: dict, provenance: dict) -> dict:
    """The keys every summary of the run starts with: the scenario, its file, the schedule's kind, the duration
    [s], the estimate (master/schedule/budget.py) and the provenance (master/run/provenance.py)."""
    return {"scenario": sc.name, "source": str(sc.source) if sc.source else None,
            "schedule": kind or sc.schedule.get("kind", "monolithic"), "duration_s": duration,
            "estimate": estimate,
            # what made the run: the code's version, the scenario file and name as loaded, every --set /
            # --swap / level, the parameters each component ran with (master/run/provenance.py)
            "provenance": provenance}


def running(head: dict, pid: int, resumed_from: float | None) -> dict:
    """The summary written when the run starts: its status ``running``, the process, the time it resumed from."""
    return {**head, "status": "running", "pid": pid, "resumed_from_t_s": resumed_from}


def hung(head: dict, message: str, t: float, timeseries: str | None, saved: str | None) -> dict:
    """The summary of a run ended by the step watchdog: ``failed`` at ``t`` [s], the time series file it closed
    (None: none) and the checkpoint it leaves (None: none)."""
    return {**head, "status": "failed", "error": message, "t_end_s": t, "timeseries": timeseries,
            "checkpoint": saved}


def ended(head: dict, sim, *, status: str, error: BaseException | None, wall_s: float, resumed_from: float | None,
          timeseries: str | None, saved: str | None, checkpoint_note: str | None, validity: list) -> dict:
    """The summary of a run that ended (``status``: complete, stopped, interrupted or failed, with ``error``):
    the report of the simulation ``sim``, ``wall_s`` [s] of wall time, the time it resumed from (None: it did
    not), its time series file's name, the checkpoint it leaves, why it took none (``checkpoint_note``) and the
    validity entries (master/observer/validity.py)."""
    report = sim.report
    return {
        **head,
        "status": status,
        "t_end_s": report.t_end,
        "timeline": [u.as_dict() for u in report.timeline],
        "hold": report.hold.as_dict() if report.hold is not None else None,
        "wall_time_s": wall_s,
        # the process's CPU time over the run (Simulation.run): beside the wall time on a loaded machine
        "cpu_time_s": report.cpu_time_s,
        # the process's peak resident memory so far (its high-water mark: this run's peak in a process of its
        # own, e.g. one command or one sweep worker's cases); None where the system does not say
        "peak_memory_MB": peak_memory_mb(),
        "resumed_from_t_s": resumed_from,
        # wall time per base step of this run, beside the estimate's (budget.py): how far the declared
        # step cost is from this machine and scenario
        "step_cost_us": (None if resumed_from is not None else
                         1e6 * wall_s / max(1, sum(u.steps for u in report.timeline))),
        "component_steps": report.component_steps,
        **engine_summary(sim),
        "timeseries": timeseries,
        # "complete", "stopped" (a component asked to stop: "stopped" names it and the time), "interrupted"
        # (SIGINT/SIGTERM: resume continues it) or "failed"
        "stopped": report.stopped,
        "checkpoint": saved,
        "checkpoint_note": checkpoint_note,
        "error": None if error is None else f"{type(error).__name__}: {error}",
        # each check of a component's validity envelope the run left: worst value, first time, limit, source
        "validity": validity,
        # the events located in the run (master/core/events.py), where a component declares event indicators
        **({} if report.events is None else {"events": report.events}),
    }


def saved_checkpoint(saver: checkpoint.Checkpointer | None) -> str | None:
    """The checkpoint file's name if ``saver`` wrote one, else None."""
    return checkpoint.CHECKPOINT if saver is not None and saver.saved else None


def final_outputs(system) -> dict:
    """``final_outputs``: every component output's last value, ``"comp.port"`` -> value (a run with no case)."""
    return {f"{n}.{k}": v for n, c in system.components.items() for k, v in c.y.items()}


def add_estimated_error(summary: dict, sc, hold) -> None:
    """The run's estimated error in summary.json's ``hold``: the largest of the case's results'
    (``estimated_error``, if it gives them; else the hold's own over its temperatures) as
    ``estimated_error_pct``, and ``advice`` (which interval, what to change) where it exceeds the scenario's
    ``[schedule] tolerance``."""
    if hold is None or summary.get("hold") is None:
        return
    est = summary.get("estimated_error")
    if est is not None:
        summary["hold"]["estimated_error_pct"] = est["largest_pct"]
    largest = summary["hold"].get("estimated_error_pct")
    tol = sc.schedule.get("tolerance")
    if largest is not None and tol is not None:
        note = hold.advice(largest, float(tol))
        if note is not None:
            summary["hold"]["advice"] = note


def as_written(summary: dict) -> dict:
    """The summary exactly as summary.json holds it (plain numbers and lists, None for NaN)."""
    return json.loads(json.dumps(plain_json(summary)))

