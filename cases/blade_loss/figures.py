"""Figures of a blade-loss run, like the paper's Figs. 9-14, from the recorded time series (in memory).

Conventions, so that each figure reads at a glance:

* time axes in absolute simulated seconds (no offset notation: the steady-state panel of a 2-minute run reads
  119.90 ... 120.00 s);
* "(a) transient" is the first thermo-mechanical (TM) interval, "(b) steady state" the last one; a run with a
  single TM interval gets one panel, not the same data twice;
* whole-run plots shade the thermal-only (TO) intervals;
* each orbit is scaled to itself (the last 5 rotor cycles); the rub-ring clearance circle is drawn where it is in
  range of the orbit, and stated otherwise, with the largest rotor-to-housing radius at the ring;
* Fig. 12 plots the inner-race stress (solid), the summary's ``max_contact_stress_MPa`` (the contact the paper's
  Table 5 load/stress pairs describe: they follow the inner-race Hertz law, ~248 Q^(1/3) MPa at #0, although its
  text says outer race), with the outer race's (dashed, ``max_contact_stress_outer_MPa``; at light loads the
  balls' centrifugal force makes it the larger);
* "(paper Fig. N)" only on the paper's own cases (a shipped blade-loss scenario at one of Table 5's levels,
  unchanged); any other run is titled by its scenario name.
"""
from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from rotorcosim.cases.blade_loss.table5 import PAPER_LEVELS
from rotorcosim.cases.blade_loss.results import BEARINGS, KELVIN, NODES

RUB_CLEARANCE_MM = 0.508  # Table 3 (both rings)
PLASTIC_FLOW_MPA = 3200.0  # the paper's incipient plastic flow limit of the ball/race contact [13]
ORBIT_CYCLES = 5
DPI = 110
#: zlib level of the PNG files (lossless at any level): 1 instead of Pillow's 6 encodes the six figures in 0.23 s
#: of CPU instead of 0.42 s, for files ~9 % larger (1.09 MB instead of 1.0 MB in all, 2850 N main job)
PNG_COMPRESS_LEVEL = 1
#: points drawn per line at most: a longer stretch is drawn as its min/max envelope (a 2-minute monolithic run
#: has 1.2 million samples per signal; a panel is ~600 pixels wide, so this loses nothing the eye can see)
PLOT_POINTS = 4000
#: the figures, in the order they are written (the job names of :func:`draw`)
JOBS = ("fig09", "fig10", "fig11", "fig12", "fig13", "fig14")


@dataclass(frozen=True)
class Context:
    """What the figures need of the run besides its series (plain values: the figures can be drawn in another
    process)."""
    name: str  # the scenario's name, in the titles of runs that are not one of the paper's cases
    F_u: float  # blade-loss force [N]
    speed_rpm: float | None  # rotor speed, for the orbit window in rotor cycles
    paper: bool  # one of the paper's own cases: titled "(paper Fig. N)"


def context(sc, F_u: float, speed_rpm: float | None) -> Context:
    """The :class:`Context` of a run of scenario ``sc`` with blade-loss force ``F_u`` [N] at the rotor speed
    ``speed_rpm`` [rev/min] (None: not declared)."""
    return Context(sc.name, float(F_u), speed_rpm, is_paper_case(sc, F_u))


