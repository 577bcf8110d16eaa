"""One case of a sweep: what it runs (:class:`Case`) and running it where it is sent (:func:`run_case`).

A case is a scenario (a shipped name, a file or a :class:`~rotorcosim.master.scenario.build.Scenario`), the
value of its level parameter (its case's level, master/case.py; ``rotorcosim sweep --level``), parameter
overrides (``comp.param`` -> value, checked as ``--set``'s), a duration and a schedule. :func:`run_case` runs it
in a temporary folder of its own and returns its files as bytes, so that the process running it (a Dask worker,
possibly on another machine) needs no access to the folder the results go to.

::

    from rotorcosim.master.sweep import Case
    c = Case("F_50", "toy_thermomechanical", level=50.0, duration=0.05)
    c.scenario_of().name          # 'toy_thermomechanical_50'
"""
from __future__ import annotations

import math
import shutil
import socket
import tempfile
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from rotorcosim.components.bounded_read import read_json
from rotorcosim.master.api import check_run, load_scenario, simulate
from rotorcosim.master.scenario.build import Scenario
from rotorcosim.master import case as cases
from rotorcosim.master.scenario.overrides import apply_set


@dataclass
class Case:
    """One run of a sweep.

    ``name``: its folder's name under the sweep's folder (also the key of its results); ``scenario``: a shipped
    name, a TOML/SSP file, or a Scenario (None: the default, :func:`rotorcosim.master.case.default_scenario`);
    ``level``: the value of the scenario's level parameter (SI; None: the
    scenario's own); ``settings``: ``{"comp.param": value}`` overrides (a case with any is named
    ``<scenario>_<case name>`` in its results); ``duration`` [s] cuts the schedule (None: the scenario's);
    ``schedule``: ``"scenario"``/None, ``"auto"``, ``"monolithic"`` or a Timeline / AutoSchedule; ``dpi``: its
    figures' resolution (None: the default; not part of what the case computes)."""
    name: str
    scenario: Any = None
    settings: dict[str, Any] = field(default_factory=dict)
    level: float | None = None
    duration: float | None = None
    schedule: Any = None
    dpi: float | None = None

    def scenario_of(self) -> Scenario:
        """The scenario this case runs: its level, then its overrides, applied (each checked, as on the command
        line)."""
        sc = self.scenario if isinstance(self.scenario, Scenario) else load_scenario(
            cases.default_scenario() if self.scenario is None else self.scenario)
        if self.level is not None:
            if isinstance(self.scenario, Scenario):
                sc = sc.copy()   # the caller's scenario is left as it was
            cases.apply_level(sc, self.level, self.settings)
        if self.settings:
            sc = apply_set(sc, self.settings, origin="--set")
            sc.name = f"{sc.name}_{self.name}"
        return sc

    def check(self, force: bool = False) -> dict:
        """The run's own checks before it is sent anywhere (the scenario, its overrides, the duration, the
        schedule, the wall-time budget: ``force`` lifts its 24 h limit); returns the run's estimate
        (``budget.check``)."""
        return check_run(self.scenario_of(), self.schedule, self.duration, force=force)

    def definition(self) -> dict:
        """What the case runs, as JSON values (``sweep.json``'s ``definitions``): a ``--resume`` checks that the
        sweep it continues ran the same cases."""
        sc = self.scenario.name if isinstance(self.scenario, Scenario) else str(
            cases.default_scenario() if self.scenario is None else self.scenario)
        return {"scenario": sc, "level": self.level, "settings": {k: _plain(v) for k, v in self.settings.items()},
                "duration_s": self.duration, "schedule": self.schedule if isinstance(self.schedule, (str, type(None)))
                else repr(self.schedule)}


def _plain(v: Any) -> Any:
    """A setting as a JSON value (a path as its text; a non-finite float as its text, JSON has none)."""
    if isinstance(v, float) and not math.isfinite(v):
        return repr(v)
    if isinstance(v, (str, int, float, bool, type(None))):
        return v
    if isinstance(v, (list, tuple)):
        return [_plain(x) for x in v]
    return str(v)


def failed_summary(case: Case, error: str) -> dict:
    """The summary of a case that left no summary of its own (it could not start, or its process died)."""
    return {"scenario": case.name, "status": "failed", "error": error, "bearings": {}}


def _work_folder() -> Path:
    """A case's temporary folder: inside its Dask worker's local directory when it runs on one (a worker killed
    in the middle of a case cannot remove it; Dask removes a dead worker's directory when the next worker of
    its machine starts), else in the system's temporary folder."""
    try:
        from distributed import get_worker

        base = get_worker().local_directory
    except (ImportError, ValueError):   # not on a Dask worker: this process's own run
        base = None
    return Path(tempfile.mkdtemp(prefix="rotorcosim-case-", dir=base))


def run_case(case: Case) -> dict:
    """Run ``case`` where this is called (a Dask worker or this process), in a temporary folder of its own.

    Returns ``{"summary": ..., "files": {relative path: bytes}, "host": ...}``. A case that fails (a bad value
    found at set-up, a divergence, an FMU that crashes) returns its summary with its ``error``, and whatever its
    run wrote: one failing case must not lose the others. An interrupt (KeyboardInterrupt) is not caught."""
    work = _work_folder()
    try:
        try:
            summary = simulate(case.scenario_of(), duration=case.duration, schedule=case.schedule, out=work,
                               figures=True, dpi=case.dpi).summary
        except Exception as exc:
            summary = failed_summary(case, f"{type(exc).__name__}: {exc}")
            written = work / "summary.json"
            if written.exists():  # a failed run wrote its summary (with its status) and what it recorded
                summary = {**read_json(written, "summary"), "error": summary["error"]}
        files = {str(p.relative_to(work)): p.read_bytes() for p in sorted(work.rglob("*")) if p.is_file()}
        return {"summary": summary, "files": files, "host": socket.gethostname()}
    finally:
        shutil.rmtree(work, ignore_errors=True)
