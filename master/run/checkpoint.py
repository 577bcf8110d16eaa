"""Checkpoints and resumption of a run; SIGINT/SIGTERM ending a run at a safe point.

A checkpoint (``checkpoint.pkl`` in the run's folder, written whole or not at all) holds everything the rest of the
run depends on: every component's state (the contract's ``get_state``), the master's engine (connection buffers:
averages, extrapolation history, step counts) and thermal-only hold (hand-off windows, measured laws), the run
report (the timeline so far), the schedule's position (``sim.schedule_state``: a timeline's
master/schedule/timeline.py TimelinePosition, the duration and step of the interval it runs, the coupled rest of
a held interval an event cut) and the observers' states (steady windows, peaks, how many rows the time series had).
It is taken by :class:`Checkpointer`, an observer placed last, every ``every_s`` seconds of wall time, at the end of
an interval when the last checkpoint is at least ``min(every_s, END_GAP_S)`` old (with the automatic schedule:
taken at every interval end, written at that pace, and the last one taken written when the run is interrupted or
fails), and when SIGINT/SIGTERM asked the run to stop: always between two base steps, where every
component has completed its step. :func:`resume` restores it into a freshly built simulation of the same scenario
(set up as usual, then overwritten), so the resumed run continues with the very numbers the uninterrupted one had:
its results are bit-identical.

Pickling: components (and the system) are written as references by name (``persistent_id``) and bound to the
new simulation's objects when read, so the master's own objects can be saved whole, whatever their internals.
Reading is guarded (:class:`_Unpickler`): a checkpoint may only name rotorcosim's classes, numpy's arrays and plain
containers, so a hostile or corrupted file is refused (CheckpointError) instead of running what it names.

The automatic schedule is checkpointed at interval ends only (its stop tests decide inside an interval; its own
state, ``sim.schedule_state``, is saved with the rest): interrupted inside an interval, it resumes from the end of
the previous one and recomputes the rest, with the same bit-identical result. FMUs' states cannot be written to
disk through FMI 2.0's Get/SetFMUstate: a system with FMUs is not checkpointed and says so in its summary.

Signals: :class:`StopRequest` turns the first SIGINT or SIGTERM into a request the Checkpointer honours at the next
safe point (a checkpoint, then :class:`RunInterrupted`); a second signal interrupts at once.
"""
from __future__ import annotations

import enum
import errno
import hashlib
import importlib
import io
import json
import os
import pickle
import signal
import struct
import sys
import threading
import time
from pathlib import Path

import numpy as np

from rotorcosim.components.contract import HELD, Component
from rotorcosim.components.bounded_read import MAX_CHECKPOINT_BYTES, read_bytes

from rotorcosim.master.observer.recorder import DISK_RESERVE_BYTES

from rotorcosim.master.observer.observer import Observer
from rotorcosim.master.schedule.timeline import Timeline
from rotorcosim.master.core.system import System

CHECKPOINT = "checkpoint.pkl"
#: the layout of what is pickled (the links' state in master/core/links.py's layout, the hold's restart ramps, a
#: timeline's position in schedule_state): a checkpoint of another format is refused by name
FORMAT = 5
#: wall time between two checkpoints inside a long interval
EVERY_S = 180.0
#: an interval end is checkpointed only when the last checkpoint (or the run's start) is at least this old [s of
#: wall time]: each save costs ~70 ms (pickling the state, flushing the time series, fsync), which a 10-s main
#: job paid at all 11 interval ends; SIGINT/SIGTERM still save where they stop, so this bounds only what a hard
#: kill (SIGKILL, power loss) loses. The automatic schedule, whose only safe points are its interval ends, takes
#: its state at every interval end and writes it at the same pace (a run of hours has hundreds of intervals, each
#: state tens of MB): an interrupt or a failure writes the last one taken.
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


