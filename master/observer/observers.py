"""Observers: they watch a run without changing it (libcosim's split).

* :class:`Recorder`: decimated time series streamed to disk while the run goes (HDF5 by h5py, or CSV), flushed
  in chunks, so a crash loses nothing already flushed; readable without this project.
* :class:`Progress`: a tqdm bar over simulated time.
* :class:`SteadyWindows`: the last ``cycles`` cycles of chosen signals at the end of every TM interval,
  kept in memory for result extraction (a case's steady-state results are read from them).
"""
from __future__ import annotations

import csv
import errno
import math
import os
from pathlib import Path
from typing import Sequence

import numpy as np

from rotorcosim.components.contract import COUPLED, HELD
from rotorcosim.master.core.cycle import WINDOW_MARGIN, Cycle, as_cycle
from rotorcosim.master.core.phases import Phases

#: empty HDF5 files of this process's recordings by layout (Recorder._open): bytes, the last few layouts
_H5_TEMPLATES: dict[tuple, bytes] = {}
#: free space a recorder keeps on its disk, so that a file refused a write can still be closed whole
DISK_RESERVE_BYTES = 4 * 1024 ** 2


def sampled_rows(ks: np.ndarray, stride: int) -> np.ndarray:
    """The rows of a compiled-loop block (step numbers ``ks``, an integer array) that an observer of ``stride``
    would have seen through ``step()``: the generic loop calls it when ``k % stride == 0``."""
    return np.flatnonzero(np.asarray(ks) % stride == 0)


class Observer:
    """Watches a run without changing it: the simulation calls its hooks (each does nothing by default).

    ``sim`` in every hook is the running :class:`~rotorcosim.master.simulation.Simulation` (``sim.t`` [s],
    ``sim.phase``, ``sim.value("comp.port")``). :attr:`stride`: :meth:`step` is called every ``stride``-th base
    step. An observer that also offers :meth:`block_signals` and :meth:`step_block` lets the compiled engine run
    (it hands over base steps in blocks); one that does not keeps the run on the generic loop.

    >>> class PeakPosition(Observer):
    ...     def __init__(self, ref):
    ...         self.ref, self.peak = ref, 0.0
    ...     def step(self, sim, t):
    ...         self.peak = max(self.peak, abs(float(sim.value(self.ref)[0])))
    >>> from rotorcosim.components.registry import create
    >>> from rotorcosim.master.core.system import Connection, System
    >>> from rotorcosim.master.schedule import Interval, Timeline
    >>> from rotorcosim.master.simulation import Simulation
    >>> system = System({"m1": create("testing.mass", "m1", {"m": 1.0, "k": 40.0, "x0": 0.1})}, [],
    ...                 inputs={"m1.F": 0.0})
    >>> peak = PeakPosition("m1.x")
    >>> report = Simulation(system, observers=[peak]).run(Timeline([Interval("TM", 1.0, 1e-3)]))
    >>> round(peak.peak, 3)                                          # the initial displacement [m]
    0.1
    """

    #: base steps between two calls of :meth:`step`
    stride = 1

    def start(self, sim, schedule) -> None:
        """The run starts (after the components' set-up); ``schedule`` is the one it runs."""
        pass

    def interval_start(self, sim, phase: str, step: float) -> None:
        """An interval starts at ``sim.t`` with base step ``step`` [s]; ``phase`` is its role (``COUPLED`` or
        ``HELD`` of the component contract; its name is ``sim.phase_name``)."""
        pass

    def step(self, sim, t: float) -> None:
        """A base step ended at time ``t`` [s] (called every :attr:`stride` steps, and at the start)."""
        pass

    def interval_end(self, sim, used) -> None:
        """An interval ended; ``used`` is its :class:`~rotorcosim.master.schedule.timeline.UsedInterval`."""
        pass

    def end(self, sim, error: BaseException | None) -> None:
        """The run ended: ``error`` is what ended it early, or None."""
        pass

    # the compiled engine (master/compiled/runner.py) runs base steps in chunks and hands them over in one call: an
    # observer that offers step_block names the signals it reads; None (the default) keeps the generic loop
    def block_signals(self, sim) -> list[str] | None:
        """The outputs (``"comp.port"``) :meth:`step_block` reads, or None: this observer needs :meth:`step`
        at every base step (the generic loop)."""
        return None

    def step_block(self, sim, ks: np.ndarray, ts: np.ndarray, data: dict) -> None:
        """Base steps ``ks`` (the interval's step counts after each step, an integer array) at times ``ts`` (an
        array): the same calls as
        ``step(sim, t)`` for every k with ``k % stride == 0``. ``data[ref]`` holds one row per base step of each
        signal named by :meth:`block_signals` (rows valid during the call only); the components hold the state
        after the last of them."""
        raise NotImplementedError

    # checkpoints (master/run/checkpoint.py): what the observer needs to continue an interrupted run; components
    # referenced from it are saved by name. The default keeps the observer's attributes.
    def checkpoint_state(self):
        """What this observer needs to continue an interrupted run (picklable; by default its attributes)."""
        return dict(self.__dict__)

    def restore_checkpoint(self, state) -> None:
        """Continue from ``state`` (:meth:`checkpoint_state`'s) of an interrupted run."""
        self.__dict__.update(state)


