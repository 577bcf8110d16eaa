"""Our blade-loss results against the paper's Table 5, cell by cell: the score, a CSV and a figure.

The compared cells are the paper's 11 results x 2 bearings x 7 unbalance levels, less the printed zeros that are
rounding (the #5 transmissibility and film power at 712 N): 152 cells. The rub power's zeros are real (no rub
below 5700 N at #0, never at #5) and are compared: such a cell matches when ours is below ``RUB_ZERO_W`` (a rub
contact dissipates kilowatts; below 1 W there is no contact), and then counts as within +-30 % and within x2.

A cell is within +-30 % when 0.7 <= ours / paper <= 1.3 and within x2 when 0.5 <= ours / paper <= 2.
"""
from __future__ import annotations

import csv
import math
import os
from pathlib import Path

from rotorcosim.cases.blade_loss.table5 import paper_table5, write_table5
from rotorcosim.cases.blade_loss.results import BEARINGS, RESULT_KEYS
from rotorcosim.components.bounded_read import read_text

COLUMNS = ("result", "bearing", "unbalance_N", "paper", "ours", "ratio")
RUB_ZERO_W = 1.0
BAND = 0.30


def _ours(by_level: dict, level: float, key: str, k: int):
    """Our value, None when missing or when the case stopped with an error (its values are not the 2-minute
    results the paper tabulates)."""
    case = by_level.get(level, {})
    if case.get("error"):
        return None
    v = case.get("bearings", {}).get(str(k), {}).get(key)
    return None if v is None else float(v)


def compare(by_level: dict) -> list[dict]:
    """The compared cells for the levels of ``by_level`` (unbalance N -> summary) that the paper has: one row
    per cell with the columns of :data:`COLUMNS` (ratio None where the paper's value is a compared zero or ours
    is missing) and the flags ``within_30``, ``within_x2``."""
    paper = paper_table5()
    rows = []
    for key in RESULT_KEYS:
        for k in BEARINGS:
            for level, ref in paper[(key, k)].items():
                if level not in by_level:
                    continue
                if ref == 0.0 and key != "rub_power_W":
                    continue                     # a printed zero that is rounding: not compared
                ours = _ours(by_level, level, key, k)
                if ours is None or not math.isfinite(ours):
                    ratio, in30, inx2 = None, False, False
                elif ref == 0.0:
                    ratio = None
                    in30 = inx2 = abs(ours) < RUB_ZERO_W
                else:
                    ratio = ours / ref
                    in30 = 1.0 - BAND <= ratio <= 1.0 + BAND
                    inx2 = 0.5 <= ratio <= 2.0
                rows.append({"result": key, "bearing": k, "unbalance_N": level, "paper": ref, "ours": ours,
                             "ratio": ratio, "within_30": in30, "within_x2": inx2})
    return rows


def score(rows: list[dict]) -> dict:
    """Cells compared, within +-30 % and within x2 (counts and fractions), and the cells outside x2."""
    n = len(rows)
    n30 = sum(r["within_30"] for r in rows)
    nx2 = sum(r["within_x2"] for r in rows)
    return {"cells": n, "within_30pct": n30, "within_x2": nx2,
            "fraction_within_30pct": n30 / n if n else float("nan"),
            "fraction_within_x2": nx2 / n if n else float("nan"),
            "outside_x2": [f"{r['result']} #{r['bearing']} {r['unbalance_N']:g} N" for r in rows if not r["within_x2"]]}


def _fmt(x) -> str:
    return "" if x is None else f"{x:.6g}"


