"""A recorded time series read back from its HDF5 file, one dataset at a time, when first used.

A run that writes ``timeseries.h5`` does not also keep the series in memory (a monolithic 2-minute run records
1.2 million rows, ~0.5 GB): :class:`rotorcosim.Result` and the figures read the datasets they use from the file.
"""
from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path

import numpy as np

from rotorcosim.components.bounded_read import MAX_DATASET_BYTES, check_size


class SeriesFile(Mapping):
    """``time``, ``phase`` and one (n, size) array per recorded port, as :meth:`Recorder.data` gives them, read
    from the HDF5 file ``path`` on first access and kept afterwards."""

    def __init__(self, path: str | Path):
        self.path = Path(path)
        self._cache: dict[str, np.ndarray] = {}
        self._names: list[str] | None = None

    def _open(self):
        import h5py

        try:
            return h5py.File(self.path, "r")
        except OSError as exc:
            raise OSError(f"the time series {self.path} cannot be read ({exc}): was it moved or deleted?") from None

    def _keys(self) -> list[str]:
        if self._names is None:
            with self._open() as f:
                self._names = list(f)
        return self._names

    def __getitem__(self, key: str) -> np.ndarray:
        if key not in self._cache:
            if key not in self._keys():
                raise KeyError(key)
            with self._open() as f:
                ds = f[key]
                check_size(ds.size * ds.dtype.itemsize, f"the time series {self.path}: dataset {key!r}",
                           "time series dataset", MAX_DATASET_BYTES)
                self._cache[key] = ds[()]
        return self._cache[key]

    def __iter__(self):
        return iter(self._keys())

    def events(self) -> list[dict]:
        """The run's located events (the file's ``events`` attribute, master/core/events.py), [] without any."""
        import json

        with self._open() as f:
            text = f.attrs.get("events")
        return json.loads(text) if text else []

    def __len__(self) -> int:
        return len(self._keys())


def events_of(data) -> list[dict]:
    """The located events of a run's recorded ``data`` (a :class:`SeriesFile`; in memory: none): what a
    time-history figure marks."""
    return data.events() if isinstance(data, SeriesFile) else []
