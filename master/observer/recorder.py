"""The recorder: decimated time series streamed to disk while the run goes, flushed in chunks, so a crash loses
nothing already flushed; readable without this project. The file's format is a back-end's (``.h5``:
:mod:`.recorder_hdf5`, ``.csv``: :mod:`.recorder_csv`); the rows are kept in memory as well on request."""
from __future__ import annotations

import errno
import math
import os
from pathlib import Path
from typing import Sequence

import numpy as np

from rotorcosim.components.contract import HELD
from rotorcosim.master.core.phases import Phases
from rotorcosim.master.observer import recorder_csv, recorder_hdf5
from rotorcosim.master.observer.observer import Observer, sampled_rows

#: free space a recorder keeps on its disk, so that a file refused a write can still be closed whole
DISK_RESERVE_BYTES = 4 * 1024 ** 2


def _size(n: float) -> str:
    """A size on disk as it reads best: 3 significant digits of GiB, or of MiB below one."""
    return f"{n / 2 ** 30:.3g} GiB" if n >= 2 ** 30 else f"{n / 2 ** 20:.3g} MiB"


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
        if self.path is not None and getattr(self, "_resume", None) is not None:
            self._open()  # a resumed run: the file holds the rows up to the checkpoint, its first sample too
            return
        if self.path is not None:
            self._check_room(sim, schedule)
            self._open()
        self._sample(sim, sim.t)

    def _check_room(self, sim, schedule) -> None:
        """Refuse a run whose time series cannot fit on its disk before it starts (it filled the disk hours in
        and failed there: tens of GB for an hour of a fast-sampled system): the rows its timeline records, at 8
        bytes a value (the HDF5 file's size; a CSV file's is larger), against the free space. The automatic
        schedule's intervals are not known before the run."""
        intervals = getattr(schedule, "intervals", None)
        if not intervals:
            return
        rows = 1.0
        for iv in intervals:
            every = iv.step if sim.phases.role(iv.phase) == HELD else max(iv.step, self.record_step)
            rows += iv.duration / every
        width = 2 + sum(self.sizes.values())
        need = rows * width * 8
        try:
            st = os.statvfs(self.path.parent)
        except (OSError, AttributeError):
            return
        free = st.f_bavail * st.f_frsize
        if need > free:
            raise ValueError(f"the time series would take about {_size(need)} ({rows:,.0f} rows of {width} values), "
                             f"more than the {_size(free)} free on the disk holding {self.path.parent}: record fewer "
                             "signals (--record), a longer [outputs] record_step or a shorter --duration")

    def _open(self):
        self.path.parent.mkdir(parents=True, exist_ok=True)
        tmp = self.path.with_name(self.path.name + ".part")
        self._tmp = tmp
        resume = getattr(self, "_resume", None)
        if resume is not None:
            self._reopen(resume)
            return
        if self.path.suffix.lower() in (".h5", ".hdf5"):
            self._file = recorder_hdf5.create(tmp, self.signals, self.variables, self.record_step, self.chunk,
                                              self._phases)
            self._datasets = None
            self._kind = "hdf5"
        elif self.path.suffix.lower() == ".csv":
            self._file, self._csv = recorder_csv.create(tmp, self.signals, self.variables)
            self._kind = "csv"
        else:
            raise ValueError(f"recorder: unknown format of {self.path} (use .h5 or .csv)")

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
            if self._datasets is None:  # opened once per file, not at every flush
                self._datasets = recorder_hdf5.datasets(f, ("time", "phase", *self.signals))
            ds = self._datasets
            recorder_hdf5.append(ds["time"], r, t)
            recorder_hdf5.append(ds["phase"], r, ph)
            for ref in self.signals:
                recorder_hdf5.append(ds[ref], r, block[ref])
            f.flush()
        elif self._kind == "csv":
            recorder_csv.write_rows(self._csv, t, ph, block, self.signals)
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
                recorder_hdf5.complete(self._file, extra, error)
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
            f = recorder_hdf5.reopen(self._tmp, self.path, ["time", "phase"] + self.signals, n)
            self._file, self._kind, self._datasets = f, "hdf5", None
        else:
            self._file, self._csv = recorder_csv.reopen(self._tmp, int(state["bytes"]))
            self._kind = "csv"
        self.rows = n
        self._resume = None
