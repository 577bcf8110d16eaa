"""Our Table 5 in the paper's format, and beside the paper's, cell by cell."""
from __future__ import annotations

import csv
import os
from pathlib import Path

from rotorcosim.cases.blade_loss.results import BEARINGS, RESULT_KEYS

from rotorcosim.cases.blade_loss import LEVELS

PAPER_LEVELS = LEVELS["paper"]
#: the paper's Table 5 is shipped beside the scenarios (a copy of shared/reference/table5.csv)
PAPER_TABLE5 = Path(__file__).resolve().with_name("reference_table5.csv")


def paper_table5() -> dict[tuple[str, int], dict[float, float]]:
    """The paper's Table 5 (reference_table5.csv): (result, bearing) -> {unbalance [N]: value}."""
    out = {}
    with open(PAPER_TABLE5) as f:
        rows = [r for r in csv.reader(line for line in f if not line.startswith("#"))]
    header = rows[0]
    levels = [float(x) for x in header[2:]]
    for r in rows[1:]:
        out[(r[0], int(r[1]))] = {lv: float(x) for lv, x in zip(levels, r[2:])}
    return out


def _fmt(x) -> str:
    return "" if x is None else f"{x:.6g}"


def bearing_ids(by_level: dict[float, dict]) -> list[str]:
    """The bearings the runs report, in the order they first appear (an engine of one's own names its own)."""
    ids: list[str] = []
    for summary in by_level.values():
        ids += [k for k in summary.get("bearings", {}) if k not in ids]
    return ids


def write_table5(out: Path, by_level: dict[float, dict], beside_paper: bool = True) -> None:
    """Write ``table5.csv`` and ``table5.md`` into the folder ``out``; ``by_level``: unbalance [N] -> that run's
    summary. ``beside_paper``: each cell beside the paper's value, for its bearings #0 and #5; otherwise (an
    engine of one's own: the paper's values are of another machine) our values alone, for the runs' bearings."""
    levels = list(by_level)
    ids = list(BEARINGS) if beside_paper else bearing_ids(by_level)
    rows = [["result", "bearing"] + [f"{f:g}" for f in levels]]
    for key in RESULT_KEYS:
        for k in ids:
            rows.append([key, str(k)] + [_fmt(by_level[f].get("bearings", {}).get(str(k), {}).get(key)) for f in levels])
    tmp = out / "table5.csv.part"
    with open(tmp, "w", newline="") as fh:
        fh.write("# rotorcosim: blade-loss results (paper Table 4 definitions); columns: unbalance force in N\n")
        csv.writer(fh).writerows(rows)
    os.replace(tmp, out / "table5.csv")
    lines = _beside_paper(by_level) if beside_paper else _ours_alone(by_level, ids)
    tmp = out / "table5.md.part"
    tmp.write_text("\n".join(lines) + "\n")
    os.replace(tmp, out / "table5.md")


def _head(title: str, cell: str, levels: list) -> list[str]:
    """The page's title, what a cell holds, and the table's header over the ``levels`` [N]."""
    return [f"# {title}", "", f"Each cell: {cell}.", "",
            "| result | brg | " + " | ".join(f"{f:g} N" for f in levels) + " |", "|---|---|" + "---|" * len(levels)]


def _ours_alone(by_level: dict[float, dict], ids: list[str]) -> list[str]:
    levels = list(by_level)
    lines = _head("Blade-loss results by unbalance level (the paper's Table 5 layout)",
                  "ours (the paper's values are of its own engine, not this one: not compared)", levels)
    for key in RESULT_KEYS:
        for k in ids:
            cells = [by_level[f].get("bearings", {}).get(k, {}).get(key) for f in levels]
            lines.append(f"| {key} | {k} | " + " | ".join("n/a" if v is None else f"{v:.4g}" for v in cells) + " |")
    return lines


def _beside_paper(by_level: dict[float, dict]) -> list[str]:
    levels = list(by_level)
    paper = paper_table5()
    lines = _head("Table 5: rotorcosim beside the paper", "ours / paper (difference in % of the paper's value)",
                  levels)
    for key in RESULT_KEYS:
        for k in BEARINGS:
            cells = []
            for f in levels:
                ours = by_level[f].get("bearings", {}).get(str(k), {}).get(key)
                ref = paper.get((key, k), {}).get(f)
                if ours is None:
                    cells.append("n/a")
                elif ref is None:
                    cells.append(f"{ours:.4g} / -")
                elif ref == 0:
                    cells.append(f"{ours:.4g} / 0")
                else:
                    cells.append(f"{ours:.4g} / {ref:.4g} ({100 * (ours - ref) / ref:+.0f} %)")
            lines.append(f"| {key} | {k} | " + " | ".join(cells) + " |")
    return lines

