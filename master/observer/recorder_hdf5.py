"""The recorder's HDF5 back-end (h5py): the file's layout (root attributes, one resizable dataset per signal plus
``time`` and ``phase``), its creation from a per-process template, the rows appended at each flush, and an
interrupted run's file cut back to its checkpoint."""
from __future__ import annotations

import os
from pathlib import Path
from typing import Sequence

import numpy as np

#: empty HDF5 files of this process's recordings by layout (:func:`create`): bytes, the last few layouts
TEMPLATES: dict[tuple, bytes] = {}
#: layouts :data:`TEMPLATES` keeps (the oldest goes first)
TEMPLATES_KEPT = 8
#: HDF5's file lock on the run's own ``.part`` file, which no other process opens while it is written: off. A child
#: process started meanwhile by another thread (the figure workers) holds a copy of the descriptor of the file
#: being created until its exec closes it, and with it that descriptor's lock, so the reopening for appending
#: was refused now and then ("unable to lock file, errno = 11")
LOCKING = False


def dtype_of(kind: str, fmi_type: str):
    """The dataset type of a signal: floats as f8, integers as i8 (UInt64 as u8), Booleans as bool, strings as
    UTF-8 strings; so an integer beyond 2^53 is kept exactly."""
    if kind == "Real":
        return "f8"
    if kind == "Integer":
        return "u8" if fmi_type == "UInt64" else "i8"
    if kind == "Boolean":
        return "?"
    import h5py

    return h5py.string_dtype("utf-8")


def write_layout(f, signals: Sequence[str], variables: dict, record_step: float, chunk: int, phases) -> None:
    """The attributes and empty datasets of a new HDF5 file ``f``: ``variables`` maps each signal to its variable
    (size, unit, description, column labels), ``phases`` is the run's :class:`~rotorcosim.master.core.phases.Phases`."""
    f.attrs["description"] = f"rotorcosim time series: SI units; phase {phases.description(tags=False)}"
    f.attrs["sampling_interval_s"] = record_step
    f.attrs["sampling"] = (f"every {record_step:g} s in thermo-mechanical intervals, every thermal step in "
                           f"thermal-only intervals (the time dataset has each sample's time)")
    f.create_dataset("time", shape=(0,), maxshape=(None,), dtype="f8", chunks=(chunk,))
    f["time"].attrs["unit"] = "s"
    f["time"].attrs["description"] = "simulated time of each sample"
    f.create_dataset("phase", shape=(0,), maxshape=(None,), dtype="i1", chunks=(chunk,))
    f["phase"].attrs["description"] = phases.description()
    for ref in signals:
        v = variables[ref]
        ds = f.create_dataset(ref, shape=(0, v.size), maxshape=(None, v.size), dtype=dtype_of(v.type, v.fmi_type),
                              chunks=(chunk, v.size))
        ds.attrs["unit"] = v.unit
        ds.attrs["description"] = v.description
        ds.attrs["columns"] = [lb or v.name for lb in v.column_labels()]
        ds.attrs["sampling_interval_s"] = record_step


def create(tmp: Path, signals: Sequence[str], variables: dict, record_step: float, chunk: int, phases):
    """A new file at ``tmp`` with :func:`write_layout`'s layout, open for appending (an ``h5py.File``)."""
    import h5py

    # the empty file (attributes and datasets, no rows) is made once per process and layout and copied:
    # its ~110 attributes and ~30 datasets cost ~16 ms per run through h5py, the copy and open ~5 ms
    key = (record_step, chunk, phases, tuple(
        (ref, variables[ref].size, variables[ref].type, variables[ref].fmi_type, variables[ref].unit,
         variables[ref].description, tuple(variables[ref].column_labels())) for ref in signals))
    blob = TEMPLATES.get(key)
    if blob is None:
        with h5py.File(tmp, "w", locking=LOCKING) as f:
            write_layout(f, signals, variables, record_step, chunk, phases)
        blob = tmp.read_bytes()
        if len(TEMPLATES) >= TEMPLATES_KEPT:
            TEMPLATES.pop(next(iter(TEMPLATES)))
        TEMPLATES[key] = blob
    else:
        tmp.write_bytes(blob)
    # no chunk cache: the recorder writes each chunk once, whole, and never reads it back; h5py's default
    # (1 MiB a dataset) held the last chunks written of every dataset, ~10 MB more per simulated second
    # of a monolithic run up to ~1 MiB x its ~30 datasets (measured: a 2 s run peaked 20 MB above a
    # 0.2 s one)
    return h5py.File(tmp, "r+", rdcc_nbytes=0, locking=LOCKING)


def datasets(f, names: Sequence[str]) -> dict:
    """The datasets ``names`` of the open file ``f``, by name."""
    import h5py

    # by h5py's low-level open: the same datasets as f[name] (which also resolves links and object types), ~0.03
    # against ~0.1 ms each, ~2 ms of every run's first flush
    return {name: h5py.Dataset(h5py.h5d.open(f.id, name.encode())) for name in names}


def append(ds, r: int, data: np.ndarray) -> None:
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


def complete(f, attributes: dict, error: BaseException | None) -> None:
    """The root attributes of a finished file: ``attributes`` (what made the run), ``complete`` and, for a run
    that failed, its ``error``."""
    for key, value in attributes.items():
        f.attrs[key] = value
    f.attrs["complete"] = error is None
    if error is not None:
        f.attrs["error"] = f"{type(error).__name__}: {error}"


def reopen(tmp: Path, path: Path, names: Sequence[str], rows: int):
    """The file ``tmp`` of an interrupted run, its datasets ``names`` cut back to ``rows`` rows and its
    ``complete`` / ``error`` attributes removed, open for appending. A file that cannot be continued goes back
    to ``path`` (the folder stays as the interrupted run left it) and raises ValueError."""
    import h5py

    try:
        f = h5py.File(tmp, "r+", locking=LOCKING)
    except OSError as exc:
        os.replace(tmp, path)
        raise ValueError(f"recorder: {path} cannot be reopened ({exc}): resume impossible") from None
    for name in names:
        ds = f.get(name)
        if ds is None or not hasattr(ds, "resize") or ds.shape[0] < rows:
            f.close()
            os.replace(tmp, path)
            what = f"has no dataset {name!r}" if ds is None or not hasattr(ds, "resize") else \
                "has fewer rows than its checkpoint"
            raise ValueError(f"recorder: {path} {what}: resume impossible")
        ds.resize((rows,) + ds.shape[1:])
    for key in ("complete", "error"):
        if key in f.attrs:
            del f.attrs[key]
    return f
