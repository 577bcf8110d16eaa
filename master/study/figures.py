"""The studies' figures (PNG): a calibration's results against its targets before and after, a UQ's histograms and
its tornado chart. Each is drawn from the study's JSON report (and table), so it can be redrawn from the files.

>>> import json, pathlib, tempfile
>>> d = pathlib.Path(tempfile.mkdtemp())
>>> calibration_figure(d / "c.png", {"targets": [{"case": "", "result": "x", "value": 2.0, "holdout": False,
...                                               "start": 3.0, "final": 2.1}]})
>>> (d / "c.png").stat().st_size > 0
True
"""
from __future__ import annotations

import math
import os
from pathlib import Path

from rotorcosim.master.study.targets import BAND


def _plt():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def _save(fig, path: Path) -> None:
    path = Path(path)
    tmp = path.with_name(path.stem + ".part.png")
    fig.savefig(tmp, dpi=110)
    _plt().close(fig)
    os.replace(tmp, path)


def calibration_figure(path: Path, report: dict) -> None:
    """Ours / target for every target, before (open) and after (filled) the update; fit targets left, holdout
    targets right of the dashed line, each group in the order of the targets file; the +-30 % band shaded, the
    x2 lines dotted."""
    plt = _plt()
    rows = report.get("targets", [])
    rows = sorted(rows, key=lambda r: r["holdout"])     # fit targets first, each group in the targets file's order
    n = max(1, len(rows))
    # one column of markers per target, labelled below: wide enough to read, at most ~22 in (150 targets)
    fig, ax = plt.subplots(figsize=(min(22.0, max(6.0, 0.14 * n + 2)), 6.5))

    def ratio(v, t):
        return v / t if v is not None and t not in (0, None) and v / t > 0 else math.nan

    x = list(range(len(rows)))
    before = [ratio(r["start"], r["value"]) for r in rows]
    after = [ratio(r["final"], r["value"]) for r in rows]
    colour = ["tab:orange" if r["holdout"] else "tab:blue" for r in rows]
    ax.axhspan(1 - BAND, 1 + BAND, color="0.9", lw=0)
    for y in (0.5, 2.0):
        ax.axhline(y, color="0.5", ls=":", lw=0.8)
    ax.axhline(1.0, color="0.3", lw=0.8)
    ax.scatter(x, before, facecolors="none", edgecolors=colour, s=28, label="before")
    ax.scatter(x, after, c=colour, s=22, label="after")
    for xi, b, a in zip(x, before, after):
        if math.isfinite(b) and math.isfinite(a):
            ax.plot([xi, xi], [b, a], color="0.6", lw=0.6)
    nfit = sum(not r["holdout"] for r in rows)
    if 0 < nfit < len(rows):
        ax.axvline(nfit - 0.5, color="0.3", ls="--", lw=0.8)
        ax.text(nfit - 0.5, 0.98, "fit | holdout", ha="center", va="top", fontsize=8, backgroundcolor="white",
                transform=ax.get_xaxis_transform())
    vals = [v for v in before + after if math.isfinite(v)]
    if vals and max(vals) / min(vals) > 5:
        ax.set_yscale("log")
    ax.set_xticks(x)
    ax.set_xticklabels([f"{r['result']} @ {r['case']}" if r["case"] else r["result"] for r in rows],
                       rotation=90, fontsize=5 if n > 60 else 6)
    ax.set_ylabel("ours / target")
    fs = report.get("fit_score") or {}
    hs = report.get("holdout_score") or {}
    title = "calibration: ours / target, open = before, filled = after (blue fit, orange holdout; shaded +-30 %)"
    if fs:
        title += (f"\nfit within +-30 %: {report['fit_score_start']['within_30pct']} -> {fs['within_30pct']} of "
                  f"{fs['targets']}")
        if hs.get("targets"):
            title += (f"; holdout: {report['holdout_score_start']['within_30pct']} -> {hs['within_30pct']} of "
                      f"{hs['targets']}")
    ax.set_title(title, fontsize=8)
    ax.legend(fontsize=7, loc="best")
    fig.tight_layout()
    _save(fig, path)