class Recorder(Observer):
    """Records ``signals`` ("component.port") every ``record_step`` seconds of a TM interval and at every step
    of a TO interval, into ``path`` (``.h5`` / ``.hdf5``: one dataset per signal plus ``time`` and ``phase``;
    ``.csv``: one column per vector element, ``component.port[label] (unit)``) and, with ``keep=True``, in
    memory as well (:meth:`data`), so that the caller gets the run back without reopening the file.
    ``path=None`` records in memory only.

    Each HDF5 dataset carries its ``unit``, ``description``, ``columns`` (the names of its vector elements) and
    ``sampling_interval_s`` (the interval in thermo-mechanical intervals; thermal-only intervals are sampled at
    every thermal step: the ``time`` dataset gives each sample's time). ``attributes``: root attributes of the
    HDF5 file (name -> str or number), or a function returning them, written when the file is completed (what
    made the run: master/run/provenance.py)."""

    def __init__(self, path: str | os.PathLike | None, signals: Sequence[str], record_step: float = 1e-4,
                 chunk: int = 2048, keep: bool = False, attributes=None):
        self.path = None if path is None else Path(path)
        self.attributes = attributes
        self.signals = list(signals)
        if not (record_step > 0 and math.isfinite(record_step)):
            raise ValueError(f"record_step must be positive, got {record_step}")
        self.record_step = float(record_step)
        self.chunk = int(chunk)
        self.keep = bool(keep) or self.path is None
        self.rows = 0
        # buffered rows, as blocks of rows (one row from step(), many from step_block())
        self._buffered = 0
        self._buf_t: list[np.ndarray] = []
        self._buf_phase: list[np.ndarray] = []
        self._buf: dict[str, list[np.ndarray]] = {s: [] for s in self.signals}
        self._kept: dict[str, list[np.ndarray]] = {s: [] for s in ["time", "phase", *self.signals]}
        self._file = None
        self._datasets = None    # the HDF5 file's datasets by name (flush)
        self._resume = None
        self._kind = None
        self.variables = {}
        self.sizes: dict[str, int] = {}

    # -- observer hooks --------------------------------------------------------------------------------
    def start(self, sim, schedule):
        for ref in self.signals:
            comp, _, port = ref.partition(".")
            if comp not in sim.system.components:
                raise ValueError(f"recorder: unknown signal {ref!r}: no component {comp!r} "
                                 f"(components: {', '.join(sim.system.components)})")
            c = sim.system.components[comp]
            v = next((x for x in c.variables if x.name == port), None)
            if v is None or v.causality != "output":
                outs = ", ".join(x.name for x in c.variables if x.causality == "output")
                raise ValueError(f"recorder: unknown signal {ref!r}: {comp} has no output {port!r} (its outputs: {outs})")
            if not v.carried:
                raise ValueError(f"recorder: {ref} is a {v.fmi_type or v.type} output: it holds no value to record")
            self.variables[ref] = v
        self.sizes = {r: v.size for r, v in self.variables.items()}
        self._phases = sim.phases
        self.units = {r: v.unit for r, v in self.variables.items()}
        # each signal is stored with its own type: floats as f8, integers as i8 (UInt64 as u8), Booleans as
        # bool, strings as UTF-8 strings; so an integer beyond 2^53 is kept exactly
        self._dtypes = {ref: _h5_dtype(v.type, v.fmi_type) for ref, v in self.variables.items()}
        if self.path is not None and getattr(self, "_resume", None) is not None:
            self._open()  # a resumed run: the file holds the rows up to the checkpoint, its first sample too
            return
        if self.path is not None:
            self._open()
        self._sample(sim, sim.t)

    def _open(self):
        self.path.parent.mkdir(parents=True, exist_ok=True)
        tmp = self.path.with_name(self.path.name + ".part")
        self._tmp = tmp
        resume = getattr(self, "_resume", None)
        if resume is not None:
            self._reopen(resume)
            return
        sizes, units = self.sizes, self.units
        if self.path.suffix.lower() in (".h5", ".hdf5"):
            import h5py

            # the empty file (attributes and datasets, no rows) is made once per process and layout and copied:
            # its ~110 attributes and ~30 datasets cost ~16 ms per run through h5py, the copy and open ~5 ms
            key = (self.record_step, self.chunk, self._phases, tuple(
                (ref, sizes[ref], self.variables[ref].type, self.variables[ref].fmi_type, units[ref],
                 self.variables[ref].description, tuple(self.variables[ref].column_labels())) for ref in self.signals))
            blob = _H5_TEMPLATES.get(key)
            if blob is None:
                with h5py.File(tmp, "w") as f:
                    self._skeleton(f)
                blob = tmp.read_bytes()
                if len(_H5_TEMPLATES) >= 8:
                    _H5_TEMPLATES.pop(next(iter(_H5_TEMPLATES)))
                _H5_TEMPLATES[key] = blob
            else:
                tmp.write_bytes(blob)
            # no chunk cache: the recorder writes each chunk once, whole, and never reads it back; h5py's default
            # (1 MiB a dataset) held the last chunks written of every dataset, ~10 MB more per simulated second
            # of a monolithic run up to ~1 MiB x its ~30 datasets (measured: a 2 s run peaked 20 MB above a
            # 0.2 s one)
            self._file = h5py.File(tmp, "r+", rdcc_nbytes=0)
            self._datasets = None
            self._kind = "hdf5"
        elif self.path.suffix.lower() == ".csv":
            self._file = open(tmp, "w", newline="")
            self._csv = csv.writer(self._file)
            self._csv.writerow(["time (s)", "phase"] + column_names(self.signals, self.variables))
            self._kind = "csv"
        else:
            raise ValueError(f"recorder: unknown format of {self.path} (use .h5 or .csv)")

    def _skeleton(self, f) -> None:
        """The attributes and empty datasets of a new HDF5 file ``f``."""
        sizes, units = self.sizes, self.units
        f.attrs["description"] = f"rotorcosim time series: SI units; phase {self._phases.description(tags=False)}"
        f.attrs["sampling_interval_s"] = self.record_step
        f.attrs["sampling"] = (f"every {self.record_step:g} s in thermo-mechanical intervals, every thermal step in "
                               f"thermal-only intervals (the time dataset has each sample's time)")
        f.create_dataset("time", shape=(0,), maxshape=(None,), dtype="f8", chunks=(self.chunk,))
        f["time"].attrs["unit"] = "s"
        f["time"].attrs["description"] = "simulated time of each sample"
        f.create_dataset("phase", shape=(0,), maxshape=(None,), dtype="i1", chunks=(self.chunk,))
        f["phase"].attrs["description"] = self._phases.description()
        for ref in self.signals:
            v = self.variables[ref]
            ds = f.create_dataset(ref, shape=(0, sizes[ref]), maxshape=(None, sizes[ref]), dtype=self._dtypes[ref],
                                  chunks=(self.chunk, sizes[ref]))
            ds.attrs["unit"] = units[ref]
            ds.attrs["description"] = v.description
            ds.attrs["columns"] = [lb or v.name for lb in v.column_labels()]
            ds.attrs["sampling_interval_s"] = self.record_step

    def interval_start(self, sim, phase, step):
        # capped: a record_step longer than any interval (1e308 overflowed) records each interval's first sample
        self.stride = 1 if phase == HELD else max(1, int(round(min(self.record_step / step, 2.0 ** 62))))

    def step(self, sim, t):
        self._sample(sim, t)

    def block_signals(self, sim):
        return list(self.signals)

    def step_block(self, sim, ks, ts, data):
        stride = self.stride
        phase = Phases.code(sim.phase)
        rows = sampled_rows(ks, stride)
        if not len(rows):
            return
        # a block is split where a flush falls, so that the file's chunks are the generic loop's
        start = 0
        while start < len(rows):
            take = rows[start:start + self.chunk - self._buffered]
            self._buf_t.append(np.asarray(ts)[take])
            self._buf_phase.append(np.full(len(take), phase, dtype=np.int8))
            for ref in self.signals:
                self._buf[ref].append(data[ref][take].copy())
            self._buffered += len(take)
            start += len(take)
            if self._buffered >= self.chunk:
                self.flush()

    def _sample(self, sim, t):
        self._buf_t.append(np.array([t], dtype=float))
        self._buf_phase.append(np.array([Phases.code(sim.phase)], dtype=np.int8))
        for ref in self.signals:
            self._buf[ref].append(np.array(sim.value(ref))[None])
        self._buffered += 1
        if self._buffered >= self.chunk:
            self.flush()

    def _ensure_space(self, n: int) -> None:
        """Refuse a write the disk cannot hold, BEFORE writing: HDF5 does not survive a failed write (the file
        cannot be closed and the process may crash: measured on a full tmpfs), so the last flush must stay the
        last complete one, with room left to close the file."""
        width = 2 + sum(self.sizes.values())
        need = 2 * n * width * 8 + DISK_RESERVE_BYTES
        try:
            st = os.statvfs(self._tmp.parent)
        except (OSError, AttributeError):
            return
        free = st.f_bavail * st.f_frsize
        if free < need:
            raise OSError(errno.ENOSPC, f"No space left on device for the time series ({free // 1024} KiB free, "
                                        f"{need // 1024} KiB needed to write {n} more rows and close the file); "
                                        f"the {self.rows} rows written so far are kept", str(self.path))

    def flush(self):
        """Write the buffered rows to the file (a full disk ends the run with what was flushed kept)."""
        n = self._buffered
        if not n:
            return
        if self._file is None and self._kind is not None:
            raise ValueError(f"recorder: {self.path} was closed at the end of the run; a run that goes on after "
                             f"its end needs a new recorder")
        if self._file is not None:
            self._ensure_space(n)
        t, ph = np.concatenate(self._buf_t), np.concatenate(self._buf_phase)
        block = {ref: np.concatenate(self._buf[ref]) for ref in self.signals}
        if self.keep:
            self._kept["time"].append(t)
            self._kept["phase"].append(ph)
            for ref in self.signals:
                self._kept[ref].append(block[ref])
        if self._kind == "hdf5":
            f = self._file
            r = self.rows
            if self._datasets is None:  # opened once per file, not at every flush, and by h5py's low-level open:
                # the same datasets as f[name] (which also resolves links and object types), ~0.03 against ~0.1 ms
                # each, ~2 ms of every run's first flush
                import h5py

                self._datasets = {name: h5py.Dataset(h5py.h5d.open(f.id, name.encode()))
                                  for name in ("time", "phase", *self.signals)}
            ds = self._datasets
            _append(ds["time"], r, t)
            _append(ds["phase"], r, ph)
            for ref in self.signals:
                _append(ds[ref], r, block[ref])
            f.flush()
        elif self._kind == "csv":
            for i, (tt, p) in enumerate(zip(t, ph)):
                row = [f"{tt:.10g}", str(p)]
                for ref in self.signals:
                    row += [_csv_text(x) for x in block[ref][i]]
                self._csv.writerow(row)
            self._file.flush()
        self.rows += n
        self._clear_buffer()

    def _clear_buffer(self):
        self._buffered = 0
        self._buf_t.clear()
        self._buf_phase.clear()
        for ref in self.signals:
            self._buf[ref].clear()

    def data(self) -> dict[str, np.ndarray]:
        """What was recorded so far (kept in memory): ``time``, ``phase`` (0 TM, 1 TO) and one (n, size) array
        per signal."""
        if not self.keep:
            raise ValueError("recorder: created with keep=False, nothing kept in memory")
        out = {}
        for key, parts in self._kept.items():
            if parts:
                out[key] = np.concatenate(parts)
            elif key in ("time", "phase"):
                out[key] = np.zeros(0, dtype=float if key == "time" else np.int8)
            else:
                out[key] = np.zeros((0, self.sizes.get(key, 1)))
        return out

    def end(self, sim, error):
        if self._file is None:  # in memory only
            self.flush()
            return
        failed = None
        try:
            try:
                self.flush()
            except OSError as exc:  # disk full: what was flushed before stays readable
                failed = exc
                error = error or exc
                self._clear_buffer()
            if self._kind == "hdf5":
                extra = self.attributes() if callable(self.attributes) else (self.attributes or {})
                for key, value in extra.items():
                    self._file.attrs[key] = value
                self._file.attrs["complete"] = error is None
                if error is not None:
                    self._file.attrs["error"] = f"{type(error).__name__}: {error}"
        finally:
            try:
                self._file.close()
            finally:
                self._file = self._datasets = None
                # the final name appears only when the file is closed (the .part file is what a crash leaves)
                os.replace(self._tmp, self.path)
        if failed is not None:
            raise failed

    # -- checkpoints (master/run/checkpoint.py) --------------------------------------------------------------
    def checkpoint_state(self):
        self.flush()
        state = {"rows": self.rows}
        if self._kind == "csv":
            state["bytes"] = self._file.tell()
        return state

    def restore_checkpoint(self, state):
        if self._file is None:  # before start(): start() reopens the file at the checkpoint's row
            self._resume = state

    def _reopen(self, state):
        """Continue the file of an interrupted run, cut back to the rows it had at the checkpoint."""
        src = self.path if self.path.exists() else self._tmp
        if not src.exists():
            raise ValueError(f"recorder: {self.path} is missing: the interrupted run's time series cannot be continued")
        os.replace(src, self._tmp)
        n = int(state["rows"])
        if self.path.suffix.lower() in (".h5", ".hdf5"):
            import h5py

            try:
                f = h5py.File(self._tmp, "r+")
            except OSError as exc:
                os.replace(self._tmp, self.path)  # the folder stays as the interrupted run left it
                raise ValueError(f"recorder: {self.path} cannot be reopened ({exc}): resume impossible") from None
            for name in ["time", "phase"] + self.signals:
                ds = f.get(name)
                short = ds is None or not hasattr(ds, "resize") or ds.shape[0] < n
                if short:
                    f.close()
                    os.replace(self._tmp, self.path)
                    what = f"has no dataset {name!r}" if ds is None or not hasattr(ds, "resize") else \
                        "has fewer rows than its checkpoint"
                    raise ValueError(f"recorder: {self.path} {what}: resume impossible")
                ds.resize((n,) + ds.shape[1:])
            for key in ("complete", "error"):
                if key in f.attrs:
                    del f.attrs[key]
            self._file, self._kind, self._datasets = f, "hdf5", None
        else:
            self._file = open(self._tmp, "r+", newline="")
            self._file.truncate(int(state["bytes"]))
            self._file.seek(int(state["bytes"]))
            self._csv = csv.writer(self._file)
            self._kind = "csv"
        self.rows = n
        self._resume = None


