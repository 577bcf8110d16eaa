"""Where a study keeps every finished run: an append-only CSV table in its output folder, read back on resume.

A row is written (and flushed) the moment its run finishes, so an interrupted study loses nothing it computed;
run again with the same SPEC and ``--out``, it reads the table and runs only what is missing. Numbers are written
with Python's ``repr`` (the shortest text that reads back to the same float), so a resumed study takes exactly the
same values as the interrupted one.

The folder's JSON file (``calibration.json``, ``uq.json``) carries the SPEC's fingerprint from the start
(``status`` "running"): a folder of another SPEC is refused rather than mixed.

>>> import tempfile, pathlib
>>> p = pathlib.Path(tempfile.mkdtemp()) / "t.csv"
>>> s = RowStore(p, ["case", "x", "y"]); s.append({"case": "a", "x": 0.1, "y": None})
>>> RowStore(p, ["case", "x", "y"]).read()
[{'case': 'a', 'x': 0.1, 'y': None}]
"""
from __future__ import annotations

import csv
import json
import math
import os
from pathlib import Path
from typing import Any, Sequence

from rotorcosim.master.run.outputs import write_json
from rotorcosim.components.bounded_read import MAX_TABLE_BYTES, read_json, read_text


class StoreError(ValueError):
    """An output folder or table that is not this study's: one line naming it."""


def _text(v: Any) -> str:
    if v is None:
        return ""
    if isinstance(v, float):
        return repr(v) if math.isfinite(v) else ""
    return str(v)


def _value(text: str) -> Any:
    if text == "":
        return None
    try:
        return float(text)
    except ValueError:
        return text


class RowStore:
    """The CSV table ``path`` with ``columns``; :meth:`append` adds a row at once, :meth:`read` the rows so far
    (numbers as floats, empty cells as None)."""

    def __init__(self, path: str | Path, columns: Sequence[str]):
        self.path = Path(path)
        self.columns = list(columns)

    def read(self) -> list[dict]:
        """The stored rows (none when the file does not exist); a file with other columns is an error."""
        if not self.path.exists():
            return []
        rows = list(csv.reader(read_text(self.path, "study table", MAX_TABLE_BYTES).splitlines()))
        if not rows:
            return []
        if rows[0] != self.columns:
            raise StoreError(f"{self.path}: its columns ({', '.join(rows[0][:6])}...) are not this study's "
                             f"({', '.join(self.columns[:6])}...): use another --out")
        # a row cut short by an interrupt while it was written is dropped (its run is done again)
        return [{c: _value(x) for c, x in zip(self.columns, r)} for r in rows[1:] if len(r) == len(self.columns)]

    def append(self, row: dict) -> None:
        """Write one row (its missing columns empty) and flush it to disk."""
        new = not self.path.exists() or self.path.stat().st_size == 0
        with open(self.path, "a", newline="") as fh:
            w = csv.writer(fh)
            if new:
                w.writerow(self.columns)
            w.writerow([_text(row.get(c)) for c in self.columns])
            fh.flush()
            os.fsync(fh.fileno())

    def rewrite(self, rows: list[dict]) -> None:
        """Replace the table by ``rows`` (whole: through a ``.part`` file), e.g. sorted at the end."""
        tmp = self.path.with_name(self.path.name + ".part")
        with open(tmp, "w", newline="") as fh:
            w = csv.writer(fh)
            w.writerow(self.columns)
            for row in rows:
                w.writerow([_text(row.get(c)) for c in self.columns])
        os.replace(tmp, self.path)


def open_folder(out: str | Path, report: str, table: str, fingerprint: str, head: dict,
                definition: dict | None = None, resume: bool = False) -> bool:
    """Make ``out`` ready for a study whose JSON report is ``report`` and table ``table``: a new or empty folder
    starts afresh, a folder holding the same SPEC's report resumes (returns True); anything else is refused, a
    study of another SPEC naming the keys of ``definition`` (what the SPEC says) that differ. ``resume``: the
    folder must hold this SPEC's study. Writes the report with ``status`` "running", the ``fingerprint``,
    ``definition`` and ``head``."""
    out = Path(out)
    if out.exists() and not out.is_dir():
        raise StoreError(f"--out {out} is a file, not a folder")
    resumed = False
    if out.is_dir() and any(out.iterdir()):
        f = out / report
        try:
            old = read_json(f, report)
        except (OSError, ValueError):
            names = ", ".join(sorted(p.name for p in out.iterdir())[:4])
            raise StoreError(f"--out {out} is not empty and holds no {report} of a study ({names}): use an empty "
                             f"or new folder") from None
        if not isinstance(old, dict) or old.get("fingerprint") != fingerprint:
            raise StoreError(f"--out {out} holds a study of another SPEC ({_differences(old, definition)}): use "
                             "another folder, or the SPEC that made it")
        resumed = (out / table).exists()
    elif resume:
        raise StoreError(f"--resume: --out {out} holds no study to resume (run without --resume to start one)")
    out.mkdir(parents=True, exist_ok=True)
    write_json(out / report, {**head, "status": "running", "fingerprint": fingerprint,
                              **({"definition": definition} if definition is not None else {})})
    return resumed


def _differences(old, definition: dict | None) -> str:
    """Which keys of a SPEC's definition differ from the one a folder's report holds, in words."""
    was = old.get("definition") if isinstance(old, dict) else None
    if not isinstance(was, dict) or definition is None:
        return "its report predates the record of what its SPEC said"
    new = json.loads(json.dumps(definition, default=str))
    keys = [k for k in sorted(set(was) | set(new)) if was.get(k) != new.get(k)]
    if not keys:
        return "its report has another fingerprint"
    shown = []
    for k in keys[:4]:
        a, b = was.get(k), new.get(k)
        short = isinstance(a, (int, float, str, type(None))) and isinstance(b, (int, float, str, type(None)))
        shown.append(f"{k} {a!r} there, {b!r} here" if short else k)
    return "differs in " + "; ".join(shown) + (f" and {len(keys) - 4} more" if len(keys) > 4 else "")