class _Unpickler(pickle._Unpickler):
    """Reads a checkpoint without letting it run code: unpickling calls whatever the file names, so a hostile or
    corrupted ``checkpoint.pkl`` could otherwise execute anything with the user's rights. Only these are let
    through: classes of rotorcosim (and of the system's component modules, for plugins) created with
    ``__new__`` (never their ``__init__``), numpy arrays, dtypes and scalars, and plain containers; any other
    name, and any call of something else, stops the loading with :class:`CheckpointError` naming it. (The pure
    Python unpickler, because the C one cannot tell a constructor call from ``__new__``.)

    ``system`` None (reading the plain fields before a simulation exists): references to components are None
    and a class of another module reads as an inert placeholder."""

    #: the only functions (and call-constructed types) a checkpoint may call, by (module, name)
    CALLABLE = {("numpy", "dtype"), ("numpy.core.multiarray", "_reconstruct"), ("numpy._core.multiarray", "_reconstruct"),
                ("numpy.core.multiarray", "scalar"), ("numpy._core.multiarray", "scalar"),
                ("numpy.core.numeric", "_frombuffer"), ("numpy._core.numeric", "_frombuffer"),
                ("builtins", "set"), ("builtins", "frozenset"), ("builtins", "complex"), ("builtins", "bytearray"),
                ("builtins", "slice"), ("builtins", "range"), ("collections", "OrderedDict"),
                ("collections", "deque")}
    #: types that may be created with __new__ besides the allowed modules' classes
    NEW = {("numpy", "ndarray"), ("builtins", "object"), ("builtins", "set"), ("builtins", "frozenset"),
           ("collections", "OrderedDict"), ("collections", "deque")}

    def __init__(self, data: bytes, system: System | None):
        super().__init__(io.BytesIO(data))
        self.system = system
        #: ids of the allowed globals read so far -> whether the checkpoint may call them (numpy's reconstructors)
        self.found: dict[int, bool] = {}
        self.packages = {"rotorcosim"}
        if system is not None:  # plugins: their state classes live beside their component class
            self.packages |= {type(c).__module__.partition(".")[0] for c in system.components.values()}
        self.dispatch = dict(pickle._Unpickler.dispatch)
        self.dispatch[pickle.REDUCE[0]] = _Unpickler._reduce
        self.dispatch[pickle.NEWOBJ[0]] = _Unpickler._newobj
        self.dispatch[pickle.NEWOBJ_EX[0]] = _Unpickler._newobj_ex
        self.dispatch[pickle.BUILD[0]] = _Unpickler._build
        for op in (pickle.INST, pickle.OBJ):  # protocol 0/1 constructor calls: never written by _dumps
            self.dispatch[op[0]] = _Unpickler._refuse

    def persistent_load(self, pid):
        if self.system is None:
            return None
        if isinstance(pid, tuple) and pid and pid[0] == "component" and len(pid) == 2 \
                and pid[1] in self.system.components:
            return self.system.components[pid[1]]
        if pid == ("system",):
            return self.system
        raise CheckpointError(f"the checkpoint refers to {pid!r}, which this run does not have")

    def find_class(self, module, name):
        if not (isinstance(module, str) and isinstance(name, str)) or "." in name or name.startswith("__"):
            raise CheckpointError(f"the checkpoint names {module}.{name}, which a checkpoint may not hold")
        ours = module.partition(".")[0] in self.packages
        if not ours and (module, name) not in self.CALLABLE | self.NEW:
            if self.system is None:
                return _Opaque
            raise CheckpointError(f"the checkpoint names {module}.{name}, which a checkpoint may not hold")
        if ours and module not in sys.modules:
            importlib.import_module(module)
        obj = getattr(sys.modules.get(module), name, None)
        if obj is None or (ours and not (isinstance(obj, type) and obj.__module__ == module)):
            raise CheckpointError(f"the checkpoint names {module}.{name}, which a checkpoint may not hold")
        self.found[id(obj)] = (module, name) in self.CALLABLE or (isinstance(obj, type) and issubclass(obj, enum.Enum))
        return obj

    def _refuse(self):
        raise CheckpointError("the checkpoint holds an old-protocol constructor call (not written by rotorcosim)")

    def _reduce(self):
        args = self.stack.pop()
        func = self.stack[-1]
        if func is _Opaque:
            self.stack[-1] = _Opaque()
            return
        if not self.found.get(id(func)) or not isinstance(args, tuple):
            raise CheckpointError(f"the checkpoint calls {getattr(func, '__qualname__', type(func).__name__)}, "
                                  "which a checkpoint may not do")
        self.stack[-1] = func(*args)

    def _newobj(self):
        args = self.stack.pop()
        cls = self.stack.pop()
        self.append(self._new(cls, args, {}))

    def _newobj_ex(self):
        kwargs = self.stack.pop()
        args = self.stack.pop()
        cls = self.stack.pop()
        self.append(self._new(cls, args, kwargs))

    def _new(self, cls, args, kwargs):
        if cls is _Opaque:
            return _Opaque()
        if not isinstance(cls, type) or id(cls) not in self.found:
            raise CheckpointError(f"the checkpoint creates {cls!r}, which a checkpoint may not do")
        return cls.__new__(cls, *args, **kwargs)

    def _build(self):
        state = self.stack[-1]
        inst = self.stack[-2]
        if isinstance(inst, _Opaque):
            self.stack.pop()
            return
        # __setstate__ only as the type defines it (an instance attribute of that name would be called)
        setstate = getattr(type(inst), "__setstate__", None)
        if setstate is None:
            dicts = state if isinstance(state, tuple) and len(state) == 2 else (state,)
            if any(isinstance(d, dict) and any(not isinstance(k, str) or k.startswith("__") for k in d)
                   for d in dicts if d):
                raise CheckpointError("the checkpoint sets a special attribute, which a checkpoint may not do")
        pickle._Unpickler.load_build(self)


