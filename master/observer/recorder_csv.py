"""The recorder's CSV back-end: one column per vector element, ``component.port[label] (unit)``, after ``time (s)``
and ``phase``."""
from __future__ import annotations

import csv
from pathlib import Path
from typing import Sequence

import numpy as np


def column_names(signals: Sequence[str], variables: dict) -> list[str]:
    """Flat column names with units, one per vector element: ``osc.x[0] (m)``, ``node.T (K)``."""
    out = []
    for ref in signals:
        v = variables[ref]
        for lb in v.column_labels():
            out.append(f"{ref}[{lb}] ({v.unit})" if lb else f"{ref} ({v.unit})")
    return out


def cell_text(x) -> str:
    """One value as written: a float with 10 significant digits, a Boolean as 1 / 0, anything else as text."""
    if isinstance(x, (float, np.floating)):
        return f"{x:.10g}"
    if isinstance(x, (bool, np.bool_)):
        return "1" if x else "0"
    return str(x)


def create(tmp: Path, signals: Sequence[str], variables: dict):
    """A new file at ``tmp`` with its header row: (the open file, its csv writer)."""
    f = open(tmp, "w", newline="")
    writer = csv.writer(f)
    writer.writerow(["time (s)", "phase"] + column_names(signals, variables))
    return f, writer


def write_rows(writer, t: np.ndarray, phase: np.ndarray, block: dict, signals: Sequence[str]) -> None:
    """Rows of times ``t``, phase codes ``phase`` and ``block[ref]`` (one row per time) of each signal."""
    for i, (tt, p) in enumerate(zip(t, phase)):
        row = [f"{tt:.10g}", str(p)]
        for ref in signals:
            row += [cell_text(x) for x in block[ref][i]]
        writer.writerow(row)


def reopen(tmp: Path, nbytes: int):
    """The file ``tmp`` of an interrupted run cut back to its checkpoint's ``nbytes``: (the open file, its writer)."""
    f = open(tmp, "r+", newline="")
    f.truncate(nbytes)
    f.seek(nbytes)
    return f, csv.writer(f)