def _append(ds, r: int, data: np.ndarray) -> None:
    """Write ``data`` as rows r.. of the resizable dataset ``ds``. Float rows go through h5py's low-level write,
    the same bytes as ``ds[r:] = data`` without its selection machinery: at every flush of every dataset it
    cost ~0.2 ms more (measured: a 2 048-row flush of the shipped case's recording 16 -> 8 ms of CPU)."""
    ds.resize((r + len(data),) + ds.shape[1:])
    if data.dtype == np.float64 and ds.dtype == np.float64 and data.flags.c_contiguous and len(data):
        from h5py import h5s

        space = ds.id.get_space()
        space.select_hyperslab((r,) + (0,) * (data.ndim - 1), data.shape)
        ds.id.write(h5s.create_simple(data.shape), space, data)
    else:
        ds[r:] = data


def _h5_dtype(kind: str, fmi_type: str):
    if kind == "Real":
        return "f8"
    if kind == "Integer":
        return "u8" if fmi_type == "UInt64" else "i8"
    if kind == "Boolean":
        return "?"
    import h5py

    return h5py.string_dtype("utf-8")


def _csv_text(x) -> str:
    if isinstance(x, (float, np.floating)):
        return f"{x:.10g}"
    if isinstance(x, (bool, np.bool_)):
        return "1" if x else "0"
    return str(x)