def _failed_note(failed: dict | None, total: int | None) -> str:
    """The line the figures' titles add when samples failed, or ''."""
    n = (failed or {}).get("count", 0)
    if not n:
        return ""
    of = f" of {total}" if total else ""
    return f"\n{n}{of} samples failed and are left out (their errors: uq.json \"failed\")"


def histograms(path: Path, results: list[str], columns: dict[str, list[float]], stats: dict,
               failed: dict | None = None, total: int | None = None) -> None:
    """One histogram per result of the UQ's successful samples, its mean and 5th / 95th percentiles marked; the
    failed samples counted in the title, and a result without any successful sample says so in its panel."""
    plt = _plt()
    n = max(1, len(results))
    ncol = min(3, n)
    nrow = math.ceil(n / ncol)
    fig, axes = plt.subplots(nrow, ncol, figsize=(4.2 * ncol, 3.2 * nrow), squeeze=False)
    for ax, r in zip(axes.flat, results):
        xs = [v for v in columns.get(r, []) if v is not None and math.isfinite(v)]
        if xs:
            ax.hist(xs, bins=max(5, min(30, int(math.sqrt(len(xs))) + 2)), color="tab:blue", alpha=0.7)
            s = stats.get(r, {})
            for key, style in (("mean", "-"), ("p5", ":"), ("p95", ":")):
                if s.get(key) is not None:
                    ax.axvline(s[key], color="k", ls=style, lw=1)
        else:
            ax.text(0.5, 0.5, "no successful sample:\nnothing to draw", ha="center", va="center", fontsize=9,
                    color="tab:red", transform=ax.transAxes)
            ax.set_xticks([])
            ax.set_yticks([])
        ax.set_title(r, fontsize=8)
        ax.tick_params(labelsize=7)
    for ax in list(axes.flat)[len(results):]:
        ax.axis("off")
    note = _failed_note(failed, total)
    fig.suptitle("UQ: distribution of each result (line: mean; dotted: 5th / 95th percentiles)" + note, fontsize=9,
                 color="tab:red" if note else "k")
    fig.tight_layout(rect=(0, 0, 1, 0.93 if note else 0.96))
    _save(fig, path)


def tornado(path: Path, results: list[str], names: list[str], bars: dict[str, list], base: dict[str, float],
            failed: dict | None = None, total: int | None = None) -> None:
    """One tornado chart per result: the result at each parameter's 5th and 95th percentile, the others at
    their means (``bars[result][j] = (low, high)``), widest bar on top, around ``base[result]``."""
    plt = _plt()
    n = max(1, len(results))
    ncol = min(2, n)
    nrow = math.ceil(n / ncol)
    fig, axes = plt.subplots(nrow, ncol, figsize=(5.5 * ncol, 0.45 * len(names) * nrow + 1.6 * nrow),
                             squeeze=False)
    for ax, r in zip(axes.flat, results):
        b = bars.get(r)
        if not b:
            ax.set_title(f"{r}: no sensitivities", fontsize=8)
            ax.text(0.5, 0.5, "too few successful samples" if (failed or {}).get("count") else "no sensitivities",
                    ha="center", va="center", fontsize=9, color="tab:red", transform=ax.transAxes)
            ax.axis("off")
            continue
        order = sorted(range(len(names)), key=lambda j: abs(b[j][1] - b[j][0]))
        y0 = base[r]
        for k, j in enumerate(order):
            lo, hi = b[j]
            ax.barh(k, lo - y0, left=y0, color="tab:blue", alpha=0.8)
            ax.barh(k, hi - y0, left=y0, color="tab:orange", alpha=0.8)
        ax.axvline(y0, color="k", lw=0.8)
        ax.set_yticks(range(len(order)))
        ax.set_yticklabels([names[j] for j in order], fontsize=7)
        ax.set_title(r, fontsize=8)
        ax.tick_params(axis="x", labelsize=7)
    for ax in list(axes.flat)[len(results):]:
        ax.axis("off")
    note = _failed_note(failed, total)
    fig.suptitle("UQ tornado: each parameter at its 5th (blue) / 95th (orange) percentile, others at their means "
                 "(linear regression on the samples)" + note, fontsize=8, color="tab:red" if note else "k")
    fig.tight_layout(rect=(0, 0, 1, 0.93 if note else 0.97))
    _save(fig, path)
