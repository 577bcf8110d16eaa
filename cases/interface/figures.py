"""The figure of the engine-to-airframe interface, from the recorded time series (``data``: ``time``, ``phase``
and one array per port): ``interface_loads.png``, for a run whose airframe's outputs were recorded.

Four panels: (a) each mount's load on the airframe (``airframe.F_NAME``, x y z [kN]) against time, from the start
to a minute after the last fuel cut (the whole run without one), (b) the same against the first spool's speed
over the coupled samples; (c), (d) the response points' accelerations (``airframe.a_P`` [g]) likewise. Each curve
is the envelope of the recorded samples: their largest magnitude per bin of :data:`BIN_SAMPLES` samples (the
recording step is coarser than the vibration's period). The blade loss (dash-dot), the fuel cuts (dotted) and the
located events (dashed) are marked on the time axes, the held (thermal-only) intervals shaded.
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from rotorcosim.master.observer.series import events_of
from rotorcosim.master.run.outputs import check_dpi

from .results import AXES, G, airframe_of

RPM = 30.0 / math.pi
#: recorded samples per envelope bin
BIN_SAMPLES = 20
#: the time panels end this long after the last fuel cut [s]
AFTER_CUT_S = 60.0
NAME = "interface_loads.png"


def _series(data, ref):
    try:
        return np.asarray(data[ref])
    except KeyError:
        return None


def envelope(x: np.ndarray, y: np.ndarray, n: int = BIN_SAMPLES) -> tuple[np.ndarray, np.ndarray]:
    """Per bin of ``n`` consecutive samples: the mean of ``x`` and the largest ``|y|`` (a column each)."""
    m = len(x) // n * n
    if m == 0:
        return np.asarray(x, float), np.abs(np.asarray(y, float))
    xb = np.asarray(x[:m], float).reshape(-1, n).mean(axis=1)
    yb = np.abs(np.asarray(y[:m], float)).reshape(-1, n, *np.shape(y)[1:]).max(axis=1)
    return xb, yb


def figures(sc, data, out, dpi: int | None = None, spool: str | None = None) -> list[str]:
    """Draw the figure (module docstring) into the folder ``out``; ``spool``: the spool component whose speed is
    the speed axis (None: no speed panels). Returns the file names ([] when nothing of the airframe was
    recorded)."""
    af = airframe_of(sc)
    t = _series(data, "time")
    if af is None or t is None or not len(t):
        return []
    mounts = sorted({k.split(".", 1)[1][2:] for k in _keys(data) if k.startswith(f"{af}.F_")
                     and not k.startswith(f"{af}.F_engine_")})
    points = sorted({k.split(".", 1)[1][2:] for k in _keys(data) if k.startswith(f"{af}.a_")})
    if not mounts and not points:
        return []
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    phase = _series(data, "phase")
    coupled = phase == 0 if phase is not None else np.ones(len(t), bool)
    w = _series(data, f"{spool}.Omega") if spool else None
    cuts = [float(c.parameters.get("t_fuel_cut", -1.0)) for c in sc.components.values()
            if c.implementation == "spool.speed"]
    cuts = [c for c in cuts if c >= 0.0]
    t_end = min(float(t[-1]), max(cuts) + AFTER_CUT_S) if cuts else float(t[-1])
    blade = sc.components["rotor"].parameters.get("t_blade_loss") if "rotor" in sc.components else None
    events = events_of(data)
    rows = [("mount", m, f"{af}.F_{m}", 1e-3, "load on the airframe [kN]") for m in mounts]
    rows += [("point", p, f"{af}.a_{p}", 1.0 / G, "acceleration [g]") for p in points]
    groups = [[r for r in rows if r[0] == "mount"], [r for r in rows if r[0] == "point"]]
    groups = [g for g in groups if g]
    ncol = 2 if w is not None else 1
    fig, axes = plt.subplots(len(groups), ncol, figsize=(6 * ncol, 3.6 * len(groups)), squeeze=False)
    styles = ("-", "--", ":", "-.")
    colours = ("tab:blue", "tab:orange", "tab:green")
    for gi, group in enumerate(groups):
        ax_t = axes[gi, 0]
        ax_w = axes[gi, 1] if w is not None else None
        for ri, (_, name, ref, scale, ylabel) in enumerate(group):
            y = _series(data, ref).reshape(len(t), 3) * scale
            sel = t <= t_end
            tb, yb = envelope(t[sel], y[sel])
            for c in range(3):
                ax_t.plot(tb, yb[:, c], ls=styles[ri % len(styles)], color=colours[c], lw=1,
                          label=f"{name} {AXES[c]}")
            if ax_w is not None:
                wr = w.reshape(len(t), -1)[:, 0] * RPM
                wb, yw = envelope(wr[coupled], y[coupled])
                for c in range(3):
                    ax_w.plot(wb, yw[:, c], ".", ms=2, color=colours[c], alpha=0.6,
                              label=f"{name} {AXES[c]}" if ri == 0 else None)
        _mark(ax_t, blade, cuts, events, phase, t, t_end)
        ax_t.set_xlim(0, t_end)
        ax_t.set_xlabel("time [s]")
        ax_t.set_ylabel(group[0][4])
        ax_t.set_ylim(bottom=0)
        ax_t.grid(alpha=0.3)
        ax_t.legend(fontsize=7, ncol=2)
        ax_t.set_title(f"({'ac'[gi]}) {'mount loads' if group[0][0] == 'mount' else 'response points'} against time "
                       "(envelope)", fontsize=9)
        if ax_w is not None:
            ax_w.set_xlabel("first spool speed [rev/min]")
            ax_w.set_ylabel(group[0][4])
            ax_w.set_ylim(bottom=0)
            ax_w.grid(alpha=0.3)
            ax_w.set_title(f"({'bd'[gi]}) against speed (coupled samples)", fontsize=9)
    fig.suptitle(f"{sc.name}: the engine-to-airframe interface (dash-dot: blade loss; dotted: fuel cut"
                 + ("; dashed: events" if events else "") + ")", fontsize=10)
    fig.tight_layout()
    fig.savefig(Path(out) / NAME, dpi=check_dpi(dpi))
    plt.close(fig)
    return [NAME]


def _keys(data) -> list[str]:
    try:
        return list(data.keys())
    except AttributeError:
        return list(data)


def _mark(ax, blade, cuts, events, phase, t, t_end) -> None:
    if blade is not None and float(blade) <= t_end:
        ax.axvline(float(blade), color="tab:purple", ls="-.", lw=1)
    for c in cuts:
        ax.axvline(c, color="tab:red", ls=":", lw=1)
    for e in events:
        ax.axvline(e["t_s"], color="k", ls="--", lw=0.8)
    if phase is not None:
        held = np.asarray(phase) == 1
        edges = np.diff(np.concatenate([[0], held.astype(int), [0]]))
        for a, b in zip(np.flatnonzero(edges == 1), np.flatnonzero(edges == -1) - 1):
            if t[max(a - 1, 0)] < t_end:
                ax.axvspan(t[max(a - 1, 0)], min(t[b], t_end), color="0.9", lw=0, zorder=0)