def column_names(signals: Sequence[str], variables: dict) -> list[str]:
    """Flat column names with units, one per vector element: ``osc.x[0] (m)``, ``node.T (K)``."""
    out = []
    for ref in signals:
        v = variables[ref]
        for lb in v.column_labels():
            out.append(f"{ref}[{lb}] ({v.unit})" if lb else f"{ref} ({v.unit})")
    return out


class Progress(Observer):
    """A progress bar over simulated time whose time-left estimate comes from the measured wall time per step
    of each phase and the steps the schedule still has: a thermo-mechanical step costs hundreds of times a
    thermal-only one, so a rate in simulated seconds per second (tqdm's own estimate) is wrong by hours early in
    a staggered run. A phase not yet measured costs its ``prior`` price (``{COUPLED: s, HELD: s}`` per step, the
    up-front estimate's: master/schedule/budget.py), or else what the measured one does (an upper bound for
    thermal-only steps). The measurement starts once the run's first compilations are over
    (``sim.first_compiled``): on a fresh machine the first steps wait for numba, and a rate measured over them
    overstates the time left tenfold or more. Without a known plan (the automatic schedule) no
    estimate is shown."""

    stride = 64
    #: the wall time [s] a phase must have been measured over before its measured price replaces the prior
    SETTLE_S = 0.5

    def __init__(self, total: float, disable: bool = False, desc: str = "simulating", prior: dict | None = None):
        self.total = total
        self.disable = disable
        self.desc = desc
        self.prior = dict(prior or {})
        self.bar = None

    def start(self, sim, schedule):
        from tqdm import tqdm

        import time as _time

        self._clock = _time.perf_counter
        intervals = getattr(schedule, "intervals", None)
        # steps of each planned interval, in order (None: not known in advance)
        self.plan = None if intervals is None else [
            (sim.phases.role(iv.phase), max(1, int(math.ceil(iv.duration / iv.step - 1e-9)))) for iv in intervals]
        self.index = -1
        self.cost_wall = {}   # phase -> wall seconds spent in finished intervals
        self.cost_steps = {}  # phase -> steps taken in finished intervals
        self.bar = tqdm(total=self.total, unit="s", desc=self.desc, disable=self.disable, mininterval=1.0,
                        bar_format="{l_bar}{bar}| {n:.3f}/{total:.3f} s simulated [{elapsed}{postfix}]")
        self.t0 = sim.t
        self.shown = 0.0
        self._shown_at = -1e9
        # the run's first compilations (None: over, or none): until they are, nothing is measured
        first = getattr(sim, "first_compiled", None)
        self._compiling = first if first is not None and not first.is_set() else None

    def interval_start(self, sim, phase, step):
        self.stride = 1 if phase == HELD else 256
        self.index += 1
        self.phase, self.h, self.name = phase, step, sim.phase_name
        self.t_iv, self.w_iv = sim.t, self._clock()
        # where this interval's measurement starts (moved to the end of the first compilations)
        self.t_meas, self.w_meas = self.t_iv, self.w_iv

    def _settle(self, t: float) -> None:
        """The first compilations just ended: measure this interval from here."""
        if self._compiling is not None and self._compiling.is_set():
            self._compiling = None
            self.t_meas, self.w_meas = t, self._clock()

    def _cost(self, phase: str, steps_now: int, wall_now: float) -> float | None:
        w = self.cost_wall.get(phase, 0.0) + (wall_now if phase == self.phase else 0.0)
        n = self.cost_steps.get(phase, 0) + (steps_now if phase == self.phase else 0)
        if self.prior.get(phase) is not None and (w < self.SETTLE_S or not n):
            return self.prior[phase]  # too little measured yet (or nothing: still compiling)
        return w / n if n else None

    def remaining(self, t: float) -> float | None:
        """Estimated wall seconds left, from the measured cost per step of each phase (the prior until enough
        is measured)."""
        if self.plan is None or self.index >= len(self.plan):
            return None
        done = max(0, int(round((t - self.t_iv) / self.h)))
        if self._compiling is not None:
            measured, wall = 0, 0.0
        else:
            measured = max(0, int(round((t - self.t_meas) / self.h)))
            wall = self._clock() - self.w_meas
        costs = {ph: self._cost(ph, measured, wall) for ph in (COUPLED, HELD)}
        known = [c for c in costs.values() if c is not None]
        if not known:
            return None
        left = max(0, self.plan[self.index][1] - done) * (costs[self.phase] or max(known))
        for ph, n in self.plan[self.index + 1:]:
            left += n * (costs[ph] if costs[ph] is not None else max(known))
        return left

    def step(self, sim, t):
        if self.bar is None:
            return
        if self._compiling is not None:
            self._settle(t)
        done = min(self.total, t - self.t0)
        now = self._clock()
        if now - self._shown_at >= 1.0 and not self.disable:
            left = self.remaining(t)
            self.bar.set_postfix_str(f"{self.name}, ~{_hms(left)} left" if left is not None else self.name,
                                     refresh=False)
            self._shown_at = now
        self.bar.update(done - self.shown)  # tqdm redraws at most once per mininterval
        self.shown = done

    def interval_end(self, sim, used):
        if self._compiling is not None:
            self._settle(sim.t)
        if self.plan is not None and self._compiling is None:
            role = sim.phase
            self.cost_wall[role] = self.cost_wall.get(role, 0.0) + self._clock() - self.w_meas
            self.cost_steps[role] = self.cost_steps.get(role, 0) + max(
                0, int(round((sim.t - self.t_meas) / self.h)))

    def block_signals(self, sim):
        return []

    def step_block(self, sim, ks, ts, data):
        rows = sampled_rows(ks, self.stride)
        if len(rows):
            self.step(sim, float(ts[rows[-1]]))

    def end(self, sim, error):
        if self.bar is not None:
            self.step(sim, sim.t)
            self.bar.set_postfix_str("done" if error is None else "stopped", refresh=False)
            self.bar.close()

    def checkpoint_state(self):
        return None

    def restore_checkpoint(self, state):
        pass


