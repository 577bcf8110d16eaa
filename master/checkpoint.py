"""Checkpoints and resumption of a run; SIGINT/SIGTERM ending a run at a safe point.

A checkpoint (``checkpoint.pkl`` in the run's folder, written whole or not at all) holds everything the rest of the
run depends on: every component's state (the contract's ``get_state``), the master's engine (connection buffers:
averages, extrapolation history, step counts) and thermal-only hold (hand-off windows, measured laws), the run
report (the timeline so far) and the observers' states (steady windows, peaks, how many rows the time series had).
It is taken by :class:`Checkpointer`, an observer placed last, every ``every_s`` seconds of wall time, at the end of
an interval when the last checkpoint is at least ``min(every_s, END_GAP_S)`` old (every interval end with the
automatic schedule), and when SIGINT/SIGTERM asked the run to stop: always between two base steps, where every
component has completed its step. :func:`resume` restores it into a freshly built simulation of the same scenario
(set up as usual, then overwritten), so the resumed run continues with the very numbers the uninterrupted one had:
its results are bit-identical.

Pickling: components (and the system) are written as references by name (``persistent_id``) and bound to the
new simulation's objects when read, so the master's own objects can be saved whole, whatever their internals.

The automatic schedule is checkpointed at interval ends only (its stop tests decide inside an interval; its own
state, ``sim.schedule_state``, is saved with the rest): interrupted inside an interval, it resumes from the end of
the previous one and recomputes the rest, with the same bit-identical result. FMUs' states cannot be written to
disk through FMI 2.0's Get/SetFMUstate: a system with FMUs is not checkpointed and says so in its summary.

Signals: :class:`StopRequest` turns the first SIGINT or SIGTERM into a request the Checkpointer honours at the next
safe point (a checkpoint, then :class:`RunInterrupted`); a second signal interrupts at once.
"""
from __future__ import annotations

import errno
import hashlib
import io
import json
import os
import pickle
import signal
import threading
import time
from pathlib import Path

import numpy as np

from rotorcosim.components.contract import Component

from .observers import DISK_RESERVE_BYTES, Observer
from .schedule import Timeline
from .system import System

CHECKPOINT = "checkpoint.pkl"
#: 3: the hold keeps the restart ramps of its hand-backs (links carry `ramp`): a format-2 checkpoint lacks them
FORMAT = 3
#: wall time between two checkpoints inside a long interval
EVERY_S = 180.0
#: an interval end is checkpointed only when the last checkpoint (or the run's start) is at least this old [s of
#: wall time]: each save costs ~70 ms (pickling the state, flushing the time series, fsync), which a 10-s main
#: job paid at all 11 interval ends; SIGINT/SIGTERM still save where they stop, so this bounds only what a hard
#: kill (SIGKILL, power loss) loses. The automatic schedule saves every interval end (its only safe points).
END_GAP_S = 30.0


class RunInterrupted(KeyboardInterrupt):
    """The run was asked to stop (SIGINT/SIGTERM); what was computed is kept and the run can be resumed."""


class CheckpointError(ValueError):
    """A checkpoint that cannot be used to resume this run (the message says why)."""


# -- signals ----------------------------------------------------------------------------------------
class StopRequest:
    """``with StopRequest() as stop:`` SIGINT/SIGTERM set ``stop.signal`` (the first) or interrupt at once (a
    second one). Outside the main thread (Dask workers) no handler is installed."""

    def __init__(self):
        self.signal: str | None = None
        self._old = {}

    def __enter__(self) -> "StopRequest":
        if threading.current_thread() is threading.main_thread():
            for sig in (signal.SIGINT, signal.SIGTERM):
                self._old[sig] = signal.signal(sig, self._handle)
        return self

    def _handle(self, signum, frame) -> None:
        name = signal.Signals(signum).name
        if self.signal is not None:
            raise RunInterrupted(f"{name} received twice: stopped at once")
        self.signal = name

    def __exit__(self, *exc) -> None:
        for sig, old in self._old.items():
            signal.signal(sig, old)
        self._old.clear()


# -- saving -----------------------------------------------------------------------------------------
class _Pickler(pickle.Pickler):
    def persistent_id(self, obj):
        if isinstance(obj, Component):
            return ("component", obj.name)
        if isinstance(obj, System):
            return ("system",)
        return None


class _Unpickler(pickle.Unpickler):
    def __init__(self, data: bytes, system: System):
        super().__init__(io.BytesIO(data))
        self.system = system

    def persistent_load(self, pid):
        if pid[0] == "component":
            return self.system.components[pid[1]]
        if pid[0] == "system":
            return self.system
        raise pickle.UnpicklingError(f"unknown reference {pid!r}")


def _dumps(obj) -> bytes:
    buf = io.BytesIO()
    _Pickler(buf, protocol=pickle.HIGHEST_PROTOCOL).dump(obj)
    return buf.getvalue()


def fingerprint(*parts) -> str:
    """A digest of what makes a run what it is (scenario, schedule, options): a checkpoint resumes only its own."""
    text = json.dumps([repr(p) for p in parts], sort_keys=True)
    return hashlib.sha256(text.encode()).hexdigest()[:16]