def envelope(t: np.ndarray, y: np.ndarray, points: int = PLOT_POINTS) -> tuple[np.ndarray, np.ndarray]:
    """``(t, y)`` with at most ~``points`` samples: beyond that, each of points/2 buckets of consecutive samples
    is replaced by its minimum and maximum, in their time order (``y`` 1-D)."""
    n = len(t)
    if n <= points:
        return t, y
    buckets = points // 2
    size = -(-n // buckets)  # ceil
    pad = buckets * size - n
    yp = np.concatenate([y, np.full(pad, y[-1])]).reshape(buckets, size)
    lo, hi = np.argmin(yp, axis=1), np.argmax(yp, axis=1)
    first, second = np.minimum(lo, hi), np.maximum(lo, hi)
    base = np.arange(buckets) * size
    idx = np.minimum(np.column_stack([base + first, base + second]).ravel(), n - 1)
    return t[idx], y[idx]


def is_paper_case(sc, F_u: float) -> bool:
    """A shipped blade-loss scenario at one of Table 5's levels, every component and parameter as shipped."""
    from rotorcosim import scenarios

    folder = Path(scenarios.FOLDER).resolve()

    def shipped(f) -> bool:
        try:
            return f is not None and Path(f).resolve().parent == folder
        except (OSError, TypeError):
            return False

    if not shipped(sc.source) or float(F_u) not in PAPER_LEVELS:
        return False
    for spec in sc.components.values():
        if not shipped(spec.origin) or not all(shipped(o) for o in spec.param_origins.values()):
            return False
    return all(shipped(c.origin) for c in sc.connections)


def tm_blocks(phase: np.ndarray) -> list[tuple[int, int]]:
    """(start, end) index pairs of the consecutive thermo-mechanical samples."""
    tm = np.asarray(phase) == 0
    edges = np.flatnonzero(np.diff(np.r_[0, tm.astype(int), 0]))
    return list(zip(edges[::2], edges[1::2]))


def to_spans(t: np.ndarray, phase: np.ndarray) -> list[tuple[float, float]]:
    """(t_start, t_end) of the thermal-only stretches (from the last TM sample before to the last TO sample)."""
    to = np.asarray(phase) == 1
    edges = np.flatnonzero(np.diff(np.r_[0, to.astype(int), 0]))
    return [(float(t[max(a - 1, 0)]), float(t[b - 1])) for a, b in zip(edges[::2], edges[1::2])]


def _absolute_time(ax) -> None:
    from matplotlib.ticker import ScalarFormatter

    fmt = ScalarFormatter(useOffset=False)
    fmt.set_scientific(False)
    ax.xaxis.set_major_formatter(fmt)


def _shade_to(ax, spans) -> None:
    for i, (a, b) in enumerate(spans):
        ax.axvspan(a, b, color="0.88", lw=0, zorder=0, label="thermal-only intervals" if i == 0 else None)


def _panels(blocks):
    """The time panels: (a) transient = first TM interval, (b) steady state = the last one (one panel when the
    run has a single TM interval)."""
    if len(blocks) == 1:
        return [(blocks[0], "thermo-mechanical interval")]
    return [(blocks[0], "(a) transient: first thermo-mechanical interval"),
            (blocks[-1], "(b) steady state: last thermo-mechanical interval")]


def _margins(fig, left=0.8, right=0.25, bottom=0.55, top=0.8, wgap=0.85, hgap=0.85) -> None:
    """Fixed margins in inches (room for tick labels, axis labels, panel titles and the figure title): the same
    look as ``tight_layout`` for these figures at a third of the drawing cost (it draws every text twice)."""
    w, h = fig.get_size_inches()
    rows, cols = fig.axes[0].get_subplotspec().get_gridspec().get_geometry()
    aw = (w - left - right - (cols - 1) * wgap) / cols  # mean axes width and height
    ah = (h - top - bottom - (rows - 1) * hgap) / rows
    fig.subplots_adjust(left=left / w, right=1 - right / w, bottom=bottom / h, top=1 - top / h,
                        wspace=wgap / aw if cols > 1 else 0.2, hspace=hgap / ah if rows > 1 else 0.2)


def _plot(a, t, y, *args, **kw):
    a.plot(*envelope(t, y), *args, **kw)


class _Figures:
    def __init__(self, ctx: Context, data, out: Path):
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        self.plt = plt
        self.ctx, self.d, self.out, self.F_u = ctx, data, Path(out), ctx.F_u
        self.t = np.asarray(data["time"])
        self.phase = np.asarray(data["phase"])
        self.blocks = tm_blocks(self.phase)
        self.panels = _panels(self.blocks) if self.blocks else []
        self.spans = to_spans(self.t, self.phase)
        self.cycle = 60.0 / ctx.speed_rpm if ctx.speed_rpm else None
        self.names: list[str] = []

    def get(self, ref):
        return self.d.get(ref)

    def title(self, text: str, fig_no: int) -> str:
        tag = f" (paper Fig. {fig_no})" if self.ctx.paper else f" [{self.ctx.name}]"
        return f"{text}, F_u = {self.F_u:g} N{tag}"

    def save(self, fig, name: str) -> None:
        _margins(fig)
        # written whole or not at all, like every result file
        tmp = self.out / (name + ".part")
        fig.savefig(tmp, dpi=DPI, format="png", pil_kwargs={"compress_level": PNG_COMPRESS_LEVEL})
        self.plt.close(fig)
        os.replace(tmp, self.out / name)
        self.names.append(name)

    def window(self) -> tuple[int, int]:
        """Index range of the last ORBIT_CYCLES rotor cycles of the last TM interval."""
        i0, i1 = self.blocks[-1]
        if self.cycle is None or i1 - i0 < 3:
            return i0, i1
        t_from = self.t[i1 - 1] - ORBIT_CYCLES * self.cycle
        return max(i0, int(np.searchsorted(self.t[i0:i1], t_from)) + i0), i1

    # -- Figs. 9 and 10 --------------------------------------------------------------------------------
    def response(self, k: int, fig_no: int) -> None:
        X = self.get(f"rotor.X_brg{k}")
        if X is None:
            return
        n = len(self.panels)
        fig, ax = self.plt.subplots(1, n + 1, figsize=(5.2 * (n + 1), 4.2),
                                    gridspec_kw={"width_ratios": [1.6] * n + [1.0]})
        for a, ((i0, i1), title) in zip(ax[:n], self.panels):
            _plot(a, self.t[i0:i1], 1e3 * X[i0:i1, 0], "-", lw=0.8, label="x")
            _plot(a, self.t[i0:i1], 1e3 * X[i0:i1, 1], ":", lw=0.9, label="y")
            a.set_xlabel("time [s]")
            a.set_ylabel("displacement [mm]")
            a.set_title(title, fontsize=10)
            a.legend(loc="upper right", fontsize=8)
            _absolute_time(a)
        self.orbit(ax[n], k, X)
        fig.suptitle(self.title(f"Power turbine at bearing #{k}", fig_no))
        self.save(fig, f"fig{fig_no:02d}_response_bearing{k}.png")

    def orbit(self, a, k: int, X) -> None:
        w0, w1 = self.window()
        x, y = 1e3 * X[w0:w1, 0], 1e3 * X[w0:w1, 1]
        a.plot(x, y, lw=0.9, label=f"orbit, last {ORBIT_CYCLES} rotor cycles")
        cx, cy = 0.5 * (x.max() + x.min()), 0.5 * (y.max() + y.min())
        half = max(x.max() - x.min(), y.max() - y.min(), 1e-9) * 0.5 * 1.25
        r_max = float(np.max(np.hypot(x, y)))
        # the largest rotor-to-housing radius at the ring (what the clearance is about), when recorded
        Xr, Xh = self.get(f"rotor.X_rub{k}"), self.get(f"rotor.X_housing{k}")
        ring = None
        if Xr is not None and Xh is not None:
            ring = 1e3 * float(np.max(np.hypot(*(Xr[w0:w1] - Xh[w0:w1]).T)))
        notes = []
        if RUB_CLEARANCE_MM <= 2.0 * r_max:  # in range of the orbit: draw it, and scale to show it
            th = np.linspace(0, 2 * np.pi, 200)
            a.plot(RUB_CLEARANCE_MM * np.cos(th), RUB_CLEARANCE_MM * np.sin(th), "k:", lw=1,
                   label=f"rub-ring clearance {RUB_CLEARANCE_MM} mm")
            half = max(half, 1.1 * RUB_CLEARANCE_MM)
            cx = cy = 0.0
        else:
            notes.append(f"rub-ring clearance {RUB_CLEARANCE_MM} mm: off this scale")
        if ring is not None:
            # the orbit is the rotor's absolute motion at the bearing; the clearance applies at the ring, to the
            # rotor's motion relative to the housing there
            notes.append(f"at the ring, rotor - housing: largest radius {ring:.3g} mm")
        if notes:
            a.text(0.03, 0.03, "\n".join(notes), transform=a.transAxes, fontsize=7.5, va="bottom",
                   bbox=dict(boxstyle="round", fc="white", ec="0.7"))
        a.set_xlim(cx - half, cx + half)
        a.set_ylim(cy - half, cy + half)
        a.set_aspect("equal")
        a.set_xlabel("x [mm]")
        a.set_ylabel("y [mm]")
        a.set_title(("(c) " if len(self.panels) > 1 else "") + "orbit", fontsize=10)
        a.legend(loc="upper right", fontsize=7)

    # -- Figs. 11 and 12: bearings in rows, time panels in columns ---------------------------------------
    def per_bearing(self, series: dict, ylabel: str, name: str, text: str, fig_no: int, line=None,
                    styles=None) -> None:
        """One row per bearing; ``series[k]`` is (n,) or (n, m) with ``styles`` ((linestyle, label) per column)."""
        rows = [k for k in BEARINGS if series.get(k) is not None]
        if not rows or not self.panels:
            return
        n = len(self.panels)
        fig, ax = self.plt.subplots(len(rows), n, figsize=(max(9.0, 6.2 * n), 3.3 * len(rows)), squeeze=False)
        for r, k in enumerate(rows):
            s = series[k]
            for c, ((i0, i1), title) in enumerate(self.panels):
                a = ax[r, c]
                cols = s.reshape(len(s), -1)
                for j in range(cols.shape[1]):
                    ls, lab = styles[j] if styles else ("-", None)
                    _plot(a, self.t[i0:i1], cols[i0:i1, j], ls, lw=0.8, color="C0", label=lab)
                if line is not None:
                    value, label = line
                    a.axhline(value, color="r", ls=":", lw=0.9, label=label)
                if line is not None or styles:
                    a.legend(loc="best", fontsize=7)
                a.set_title(f"bearing #{k}: {title}", fontsize=10)
                a.set_xlabel("time [s]")
                a.set_ylabel(ylabel)
                _absolute_time(a)
        fig.suptitle(self.title(text, fig_no))
        self.save(fig, name)

    # -- Figs. 13 and 14: the whole run, TO intervals shaded ---------------------------------------------
    def temperatures(self, fig_no: int, pair) -> None:
        fig, ax = self.plt.subplots(1, 2, figsize=(12, 4.2))
        drawn = False
        for a, (node, title) in zip(ax, pair):
            _shade_to(a, self.spans)
            for k, style in ((0, "-"), (5, ":")):
                T = self.get(f"thermal{k}.T_nodes")
                if T is not None:
                    _plot(a, self.t, T[:, NODES.index(node)] - KELVIN, style, label=f"bearing #{k}")
                    drawn = True
            a.set_xlabel("time [s]")
            a.set_ylabel("temperature [°C]")
            a.set_title(title, fontsize=10)
            a.legend(fontsize=8)
            _absolute_time(a)
        if not drawn:
            self.plt.close(fig)
            return
        fig.suptitle(self.title("Temperatures", fig_no))
        self.save(fig, f"fig{fig_no}_temperatures.png")


def draw(job: str, data, out: Path, ctx: Context) -> list[str]:
    """Draw the figure ``job`` (one of :data:`JOBS`) into ``out``; returns the file names written (none when
    the run did not record what it shows). ``data``: ``time``, ``phase`` and one array per recorded port, a dict
    or a :class:`~rotorcosim.master.observer.series.SeriesFile`."""
    f = _Figures(ctx, data, out)
    if not f.blocks:
        return []
    if job in ("fig09", "fig10"):
        k = 0 if job == "fig09" else 5
        f.response(k, int(job[3:]))
    elif job == "fig11":
        trans = {}
        for k in BEARINGS:
            F = f.get(f"damper{k}.F_journal")
            if F is not None and f.F_u > 0:
                trans[k] = np.hypot(F[:, 0], F[:, 1]) / f.F_u
        f.per_bearing(trans, "transmissibility, eq. (23)", "fig11_transmissibility.png",
                      "Transmissibility |F_sfd + F_cs| / F_u", 11)
    elif job == "fig12":
        stress = {k: 1e-6 * S for k in BEARINGS if (S := f.get(f"bearing{k}.sigma_max")) is not None}
        f.per_bearing(stress, "max contact stress [MPa]", "fig12_contact_stress.png",
                      "Maximum ball contact stress (reported: inner race, solid)", 12,
                      line=(PLASTIC_FLOW_MPA, f"incipient plastic flow {PLASTIC_FLOW_MPA:.0f} MPa"),
                      styles=(("-", "inner race (reported)"), ("--", "outer race")))
    elif job == "fig13":
        f.temperatures(13, (("inner_race", "(a) inner race"), ("ball", "(b) ball")))
    elif job == "fig14":
        f.temperatures(14, (("outer_race", "(a) outer race"), ("sfd_oil", "(b) squeeze film damper oil")))
    else:
        raise ValueError(f"no figure {job!r}; the figures are {', '.join(JOBS)}")
    return f.names


def figures(sc, data, out: Path, F_u: float, speed_rpm: float | None = None) -> list[str]:
    """Draw every figure into ``out``, in this process; returns their file names."""
    if data is None or "time" not in data or not len(data["time"]):
        return []
    ctx = context(sc, F_u, speed_rpm)
    return [name for job in JOBS for name in draw(job, data, out, ctx)]