def _hms(seconds: float) -> str:
    s = int(round(seconds))
    return f"{s // 3600}:{s % 3600 // 60:02d}:{s % 60:02d}" if s >= 3600 else f"{s // 60}:{s % 60:02d}"


class SteadyWindows(Observer):
    """Keeps the last ``cycles`` cycles of ``signals`` in each TM interval; at the interval end, the window is
    stored in ``windows`` as a dict with ``t`` and one array per signal. ``cycle``: the cycle period [s] or a
    cycle source (master/core/cycle.py), read at the start of each TM interval. A cycle source with an angle
    counts the window in its turns (the run's RevolutionCounter): the samples since the last ``cycles`` turns
    began, plus the one at or before that time, as a window of ``cycles`` periods has; the window's dict then has
    ``revolutions``, the turns it spans (fewer than ``cycles`` where the interval was shorter); its ring, sized for
    the turns at 1 / WINDOW_MARGIN of the speed at the interval's start, grows where the speed falls further (a
    monolithic run of a falling speed)."""

    def __init__(self, signals: Sequence[str], cycle: Cycle | float, cycles: float = 5.0,
                 sample_step: float | None = None):
        self.signals = list(signals)
        self.cycle = as_cycle(cycle)
        self.cycles = cycles
        #: the window of the present TM interval [s]
        self.window = cycles * self.cycle.constant if self.cycle.constant is not None else None
        self.sample_step = sample_step
        self.windows: list[dict] = []

    def interval_start(self, sim, phase, step):
        self.active = phase == COUPLED
        counter = getattr(sim, "revolutions", None)
        # counted in the turns of the run's angle when this window's cycle has that angle
        self._turns = counter if counter is not None and self.cycle.angle == counter.ref else None
        if self.active:
            self.window = self.cycles * self.cycle.period(sim.system)
        self.stride = 1 if self.sample_step is None else max(1, int(round(self.sample_step / step)))
        self._h = step
        n = int(math.ceil((self.window or 0.0) / (self.stride * step))) + 1
        if self._turns is not None and self.active:
            self._turns.need(self.cycles)
            n = int(math.ceil(WINDOW_MARGIN * self.window / (self.stride * step))) + 1
            if sim.interval_steps is not None:
                n = min(n, sim.interval_steps // self.stride + 1)
        self._n = n
        self._t = np.full(n, np.nan)
        self._data = {r: np.zeros((n, len(sim.value(r)))) for r in self.signals}
        comps = sim.system.components
        # (component, port, buffer) resolved once: this runs at every step of a thermo-mechanical interval
        self._taps = [(comps[r.partition(".")[0]], r.partition(".")[2], self._data[r]) for r in self.signals]
        self._pos = 0
        self._count = 0
        # a step number at or below this cannot be among the interval's last n samples (sampled steps are
        # multiples of the stride): step_block leaves those ring slots for the later rows that overwrite them
        steps = sim.interval_steps
        self._old = None if steps is None else steps - (n + 1) * self.stride
        if self._turns is not None:   # the ring may grow (_room): every row is kept
            self._old = None

    def _room(self, t: float, more: int = 0) -> None:
        """Counted in turns: a ring that would drop samples the window still needs (the speed fell below
        1 / WINDOW_MARGIN of its value at the interval's start) grows, oldest samples first."""
        need = int(math.ceil((t - self._turns.began(self.cycles, t)) / (self.stride * self._h) - 1e-9)) + 2 + more
        if need <= self._n:
            return
        n, count = self._n, self._count
        a = (self._pos - count) % n
        size = max(need, 2 * n)

        def grown(x):
            y = np.zeros((size,) + x.shape[1:]) if x.ndim > 1 else np.full(size, np.nan)
            y[:count] = x[a:a + count] if a + count <= n else np.concatenate((x[a:], x[:a + count - n]))
            return y

        self._t = grown(self._t)
        self._data = {r: grown(b) for r, b in self._data.items()}
        self._taps = [(c, port, self._data[r]) for (c, port, _), r in zip(self._taps, self.signals)]
        self._n, self._pos = size, count % size

    def step(self, sim, t):
        if not self.active:
            return
        if self._turns is not None and self._count == self._n and self._pos % 64 == 0:
            self._room(t, 64)
        i = self._pos
        self._t[i] = t
        for comp, port, buf in self._taps:
            buf[i] = comp.y[port]
        self._pos = (i + 1) % self._n
        self._count = min(self._count + 1, self._n)

    def block_signals(self, sim):
        return list(self.signals)

    def step_block(self, sim, ks, ts, data):
        if not self.active:
            return
        rows = sampled_rows(ks, self.stride)
        nr = len(rows)
        if not nr:
            return
        if self._turns is not None:   # the run's RevolutionCounter has this block already (the first observer)
            self._room(float(np.asarray(ts)[rows[-1]]))
        n = self._n
        m = min(nr, n)  # the ring keeps the last n samples: rows[nr - m:], the first of them at ring slot pos
        pos = (self._pos + (nr - m)) % n
        j0 = nr - m
        if self._old is not None:  # and of those, the rows after step _old (ks increase: a tail of them)
            j0 = max(j0, int(np.searchsorted(np.asarray(ks)[rows], self._old, side="right")))
        count = nr - j0
        if count:
            # rows j0.. go to the ring slots from p0 on (wrapping once at most), as slices: the sampled rows are
            # every stride-th row of the block, copied by slices rather than index arrays (the same values; the
            # index arrays cost ~1 ms a block of 2 048 rows, the most of a staggered run's short intervals)
            p0 = (pos + j0 - (nr - m)) % n
            a, b = int(rows[j0]), int(rows[-1])
            src = slice(a, b + 1, self.stride) if b - a == (count - 1) * self.stride else rows[j0:]
            first = min(count, n - p0)
            parts = [(slice(p0, p0 + first), slice(0, first))]
            if count > first:
                parts.append((slice(0, count - first), slice(first, count)))
            block = np.asarray(ts)[src]
            for dst, part in parts:
                self._t[dst] = block[part]
            for r in self.signals:
                block, ring = data[r][src], self._data[r]
                for dst, part in parts:
                    ring[dst] = block[part]
        self._pos = (pos + m) % n
        self._count = min(self._count + nr, n)

    def interval_end(self, sim, used):
        if not getattr(self, "active", False) or self._count == 0:
            return
        n, count = self._n, self._count
        a = (self._pos - count) % n  # the oldest sample's slot; the ring holds count samples from there on

        def ordered(x):  # oldest first (slices, not an index array)
            return x[a:a + count].copy() if a + count <= n else np.concatenate((x[a:], x[:a + count - n]))

        win = {"t": ordered(self._t), "t_start": used.t_start, "t_end": used.t_end}
        for r in self.signals:
            win[r] = ordered(self._data[r])
        if self._turns is not None:
            # the samples since the last turns began, and the one at or before that time
            t = win["t"]
            began = self._turns.began(self.cycles, float(t[-1]))
            k = min(int(math.ceil((t[-1] - began) / (self.stride * self._h) - 1e-9)) + 1, len(t))
            for key in ["t", *self.signals]:
                win[key] = win[key][len(t) - k:]
            win["revolutions"] = self._turns.revolutions(float(win["t"][0]), float(win["t"][-1]))
        self.windows.append(win)