class _Opaque:
    """What an unknown class reads as while only a checkpoint's plain fields are read (never called)."""

    def __init__(self, *args, **kwargs):
        pass


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
        #: the automatic schedule's last interval end taken and not yet written (bytes), or None
        self.pending: bytes | None = None

    def start(self, sim, schedule):
        # the automatic schedule's stop tests live inside its intervals: only their ends are safe points
        self.interval_ends_only = not isinstance(schedule, Timeline)
        self._last = time.perf_counter()

    def interval_start(self, sim, phase, step):
        # a thermo-mechanical base step is ~0.1-0.3 ms: looking every 64 steps keeps the reaction within ~20 ms
        self.stride = 1 if phase == HELD else 64
        self._t_start = sim.t
        self._step = step
        self._phase = phase

    def step(self, sim, t):
        if self.stop is not None and self.stop.signal:
            if not self.interval_ends_only:
                self.save(sim, round((t - self._t_start) / self._step))
            self.write_pending()
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
        if not self.interval_ends_only and used.reason == "event":
            # a timeline's held interval ended by an event: its coupled rest follows (Timeline.run), not the next
            # interval; the rest's own steps are checkpointed
            return
        due = time.perf_counter() - self._last >= min(self.every_s, END_GAP_S)
        if self.interval_ends_only:
            # its only safe points: each one taken, written at the pace of the others
            self.save(sim, 0, next_interval=True, write=due)
        elif due:
            self.save(sim, 0, next_interval=True)

    def end(self, sim, error):
        if error is not None:   # interrupted or failed: the last interval end taken, for --resume
            self.write_pending()

    def write_pending(self) -> None:
        """Write the last interval end taken and not yet written, if any (module docstring)."""
        data, self.pending = self.pending, None
        if data is not None and self.path is not None and not self.disabled:
            self._write(data)

    def save(self, sim, k: int, next_interval: bool = False, write: bool = True) -> None:
        """Write a checkpoint of ``sim`` at base step ``k`` of its current interval (``next_interval``: at the
        start of the next one), replacing the previous checkpoint whole (``write`` False: taken only, written by
        :meth:`write_pending`). A state that cannot be saved or a full disk disables further checkpoints
        (:attr:`disabled` says why) and the run goes on."""
        self.pending = None
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
        if write:
            self._write(data)
        else:
            self.pending = data

    def _write(self, data: bytes) -> None:
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
        try:
            data = _Unpickler(self.raw, sim.system).load()
        except CheckpointError as exc:
            raise CheckpointError(f"--resume: the checkpoint cannot be used: {exc}") from None
        except Exception as exc:
            raise CheckpointError(f"--resume: the checkpoint is not readable ({type(exc).__name__}: {exc})") from None
        sim.engine = data["engine"]
        sim.hold = data["hold"]  # pickled with the engine: it shares the engine's connection objects
        if sim.revolutions is not None:  # the windows count the turns this run's observer records
            sim.hold.bind_revolutions(sim.revolutions)
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
    """The checkpoint file ``path`` as a point to resume from; ``key`` identifies the run (scenario and options):
    a checkpoint of another run, version or a damaged file is a CheckpointError saying which."""
    path = Path(path)
    raw = None
    try:
        raw = read_bytes(path, "checkpoint", MAX_CHECKPOINT_BYTES)
        data = _peek(raw)
    except FileNotFoundError:
        raise CheckpointError(f"--resume: no checkpoint {path}") from None
    except Exception as exc:
        # checkpoints are pickles of protocol >= 2, which begin with the PROTO opcode (0x80)
        why = ("cannot be read" if raw is None else "empty" if not raw else
               "not a checkpoint" if raw[:1] != b"\x80" else
               "truncated" if _ended_early(exc) else "damaged")
        raise CheckpointError(f"--resume: {path} is not a readable checkpoint ({why}: {type(exc).__name__}: "
                              f"{exc}); run again without --resume, into a new folder or with --overwrite") from None
    if data.get("format") != FORMAT:
        raise CheckpointError(f"--resume: {path} was written by another version of rotorcosim")
    if data.get("key") != key:
        raise CheckpointError(f"--resume: {path} was written by a run of another scenario or with other options "
                              "(level, duration, schedule, outputs, --record): resume with the same command")
    return ResumePoint(raw, data)


def _ended_early(exc: Exception) -> bool:
    """Did the unpickler fail by reading past the end of the data? An opcode cut from its argument fails in the
    read of that argument: an empty read (EOFError, a frame "exhausted"), a byte taken from nothing (IndexError
    "index out of range": a one-byte integer or length) or a number unpacked from too few bytes (struct.error)."""
    return (isinstance(exc, EOFError) or "exhausted" in str(exc)
            or (isinstance(exc, IndexError) and str(exc) == "index out of range")
            or (isinstance(exc, struct.error) and "requires a buffer" in str(exc)))


def _peek(raw: bytes) -> dict:
    """The checkpoint's plain fields, without binding its references (no simulation yet)."""
    data = _Unpickler(raw, None).load()
    if not isinstance(data, dict):
        raise CheckpointError("not a checkpoint's table of fields")
    return data


def resume(sim, schedule, point: ResumePoint):
    """Continue ``sim`` (built afresh from the same scenario, observers in the same order) from ``point``."""
    if isinstance(schedule, Timeline) and point.interval > len(schedule.intervals):
        raise CheckpointError("--resume: the checkpoint lies beyond this schedule's end")
    sim.resume_point = point
    return sim.run(schedule)
