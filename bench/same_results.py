"""Are two run folders' results bit-identical? ``python bench/same_results.py DIR_A DIR_B``

Compares ``summary.json`` (every value except the ones that measure the machine: wall and CPU times, the load,
dates, the engine's compile notes; a path that differs only in the checkout it ran from) and every dataset and attribute of ``timeseries.h5``, exactly. Prints each
difference and exits 1 if there is one, 0 if the results are the same. Used to check that a change meant to
leave results alone did (e.g. ``rotorcosim run --out A`` on two versions of the code).
"""
from __future__ import annotations

import json
import re
import sys
from pathlib import Path

import h5py
import numpy as np

#: summary keys that measure the run, not its results
MACHINE_KEYS = {"wall_time_s", "cpu_time_s", "load_average", "started", "finished", "engine_note", "timing",
                "wall_time_by_phase_s", "peak_memory_MB", "estimate", "files", "output_folder", "step_cost_us", "source"}


#: a path into one of the project's top folders, from wherever the checkout is
_CHECKOUT_PATH = re.compile(r"/\S*?/(components|scenarios|cases|interop|fmus|master)/")


def _same_file_elsewhere(a, b) -> bool:
    """Two strings that differ only in the folder the code ran from (two checkouts' copies of one file, as
    provenance names them): ``/x/main/scenarios/f.toml`` and ``/y/ref/scenarios/f.toml``, also inside a longer
    text ("computed from /x/main/components/...")."""
    if not (isinstance(a, str) and isinstance(b, str)):
        return False
    return _CHECKOUT_PATH.sub(r"<checkout>/\1/", a) == _CHECKOUT_PATH.sub(r"<checkout>/\1/", b)


def _short(v, n: int = 160) -> str:
    """repr of ``v``, cut to ``n`` characters (a list of hundreds of records stays one readable line)."""
    r = repr(v)
    return r if len(r) <= n else r[:n] + f"... ({len(r)} characters)"


def _walk(a, b, where: str, out: list[str]) -> None:
    if isinstance(a, dict) and isinstance(b, dict):
        for k in sorted(set(a) | set(b)):
            if k in MACHINE_KEYS:
                continue
            if k not in a or k not in b:
                out.append(f"{where}/{k}: only in {'B' if k not in a else 'A'}")
            else:
                _walk(a[k], b[k], f"{where}/{k}", out)
    elif isinstance(a, list) and isinstance(b, list) and len(a) == len(b):
        for i, (x, y) in enumerate(zip(a, b)):
            _walk(x, y, f"{where}[{i}]", out)
    elif a != b and not (isinstance(a, float) and isinstance(b, float) and np.isnan(a) and np.isnan(b)) \
            and not _same_file_elsewhere(a, b):
        out.append(f"{where}: {_short(a)} != {_short(b)}")


def differences(dir_a: Path, dir_b: Path) -> list[str]:
    out: list[str] = []
    sa = json.loads((dir_a / "summary.json").read_text())
    sb = json.loads((dir_b / "summary.json").read_text())
    _walk(sa, sb, "summary.json", out)
    with h5py.File(dir_a / "timeseries.h5", "r") as fa, h5py.File(dir_b / "timeseries.h5", "r") as fb:
        names = sorted(set(fa) | set(fb))
        for n in names:
            if n not in fa or n not in fb:
                out.append(f"timeseries.h5/{n}: only in {'B' if n not in fa else 'A'}")
                continue
            x, y = fa[n][()], fb[n][()]
            if x.shape != y.shape or x.dtype != y.dtype:
                out.append(f"timeseries.h5/{n}: shape/dtype {x.shape} {x.dtype} != {y.shape} {y.dtype}")
            elif not np.array_equal(x, y, equal_nan=x.dtype.kind == "f"):
                bad = np.flatnonzero(~((x == y) | (np.isnan(x) & np.isnan(y)) if x.dtype.kind == "f" else x == y))
                out.append(f"timeseries.h5/{n}: {bad.size} values differ, the first at flat index {bad[0]}")
            for k in sorted(set(fa[n].attrs) | set(fb[n].attrs)):
                va, vb = fa[n].attrs.get(k), fb[n].attrs.get(k)
                if not np.array_equal(np.asarray(va), np.asarray(vb)):
                    out.append(f"timeseries.h5/{n}@{k}: {va!r} != {vb!r}")
    return out


def main(argv: list[str]) -> int:
    if len(argv) != 2:
        print(__doc__.splitlines()[0], file=sys.stderr)
        return 2
    for d in argv:
        missing = [f for f in ("summary.json", "timeseries.h5") if not (Path(d) / f).is_file()]
        if missing:
            print(f"same_results: {d} is not a run folder (no {' or '.join(missing)})", file=sys.stderr)
            return 2
    diffs = differences(Path(argv[0]), Path(argv[1]))
    for d in diffs:
        print(d)
    print("bit-identical" if not diffs else f"{len(diffs)} difference(s)")
    return 1 if diffs else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