class Checkpointer(Observer):
    """Saves checkpoints (see the module's docstring) and ends the run at a safe point when asked to stop.
    ``path`` None: no checkpoints, only the stop request is honoured. Must be the last observer."""

    def __init__(self, path: str | os.PathLike | None, stop: StopRequest | None = None, every_s: float = EVERY_S,
                 key: str = ""):
        self.path = Path(path) if path is not None else None
        self.stop = stop
        self.every_s = float(every_s)
        self.key = key
        self.saved = 0
        self.disabled: str | None = None
        self.interval_ends_only = False

    def start(self, sim, schedule):
        # the automatic schedule's stop tests live inside its intervals: only their ends are safe points
        self.interval_ends_only = not isinstance(schedule, Timeline)
        self._last = time.perf_counter()

    def interval_start(self, sim, phase, step):
        # a thermo-mechanical base step is ~0.1-0.3 ms: looking every 64 steps keeps the reaction within ~20 ms
        self.stride = 1 if phase == "TO" else 64
        self._t_start = sim.t
        self._step = step
        self._phase = phase

    def step(self, sim, t):
        if self.stop is not None and self.stop.signal:
            if not self.interval_ends_only:
                self.save(sim, round((t - self._t_start) / self._step))
            raise RunInterrupted(f"{self.stop.signal} received: stopped at t = {t:.9g} s")
        if self.interval_ends_only:
            return
        if self.path is not None and time.perf_counter() - self._last >= self.every_s:
            self.save(sim, round((t - self._t_start) / self._step))

    def block_signals(self, sim):
        return []

    def step_block(self, sim, ks, ts, data):
        # the compiled engine: the components hold the state after the block's last step, a safe point
        if (np.asarray(ks) % self.stride == 0).any():
            self.step(sim, float(ts[-1]))

    def interval_end(self, sim, used):
        # the position is the start of the next interval; the report already holds this one
        self._t_start = sim.t
        if self.interval_ends_only or time.perf_counter() - self._last >= min(self.every_s, END_GAP_S):
            self.save(sim, 0, next_interval=True)

    def save(self, sim, k: int, next_interval: bool = False) -> None:
        if self.path is None or self.disabled:
            return
        index = sim.interval_index + (1 if next_interval else 0)
        try:
            comps = {n: c.get_state() for n, c in sim.system.components.items()}
            data = _dumps({
                "format": FORMAT, "key": self.key, "interval": index, "k": k, "t_start": self._t_start,
                "t": sim.t, "components": comps, "engine": sim.engine, "hold": sim.hold, "report": sim.report,
                "schedule_state": sim.schedule_state,
                "observers": [o.checkpoint_state() for o in sim.observers if o is not self],
            })
        except Exception as exc:  # an FMU's state (a pointer into the FMU), or another unpicklable object
            self.disabled = f"the run's state cannot be saved to disk ({type(exc).__name__}: {exc})"
            return
        tmp = self.path.with_name(self.path.name + ".part")
        try:
            st = os.statvfs(self.path.parent)
            if st.f_bavail * st.f_frsize < 2 * len(data) + DISK_RESERVE_BYTES:
                raise OSError(errno.ENOSPC, "No space left on device")
            with open(tmp, "wb") as f:
                f.write(data)
                f.flush()
                os.fsync(f.fileno())
            os.replace(tmp, self.path)
        except OSError as exc:  # a nearly full disk: the run goes on (the recorder will say it), unsaved
            tmp.unlink(missing_ok=True)
            self.disabled = f"checkpoint not written ({exc.strerror or exc}); the last one saved is kept"
            return
        self.saved += 1
        self._last = time.perf_counter()


# -- resuming ---------------------------------------------------------------------------------------
class ResumePoint:
    """A loaded checkpoint; :meth:`restore` puts it into a simulation (see Simulation.run / run_interval)."""

    def __init__(self, raw: bytes, data: dict):
        self.raw = raw
        self.interval = int(data["interval"])
        self.k = int(data["k"])
        self.t_start = float(data["t_start"])
        self.t = float(data["t"])

    def restore(self, sim) -> None:
        """Everything the checkpoint holds into ``sim`` (a fresh unpickling each time: the master's objects
        are replaced, never shared with an earlier restore)."""
        data = _Unpickler(self.raw, sim.system).load()
        sim.engine = data["engine"]
        sim.hold = data["hold"]  # pickled with the engine: it shares the engine's connection objects
        sim.report = data["report"]
        sim.schedule_state = data["schedule_state"]
        for name, snap in data["components"].items():
            sim.system.components[name].set_state(snap)
        observers = [o for o in sim.observers if not isinstance(o, Checkpointer)]
        if len(observers) != len(data["observers"]):
            raise CheckpointError("the checkpoint was written with other observers (outputs or results differ)")
        for obs, state in zip(observers, data["observers"]):
            obs.restore_checkpoint(state)
        sim.t = self.t_start


def load(path: str | os.PathLike, key: str) -> ResumePoint:
    path = Path(path)
    try:
        raw = path.read_bytes()
        data = _peek(raw)
    except FileNotFoundError:
        raise CheckpointError(f"--resume: no checkpoint {path}") from None
    except Exception as exc:
        raise CheckpointError(f"--resume: {path} is not a readable checkpoint ({type(exc).__name__}: {exc})") from None
    if data.get("format") != FORMAT:
        raise CheckpointError(f"--resume: {path} was written by another version of rotorcosim")
    if data.get("key") != key:
        raise CheckpointError(f"--resume: {path} was written by a run of another scenario or with other options "
                              "(unbalance, duration, schedule, outputs): resume with the same command")
    return ResumePoint(raw, data)


def _peek(raw: bytes) -> dict:
    """The checkpoint's plain fields, without binding its references (no simulation yet)."""

    class Peek(pickle.Unpickler):
        def persistent_load(self, pid):
            return None

    return Peek(io.BytesIO(raw)).load()


def resume(sim, schedule, point: ResumePoint):
    """Continue ``sim`` (built afresh from the same scenario, observers in the same order) from ``point``."""
    if isinstance(schedule, Timeline) and point.interval > len(schedule.intervals):
        raise CheckpointError("--resume: the checkpoint lies beyond this schedule's end")
    sim.resume_point = point
    return sim.run(schedule)
