"""Writing result files whole or not at all (a crash never leaves a half-written summary)."""
from __future__ import annotations

import json
import math
import os
from pathlib import Path
from typing import Any

import numpy as np

#: resolution of the PNG figures a run writes [dots per inch] (``rotorcosim run --dpi``): print quality for a
#: report at the figures' 10-16 inch width
FIGURE_DPI = 150
#: the range ``--dpi`` accepts: below, text is unreadable; above, a figure is tens of megabytes
DPI_RANGE = (50, 1200)


def check_dpi(dpi) -> int:
    """``dpi`` as an int if it is a resolution a figure can be written at (:data:`DPI_RANGE`), else a ValueError
    naming it. None gives :data:`FIGURE_DPI`.

    >>> check_dpi(None), check_dpi(300)
    (150, 300)
    """
    if dpi is None:
        return FIGURE_DPI
    lo, hi = DPI_RANGE
    if isinstance(dpi, bool) or not isinstance(dpi, (int, float, np.integer, np.floating)) or not lo <= dpi <= hi:
        raise ValueError(f"--dpi must be a number of dots per inch from {lo} to {hi}, got {dpi!r}")
    return int(round(dpi))


def plain_json(obj: Any) -> Any:
    """``obj`` in what JSON holds: numpy values as Python numbers and lists, NaN/inf as None, paths as text."""
    if isinstance(obj, dict):
        return {str(k): plain_json(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [plain_json(v) for v in obj]
    if isinstance(obj, np.ndarray):
        return plain_json(obj.tolist())
    if isinstance(obj, (np.floating, float)):
        x = float(obj)
        return x if math.isfinite(x) else None
    if isinstance(obj, (np.integer,)):
        return int(obj)
    if isinstance(obj, Path):
        return str(obj)
    return obj


def write_json(path: str | os.PathLike, data: Any) -> Path:
    """JSON with NaN/inf written as null; written to a temporary file first, then renamed."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(path.name + ".part")
    tmp.write_text(json.dumps(plain_json(data), indent=2) + "\n")
    os.replace(tmp, path)
    return path
