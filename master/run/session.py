"""One run of a scenario and what surrounds it: the output folder and its lock, checkpoints and resuming, the
step watchdog, the provenance record, the recorder, and the summary written when it starts and when it ends.

:func:`rotorcosim.simulate` makes one :class:`RunSession` per run; the case's results and figures stay with the
API (master/api.py), which alone may know the cases. A run without a folder (``out=None``) is recorded in memory
and writes nothing.
"""
from __future__ import annotations

import contextlib
import json
import os
import sys
import time
from pathlib import Path

import numpy as np

from rotorcosim.master.observer.progress import Progress
from rotorcosim.master.observer.recorder import Recorder
from rotorcosim.master.observer.plausible import Plausibility
from rotorcosim.master.observer.series import SeriesFile
from rotorcosim.master.observer.validity import Validity
from rotorcosim.master.run import checkpoint, summary, watchdog
from rotorcosim.master.run.options import RunOptions
from rotorcosim.master.run.outputs import plain_json, write_json
from rotorcosim.master.run.provenance import h5_attributes, provenance
from rotorcosim.master.run.rundir import RunFolder

#: how the run's summary file is named in its folder
SUMMARY = "summary.json"


class RunSession:
    """``with RunSession(sc, schedule, signals, fmt, opts) as run:`` one run of the scenario ``sc`` over the
    :class:`~rotorcosim.master.schedule.timeline.Schedule` ``schedule``, recording ``signals`` (``"comp.port"``)
    in the format ``fmt`` (``"h5"`` or ``"csv"``), made as :class:`~rotorcosim.master.run.options.RunOptions`
    ``opts`` says. Entering it takes the output folder (with ``opts.out``: its lock, the ``--overwrite`` /
    ``--resume`` rules, the checkpoint resumed from) and makes the recorder; leaving it gives the folder back.

    In order: :meth:`observers` (the list the simulation is built with), :meth:`built` (the simulation),
    :meth:`start` (the summary's first keys, written as ``running``), :meth:`execute`, then :meth:`refused`,
    :meth:`summary`, :meth:`recorded` and :meth:`finish`.

    Its state: ``out`` (the folder's path; None in memory), ``folder`` (:class:`~.rundir.RunFolder`), ``stop``
    (:class:`~.checkpoint.StopRequest`), ``point`` (the checkpoint resumed from, or None), ``series`` (the time
    series file, or None), ``recorder``, ``validity``, ``saver`` (the :class:`~.checkpoint.Checkpointer`, or
    None), ``provenance`` (master/run/provenance.py: completed with the components' parameters once built),
    ``head`` (the keys every summary starts with), ``sim``, and once run ``status``, ``error`` and ``wall_s``.

    >>> with RunSession(sc, schedule, ["osc.x"], "h5", RunOptions()) as run:   # doctest: +SKIP
    ...     run.built(build_simulation(sc, run.observers([], estimate)))
    ...     run.start(summary.head(sc, None, schedule.duration, estimate, run.provenance))
    ...     run.execute()
    """

    def __init__(self, sc, schedule, signals: list[str], fmt: str, opts: RunOptions):
        self.sc, self.schedule, self.signals, self.fmt, self.opts = sc, schedule, signals, fmt, opts
        self.out: Path | None = None
        self.folder: RunFolder | None = None
        self.stop: checkpoint.StopRequest | None = None
        self.point: checkpoint.ResumePoint | None = None
        self.series: Path | None = None
        self.key: str | None = None
        self.recorder: Recorder | None = None
        self.validity: Validity | None = None
        self.saver: checkpoint.Checkpointer | None = None
        self.provenance = provenance(sc)
        self.head: dict = {}
        self.sim = None
        self.status: str | None = None
        self.error: BaseException | None = None
        self.wall_s = 0.0
        self._stepped = False
        self._exits = contextlib.ExitStack()

    # -- the folder ------------------------------------------------------------------------------------------
    def __enter__(self) -> "RunSession":
        self._exits.__enter__()
        try:
            self._take_folder()
            # a file run keeps nothing in memory: the result and the figures read the HDF5 file (CSV is not
            # read back)
            self.recorder = Recorder(self.series, self.signals, float(self.sc.outputs.get("record_step", 1e-4)),
                                     keep=self.keep, attributes=self.h5_attributes)
        except BaseException:
            if not self._exits.__exit__(*sys.exc_info()):
                raise
        return self

    def __exit__(self, *exc) -> bool:
        return self._exits.__exit__(*exc)

    def _take_folder(self) -> None:
        opts, sc = self.opts, self.sc
        if opts.out is None:
            return
        # the recorded signals too: a resume with another --record continued some datasets and not others
        # (a file whose osc.x had 301 rows and node.T 257, beside a 301-row time)
        self.key = checkpoint.fingerprint(sc.name, sc.components, sc.connections, sc.inputs, sc.algorithm,
                                          sc.schedule, sc.outputs, sc.extra, self.schedule, self.signals)
        self.folder = self._exits.enter_context(RunFolder(opts.out, overwrite=opts.overwrite, resume=opts.resume))
        self.stop = self._exits.enter_context(checkpoint.StopRequest())
        self.out = self.folder.path
        self.point = checkpoint.load(self.out / checkpoint.CHECKPOINT, self.key) if opts.resume else None
        self.series = self.out / f"timeseries.{self.fmt}" if self.signals else None

    def on_exit(self, callback) -> None:
        """Call ``callback()`` when the session ends, before the folder is given back."""
        self._exits.callback(callback)

    @property
    def keep(self) -> bool:
        """True if the run keeps its samples in memory: no time series file, or one that is not read back (CSV)."""
        return self.series is None or self.fmt != "h5"

    def h5_attributes(self) -> dict[str, str]:
        """The time series file's attributes: the provenance as it stands (master/run/provenance.py) and, in a run
        whose components declare event indicators, its located ``events`` (JSON, as summary.json's)."""
        attrs = h5_attributes(self.provenance)
        if self.sim is not None and self.sim.report.events is not None:
            attrs["events"] = json.dumps(plain_json(self.sim.report.events))
        return attrs

    # -- set-up ----------------------------------------------------------------------------------------------
    def observers(self, case_observers: list, estimate: dict) -> list:
        """The run's observers, in the order they see a step: the recorder, the case's (``case_observers``), the
        progress bar (its first estimate from the budget's ``estimate``), the validity checks, the plausibility
        warning, and with a folder the checkpointer, last: it sees every other observer done with the step."""
        sc, opts = self.sc, self.opts
        # where the components' models stop holding: after the progress bar, so that its lines follow the bar's
        self.validity = Validity(self.recorder.record_step, sc.name)
        prior = {ph: 1e-6 * us for ph, us in estimate["step_cost_us"].items()}
        # a parameter off by a unit factor: warned once the components are set up (after their own checks)
        observers = [self.recorder, *case_observers,
                     Progress(self.schedule.duration, disable=not opts.progress, desc=sc.name, prior=prior),
                     self.validity, Plausibility(sc.name)]
        if self.out is not None:
            # checkpoint_every=None: no checkpoints (a timing comparison is run again, not resumed)
            self.saver = checkpoint.Checkpointer(
                self.out / checkpoint.CHECKPOINT if opts.checkpoint_every is not None else None, self.stop,
                opts.checkpoint_every or checkpoint.EVERY_S, self.key)
            observers.append(self.saver)
        return observers

    def built(self, sim) -> None:
        """The simulation built with :meth:`observers`: the provenance completed with its components' parameters."""
        self.sim = sim
        self.provenance = provenance(self.sc, sim.system)

    def start(self, head: dict) -> None:
        """``head``: the keys every summary of the run starts with (:func:`.summary.head`); with a folder, written
        as the summary of a ``running`` run. From here the folder holds this run's summary, whatever happens."""
        self.head = head
        if self.out is not None:
            write_json(self.out / SUMMARY, summary.running(head, os.getpid(),
                                                           self.point.t if self.point else None))
            self.folder.started = True

    # -- the run ---------------------------------------------------------------------------------------------
    def execute(self) -> None:
        """Run (or resume) the simulation under the step watchdog; sets :attr:`status` ("complete", "stopped": a
        component asked to stop, "interrupted", "failed"), :attr:`error` (None, or what ended the run: raised by
        the caller once the summary and the time series are written) and :attr:`wall_s`."""
        t0 = time.perf_counter()
        limit = self.opts.step_timeout
        guard = watchdog.Watchdog(limit, self._hung, "rotorcosim run") if limit > 0 else contextlib.nullcontext()
        try:
            # numpy's floating-point warnings (overflow, invalid) off during the steps: the engine checks every
            # output another component reads after each step and stops with SimulationDiverged naming the port
            # and the time (algorithm.py), so a warning would only add a stray line of source text before that
            # error
            with guard, np.errstate(over="ignore", invalid="ignore", divide="ignore"):
                report = (checkpoint.resume(self.sim, self.schedule, self.point) if self.point
                          else self.sim.run(self.schedule))
            self.status = report.status
        except checkpoint.RunInterrupted as exc:
            self.error, self.status = exc, "interrupted"
        except BaseException as exc:  # diverged, disk full, a component's failure: summary first, then raise
            self.error, self.status = exc, ("interrupted" if isinstance(exc, KeyboardInterrupt) else "failed")
        self.wall_s = time.perf_counter() - t0

    def _hung(self, message: str) -> None:
        """The watchdog's last act before it ends the process: the summary of a failed run, the time series
        closed."""
        if self.out is None:
            return
        closed = None
        if self.series is not None:
            # the rows still buffered (up to a flush's worth: all of a short run's) written and the file
            # closed, marked incomplete, under its final name (not left as timeseries.h5.part). The run's thread
            # is inside the hung component's step, not in the recorder.
            try:
                self.recorder.end(self.sim, TimeoutError(message))
                closed = self.series.name
            except Exception:  # noqa: BLE001 - the process ends now whatever happens: the .part file stays
                pass
        write_json(self.out / SUMMARY, summary.hung(self.head, message, self.sim.t, closed,
                                                    summary.saved_checkpoint(self.saver)))

    def refused(self) -> bool:
        """True if the run failed at its start with nothing computed (a bad --set value, a missing model file, a
        file that cannot be opened, a cycle with no period at t0): its folder is then left as it was found
        (rundir.py takes back the lock and the folders it made) and the caller raises the error alone."""
        if not (self.status == "failed" and self.out is not None and self.point is None and not self.sim.computed):
            return False
        series = self.series
        for f in (self.out / SUMMARY, series, series and series.with_name(series.name + ".part")):
            if f is not None:
                f.unlink(missing_ok=True)
        self.folder.started = False
        return True

    # -- the end ---------------------------------------------------------------------------------------------
    def post_failed(self, error: BaseException) -> None:
        """The run's steps ended by themselves, then making its results raised ``error``: the run is
        ``failed`` with it. Its checkpoint goes all the same (:meth:`finish`): the time series is whole, and a
        ``--resume`` from the checkpoint would only compute again what it holds."""
        self.error, self.status, self._stepped = error, "failed", True

    def summary(self) -> dict:
        """The summary of the run that ended (:func:`.summary.ended`), before the case's results are added."""
        saver = self.saver
        return summary.ended(
            self.head, self.sim, status=self.status, error=self.error, wall_s=self.wall_s,
            resumed_from=self.point.t if self.point else None,
            timeseries=self.series.name if self.series is not None else None,
            saved=summary.saved_checkpoint(saver) if self.status in ("interrupted", "failed") else None,
            checkpoint_note=saver.disabled if saver is not None else None,
            validity=self.validity.entries())

    def recorded(self) -> tuple[dict, list[Path]]:
        """The run's samples (``"time"``, ``"phase"``, one array per signal: in memory, or the time series file
        read when first used) and the files written so far (the time series)."""
        if self.keep:
            # a resumed run holds in memory only what it computed itself (CSV is not read back)
            data = {} if self.point is not None and self.series is not None else self.recorder.data()
        else:
            data = SeriesFile(self.series) if self.series.exists() else _nothing_recorded(self.recorder)
        files = [self.series] if self.series is not None and self.series.exists() else []
        return data, files

    def finish(self, final: dict, files: list[Path]) -> None:
        """With a folder: the summary ``final`` written (first in ``files``), and the checkpoint removed from a run
        that ended by itself. A failed run whose summary cannot be written raises its own error, not this one."""
        if self.out is None:
            return
        try:
            files.insert(0, write_json(self.out / SUMMARY, final))
        except OSError:
            if self.error is None:
                raise
        if self.status in summary.ENDED or self._stepped:
            (self.out / checkpoint.CHECKPOINT).unlink(missing_ok=True)


def _nothing_recorded(recorder: Recorder) -> dict[str, np.ndarray]:
    """The arrays of a run that ended before its time series file was written."""
    return {"time": np.zeros(0), "phase": np.zeros(0, dtype=np.int8),
            **{ref: np.zeros((0, size)) for ref, size in recorder.sizes.items()}}