def write_csv(path: Path, rows: list[dict]) -> None:
    """Write the comparison ``rows`` (:func:`rows`) to the CSV file ``path`` (whole: through a ``.part`` file):
    result, bearing, unbalance [N], the paper's value, ours and their ratio."""
    path = Path(path)
    tmp = path.with_name(path.name + ".part")
    with open(tmp, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(COLUMNS)
        for r in rows:
            w.writerow([r["result"], r["bearing"], f"{r['unbalance_N']:g}", _fmt(r["paper"]), _fmt(r["ours"]),
                        _fmt(r["ratio"])])
    os.replace(tmp, path)


def figure(path: Path, rows: list[dict], sc: dict | None = None) -> None:
    """One panel per result: ours (markers) against the paper (line) for bearings #0 and #5 over the unbalance
    levels, the paper's +-30 % band shaded, logarithmic axes where the values span more than a decade."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    path = Path(path)
    keys = [k for k in RESULT_KEYS if any(r["result"] == k for r in rows)]
    ncol = 4
    nrow = math.ceil(len(keys) / ncol)
    fig, axes = plt.subplots(nrow, ncol, figsize=(4.2 * ncol, 3.3 * nrow), squeeze=False)
    colours = {0: "tab:blue", 5: "tab:orange"}
    for ax, key in zip(axes.flat, keys):
        vals = []
        for k in BEARINGS:
            sel = sorted((r for r in rows if r["result"] == key and r["bearing"] == k), key=lambda r: r["unbalance_N"])
            if not sel:
                continue
            x = [r["unbalance_N"] for r in sel]
            p = [r["paper"] for r in sel]
            o = [r["ours"] if r["ours"] is not None else math.nan for r in sel]
            ax.plot(x, p, "-", color=colours[k], lw=1.2, label=f"paper #{k}")
            ax.fill_between(x, [v * (1 - BAND) for v in p], [v * (1 + BAND) for v in p], color=colours[k],
                            alpha=0.15, lw=0)
            ax.plot(x, o, "o", color=colours[k], ms=4, mfc="none", label=f"ours #{k}")
            vals += [v for v in p + o if v is not None and math.isfinite(v) and v > 0]
        ax.set_xscale("log")
        if vals and max(vals) / min(vals) > 10.0:
            ax.set_yscale("log")
        ax.set_title(key, fontsize=9)
        ax.set_xlabel("blade-loss force [N]", fontsize=8)
        ax.tick_params(labelsize=7)
    for ax in list(axes.flat)[len(keys):]:
        ax.axis("off")
    axes.flat[0].legend(fontsize=7)
    title = "rotorcosim against the paper's Table 5 (shaded: paper +-30 %)"
    if sc:
        title += (f"; {sc['within_30pct']}/{sc['cells']} cells within +-30 %, {sc['within_x2']}/{sc['cells']} "
                  f"within x2")
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    tmp = path.with_name(path.stem + ".part.png")
    fig.savefig(tmp, dpi=110)
    plt.close(fig)
    os.replace(tmp, path)


def write(out: Path, by_level: dict) -> dict | None:
    """DIR/paper_comparison.csv and DIR/paper_comparison.png for the paper's levels among ``by_level``; returns
    the score (None when no level is one of the paper's)."""
    rows = compare(by_level)
    if not rows:
        return None
    sc = score(rows)
    write_csv(Path(out) / "paper_comparison.csv", rows)
    figure(Path(out) / "paper_comparison.png", rows, sc)
    return sc


def read_table5(path: Path) -> dict:
    """A table5.csv of ours (``rotorcosim sweep``'s) as ``by_level`` summaries, to score a finished sweep."""
    text = read_text(path, "Table 5 file")
    rows = [r for r in csv.reader(line for line in text.splitlines() if not line.startswith("#"))]
    levels = [float(x) for x in rows[0][2:]]
    out = {lv: {"bearings": {"0": {}, "5": {}}} for lv in levels}
    for r in rows[1:]:
        for lv, x in zip(levels, r[2:]):
            if x != "":
                out[lv]["bearings"].setdefault(r[1], {})[r[0]] = float(x)
    return out


def score_line(sc: dict, out) -> str:
    """The line ``rotorcosim sweep`` prints for the score ``sc`` of the sweep in ``out``."""
    return (f"against the paper's Table 5 ({out}/paper_comparison.csv, .png): {sc['within_30pct']}/"
            f"{sc['cells']} cells within +-30 %, {sc['within_x2']}/{sc['cells']} within x2")


def of_the_paper_engine(summary: dict) -> bool:
    """Whether a run's summary is of the paper's engine: its rotor's model file the shipped one, or a copy of it
    (the same bytes, the files it extends included: a sweep over a copied engine file is the paper's engine); a
    summary that does not say, a case that failed before it started, counts as the paper's."""
    from rotorcosim.components.rotor.model import DEFAULT_FILE, file_digest

    rotor = summary.get("provenance", {}).get("parameters", {}).get("rotor", {})
    model = rotor.get("parameters", {}).get("model_file") if isinstance(rotor, dict) else None
    if not model or Path(str(model)).resolve() == Path(DEFAULT_FILE).resolve():
        return True
    try:
        return file_digest(str(model)) == file_digest(None)
    except (OSError, ValueError):       # the file is gone or unreadable since the run: not known to be the paper's
        return False


def sweep_tables(out: Path, by_level: dict) -> dict | None:
    """A sweep with one case per unbalance level (``by_level``: F_u [N] -> summary): ``table5.csv`` /
    ``table5.md`` in ``out``, and the comparison with the paper for its levels; returns the score (or None).
    A sweep of another engine is not scored against the paper's, which are of another machine."""
    paper = all(of_the_paper_engine(s) for s in by_level.values())
    write_table5(out, by_level, beside_paper=paper)
    return write(out, by_level) if paper else None
