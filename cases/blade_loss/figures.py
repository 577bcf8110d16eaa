"""Figures of a blade-loss run, like the paper's Figs. 9-14, from the recorded time series (in memory).

Conventions, so that each figure reads at a glance:

* time axes in absolute simulated seconds (no offset notation: the steady-state panel of a 2-minute run reads
  119.90 ... 120.00 s);
* "(a) transient" is the first thermo-mechanical (TM) interval, "(b) steady state" the last one; a run with a
  single TM interval gets one panel, not the same data twice;
* whole-run plots shade every interval of the timeline: thermal-only (TO) grey, thermo-mechanical (TM) purple,
  each at least :data:`MIN_SPAN_FRACTION` of the axis wide (a 0.1 s TM interval of a 2-minute run is a fraction
  of a pixel, drawn or not by the rasteriser's whim);
* the orbit (c) is the rotor's motion at the rub ring relative to the housing (what the ring's clearance is
  about), over the last 5 rotor cycles, against the clearance circle (drawn where it is in range of the orbit,
  :data:`CIRCLE_RANGE`, and stated in the legend otherwise); without a recorded ring and housing, the bearing's
  absolute orbit, so labelled;
* a ratio (the transmissibility) is drawn from zero, so that a 1 % restart transient looks like one;
* legends sit below the panels (one per figure), never over the data; a figure's resolution is ``dpi``
  (``rotorcosim run --dpi``, default :data:`~rotorcosim.master.run.outputs.FIGURE_DPI`);
* Fig. 12 plots the inner-race stress (solid), the summary's ``max_contact_stress_MPa`` (the contact the paper's
  Table 5 load/stress pairs describe: they follow the inner-race Hertz law, ~248 Q^(1/3) MPa at #0, although its
  text says outer race), with the outer race's (dashed, ``max_contact_stress_outer_MPa``; at light loads the
  balls' centrifugal force makes it the larger);
* one response figure per co-simulated bearing: the first bearing's is ``fig09_response_bearing<ID>.png``, every
  other's ``fig10_response_bearing<ID>.png`` (#0 and #5 for the paper's engine); Figs. 11-14 have a row or a line
  per bearing;
* "(paper Fig. N)" only on the paper's own cases (a shipped blade-loss scenario at one of Table 5's levels,
  unchanged); any other run is titled by its scenario name.
"""
from __future__ import annotations

import os
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from rotorcosim.cases.blade_loss.engine_names import bearing_spools, rub_clearances_mm
from rotorcosim.cases.blade_loss.table5 import PAPER_LEVELS
from rotorcosim.cases.blade_loss.results import KELVIN, NODES, PLASTIC_FLOW_MPA, bearing_ids
from rotorcosim.master.observer.series import events_of
from rotorcosim.master.run.outputs import FIGURE_DPI

ORBIT_CYCLES = 5
#: the narrowest a shaded interval is drawn, as a fraction of the axis's width (~3.7 pixels of a 5-inch axis at
#: 150 dpi): every interval of the timeline shows, however short
MIN_SPAN_FRACTION = 0.005
#: the clearance circle is drawn when the orbit's radius is at least 1/CIRCLE_RANGE of it (a smaller orbit would
#: shrink to a dot beside it; the legend states the clearance instead)
CIRCLE_RANGE = 4.0
#: room below the panels for the figure's legend [in]
LEGEND_ROOM_IN = 0.45
#: zlib level of the PNG files (lossless at any level): 1 instead of Pillow's 6 encodes the six figures in 0.23 s
#: of CPU instead of 0.42 s, for files ~9 % larger (1.09 MB instead of 1.0 MB in all, 2850 N main job)
PNG_COMPRESS_LEVEL = 1
#: points drawn per line at most: a longer stretch is drawn as its min/max envelope (a 2-minute monolithic run
#: has 1.2 million samples per signal; a panel is ~600 pixels wide, so this loses nothing the eye can see)
PLOT_POINTS = 4000
#: the figures, in the order they are written (the job names of :func:`draw`)
JOBS = ("fig09", "fig10", "fig11", "fig12", "fig13", "fig14")
#: the temperature lines of the bearings, in the order of their ids (#0 solid, #5 dotted for the paper's engine)
LINE_STYLES = ("-", ":", "--", "-.")


@dataclass(frozen=True)
class Context:
    """What the figures need of the run besides its series (plain values: the figures can be drawn in another
    process)."""
    name: str  # the scenario's name, in the titles of runs that are not one of the paper's cases
    F_u: float  # blade-loss force [N]
    speed_rpm: float | None  # rotor speed, for the orbit window in rotor cycles
    paper: bool  # one of the paper's own cases: titled "(paper Fig. N)"
    dpi: int = FIGURE_DPI  # resolution of the PNG files [dots per inch]
    bearings: tuple = ("0", "5")  # the ids of the co-simulated bearings (results.bearing_ids), in order
    #: (id, the engine's name of the spool the bearing is on), in the order of ``bearings``
    spools: tuple = (("0", "power turbine"), ("5", "power turbine"))
    #: (id, the run's rub-ring clearance at the bearing [mm], None: no rub ring or not known)
    rub_clearances_mm: tuple = (("0", 0.508), ("5", 0.508))

    def spool(self, k) -> str:
        """The engine's name of the spool bearing ``k`` is on, capitalised for a title."""
        name = dict(self.spools).get(str(k)) or "rotor"
        return name[:1].upper() + name[1:]

    def rub_clearance_mm(self, k) -> float | None:
        """The run's rub-ring clearance at bearing ``k`` [mm] (None: no rub ring there, or not known)."""
        return dict(self.rub_clearances_mm).get(str(k))


def context(sc, F_u: float, speed_rpm: float | None, dpi: int | None = None, out: Path | None = None) -> Context:
    """The :class:`Context` of a run of scenario ``sc`` with blade-loss force ``F_u`` [N] at the rotor speed
    ``speed_rpm`` [rev/min] (None: not declared), drawn at ``dpi`` (None: :data:`FIGURE_DPI`); ``out``: the
    run's folder (its summary's provenance gives the clearances the run had)."""
    ids = bearing_ids(sc.components)
    spools, clear = bearing_spools(sc, ids), rub_clearances_mm(sc, ids, out)
    return Context(sc.name, float(F_u), speed_rpm, is_paper_case(sc, F_u), int(dpi or FIGURE_DPI), ids,
                   tuple((k, spools[k]) for k in ids), tuple((k, clear[k]) for k in ids))


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

    from rotorcosim.components.rotor.model import DEFAULT_FILE

    folders = (Path(scenarios.FOLDER).resolve(), Path(scenarios.FOLDER).resolve() / "templates")
    engine = Path(DEFAULT_FILE).resolve()
    rotor = sc.components.get("rotor")
    model = rotor.parameters.get("model_file") if rotor is not None else None
    shipped_engine = not model or Path(str(model)).resolve() == engine

    def shipped(f) -> bool:   # a shipped scenario or template, or a value of the shipped engine file
        if f == "the engine":  # the rotor's engine file itself (master/scenario/engine.py)
            return shipped_engine
        try:
            if f is not None and Path(str(f).split(" [", 1)[0]).resolve() == engine:
                return True   # "<engine.toml> [damper.0] clearance_mm": a record of the shipped engine
            return f is not None and Path(f).resolve().parent in folders
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


def timeline_spans(t: np.ndarray, phase: np.ndarray) -> list[tuple[str, float, float]]:
    """Every interval of the run's timeline as recorded, in time order: ``(phase, t_start, t_end)`` with phase
    "TM" or "TO" (a TM stretch from its first to its last sample, a TO one as :func:`to_spans`)."""
    spans = [("TM", float(t[a]), float(t[b - 1])) for a, b in tm_blocks(phase)]
    spans += [("TO", a, b) for a, b in to_spans(t, phase)]
    return sorted(spans, key=lambda s: (s[1], s[2]))


def _absolute_time(ax) -> None:
    from matplotlib.ticker import MaxNLocator, ScalarFormatter

    fmt = ScalarFormatter(useOffset=False)
    fmt.set_scientific(False)
    ax.xaxis.set_major_formatter(fmt)
    # at most 6 labels: "119.90 ... 120.00" are six characters each
    ax.xaxis.set_major_locator(MaxNLocator(nbins=6, steps=[1, 2, 2.5, 5, 10]))


#: the colours of the shaded intervals, by phase
SPAN_STYLE = {"TO": dict(color="0.88", label="thermal-only intervals"),
              "TM": dict(color="#d4bfe6", label="thermo-mechanical intervals")}


def _shade_timeline(ax, spans, t_end: float) -> None:
    """Shade every interval of ``spans`` (:func:`timeline_spans`), each at least :data:`MIN_SPAN_FRACTION` of
    the run wide (centred on its middle), one legend entry per phase."""
    least = MIN_SPAN_FRACTION * max(t_end - (spans[0][1] if spans else 0.0), 1e-30)
    seen = set()
    for phase, a, b in spans:
        if b - a < least:
            mid = 0.5 * (a + b)
            a, b = mid - 0.5 * least, mid + 0.5 * least
        style = SPAN_STYLE[phase]
        ax.axvspan(a, b, color=style["color"], lw=0, zorder=0, gid=f"span-{phase}",
                   label=style["label"] if phase not in seen else None)
        seen.add(phase)


def _panels(blocks):
    """The time panels: (a) transient = first TM interval, (b) steady state = the last one (one panel when the
    run has a single TM interval)."""
    if len(blocks) == 1:
        return [(blocks[0], "thermo-mechanical interval")]
    return [(blocks[0], "(a) transient: first thermo-mechanical interval"),
            (blocks[-1], "(b) steady state: last thermo-mechanical interval")]


def _margins(fig, left=0.85, right=0.25, bottom=0.55, top=0.8, wgap=0.95, hgap=0.85) -> None:
    """Fixed margins in inches (room for tick labels, axis labels, panel titles, the figure title and, when
    the figure has one, its legend below the panels): the same look as ``tight_layout`` for these figures at a
    third of the drawing cost (it draws every text twice)."""
    if fig.legends:
        bottom += LEGEND_ROOM_IN
    w, h = fig.get_size_inches()
    rows, cols = fig.axes[0].get_subplotspec().get_gridspec().get_geometry()
    aw = (w - left - right - (cols - 1) * wgap) / cols  # mean axes width and height
    ah = (h - top - bottom - (rows - 1) * hgap) / rows
    fig.subplots_adjust(left=left / w, right=1 - right / w, bottom=bottom / h, top=1 - top / h,
                        wspace=wgap / aw if cols > 1 else 0.2, hspace=hgap / ah if rows > 1 else 0.2)


def _legend_below(fig, axes) -> None:
    """One legend for the figure, below its panels: the entries of ``axes`` (each label once, in order)."""
    handles, labels = [], []
    for a in axes:
        for h, lab in zip(*a.get_legend_handles_labels()):
            if lab not in labels:
                handles.append(h)
                labels.append(lab)
    if handles:
        fig.legend(handles, labels, loc="lower center", bbox_to_anchor=(0.5, 0.01), ncol=len(labels) if len(labels) <= 5 else 3,
                   fontsize=8, frameon=False)


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
        self.spans = timeline_spans(self.t, self.phase) if len(self.t) else []
        self.cycle = 60.0 / ctx.speed_rpm if ctx.speed_rpm else None
        self.names: list[str] = []
        #: the figures drawn, kept open instead of closed when set (a test reads their text extents)
        self.keep: list | None = None
        #: the run's located events (master/core/events.py), marked on every time axis
        self.events = events_of(data)

    def get(self, ref):
        return self.d.get(ref)

    def title(self, text: str, fig_no: int) -> str:
        tag = f" (paper Fig. {fig_no})" if self.ctx.paper else f" [{self.ctx.name}]"
        return f"{text}, F_u = {self.F_u:g} N{tag}"

    def mark_events(self, fig) -> None:
        """A dashed line at each located event on every time axis of ``fig`` (those labelled "time ...", and
        those sharing their x axis) that shows its time."""
        timed = [a for a in fig.axes if a.get_xlabel().startswith("time")]
        for a in fig.axes:
            if not (a in timed or any(a.get_shared_x_axes().joined(a, b) for b in timed)):
                continue
            lo, hi = a.get_xlim()
            for e in self.events:
                if lo <= e["t_s"] <= hi:
                    a.axvline(e["t_s"], color="k", ls="--", lw=0.8, gid=f"event-{e['component']}-{e['kind']}")

    def save(self, fig, name: str) -> None:
        if self.events:
            self.mark_events(fig)
        _margins(fig)
        # written whole or not at all, like every result file
        tmp = self.out / (name + ".part")
        fig.savefig(tmp, dpi=self.ctx.dpi, format="png", pil_kwargs={"compress_level": PNG_COMPRESS_LEVEL})
        if self.keep is None:
            self.plt.close(fig)
        else:
            self.keep.append(fig)
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
            _absolute_time(a)
        self.orbit(ax[n], k, X)
        _legend_below(fig, ax)
        fig.suptitle(self.title(f"{self.ctx.spool(k)} at bearing #{k}", fig_no))
        self.save(fig, f"fig{fig_no:02d}_response_bearing{k}.png")

    def orbit(self, a, k: int, X) -> None:
        """The orbit over the last rotor cycles: the rotor's motion at the rub ring relative to the housing,
        against the ring's clearance circle (the clearance is about that motion; the absolute orbit at the bearing
        drawn over the circle made the rotor seem to pass through the ring). Without a recorded ring and housing,
        the bearing's absolute orbit, so labelled, and no circle."""
        from matplotlib.ticker import MaxNLocator

        w0, w1 = self.window()
        Xh, Xr = self.get(f"rotor.X_housing{k}"), self.get(f"rotor.X_rub{k}")
        relative = Xh is not None and Xr is not None
        if relative:
            xy = 1e3 * (np.asarray(Xr[w0:w1, :2]) - np.asarray(Xh[w0:w1, :2]))
            label, where = "rotor at the rub ring, relative to the housing", "at the rub ring, relative to the housing"
        else:
            xy = 1e3 * np.asarray(X[w0:w1, :2])
            label, where = "rotor at the bearing (absolute)", "at the bearing"
        a.plot(xy[:, 0], xy[:, 1], lw=0.9, color="C2", label=label)
        cx, cy = 0.5 * (xy.max(axis=0) + xy.min(axis=0))
        half = max(float(np.ptp(xy[:, 0])), float(np.ptp(xy[:, 1])), 1e-9) * 0.5 * 1.25
        clearance = self.ctx.rub_clearance_mm(k)
        if relative and clearance is not None:
            r = float(np.max(np.hypot(*xy.T)))
            text = f"rub-ring clearance {clearance:.4g} mm"
            if clearance <= CIRCLE_RANGE * r:  # in range of the orbit: draw it, and scale to show it
                th = np.linspace(0, 2 * np.pi, 200)
                a.plot(clearance * np.cos(th), clearance * np.sin(th), "k:", lw=1, label=text)
                half = max(half, 1.1 * clearance)
                cx = cy = 0.0
            else:  # a legend entry without a line: the circle would shrink the orbit to a dot
                a.plot([], [], " ", label=f"{text}: off this scale (orbit radius {r:.2g} mm)")
        a.set_xlim(cx - half, cx + half)
        a.set_ylim(cy - half, cy + half)
        a.set_aspect("equal")
        for axis in (a.xaxis, a.yaxis):  # a narrow square panel: 5 labels like "-0.015" fit, 7 overlap
            axis.set_major_locator(MaxNLocator(nbins=4))
        a.set_xlabel("x [mm]")
        a.set_ylabel("y [mm]")
        a.set_title(("(c) " if len(self.panels) > 1 else "") + f"orbit {where}", fontsize=10)

    # -- Figs. 11 and 12: bearings in rows, time panels in columns ---------------------------------------
    def per_bearing(self, series: dict, ylabel: str, name: str, text: str, fig_no: int, line=None,
                    styles=None, ratio: bool = False) -> None:
        """One row per bearing; ``series[k]`` is (n,) or (n, m) with ``styles`` ((linestyle, label) per column).
        ``ratio``: the quantity is a ratio, drawn from zero."""
        rows = [k for k in self.ctx.bearings if series.get(k) is not None]
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
                if ratio:
                    top = float(np.nanmax(cols[i0:i1])) if i1 > i0 else 1.0
                    a.set_ylim(0.0, 1.1 * top if top > 0 else 1.0)
                a.yaxis.get_major_locator().set_params(nbins=6)
                a.set_title(f"bearing #{k}: {title}", fontsize=10)
                a.set_xlabel("time [s]")
                a.set_ylabel(ylabel)
                _absolute_time(a)
        _legend_below(fig, ax.ravel())
        fig.suptitle(self.title(text, fig_no))
        self.save(fig, name)

    # -- Figs. 13 and 14: the whole run, every interval of the timeline shaded ---------------------------
    def temperatures(self, fig_no: int, pair) -> None:
        fig, ax = self.plt.subplots(1, 2, figsize=(12, 4.2))
        drawn = False
        for a, (node, title) in zip(ax, pair):
            for k, style in zip(self.ctx.bearings, LINE_STYLES * len(self.ctx.bearings)):
                T = self.get(f"thermal{k}.T_nodes")
                if T is not None:
                    _plot(a, self.t, T[:, NODES.index(node)] - KELVIN, style, label=f"bearing #{k}")
                    drawn = True
            _shade_timeline(a, self.spans, float(self.t[-1]))
            pad = 0.01 * (float(self.t[-1]) - float(self.t[0]))  # the first and last intervals clear the spines
            a.set_xlim(float(self.t[0]) - pad, float(self.t[-1]) + pad)
            a.set_xlabel("time [s]")
            a.set_ylabel("temperature [°C]")
            a.set_title(title, fontsize=10)
            _absolute_time(a)
        if not drawn:
            self.plt.close(fig)
            return
        _legend_below(fig, ax)
        fig.suptitle(self.title("Temperatures", fig_no))
        self.save(fig, f"fig{fig_no}_temperatures.png")


def draw(job: str, data, out: Path, ctx: Context, keep: list | None = None) -> list[str]:
    """Draw the figure ``job`` (one of :data:`JOBS`) into ``out``; returns the file names written (none when
    the run did not record what it shows). ``data``: ``time``, ``phase`` and one array per recorded port, a dict
    or a :class:`~rotorcosim.master.observer.series.SeriesFile`. ``keep``: a list that receives the matplotlib
    figures, left open (to inspect them; the caller closes them), instead of closing them."""
    f = _Figures(ctx, data, out)
    f.keep = keep
    if not f.blocks:
        return []
    ids = ctx.bearings
    if job == "fig09" and ids:    # the first bearing's response (#0 of the paper's engine)
        f.response(ids[0], 9)
    elif job == "fig10":          # every other bearing's (#5)
        for k in ids[1:]:
            f.response(k, 10)
    elif job == "fig11":
        trans = {}
        for k in ids:
            F = f.get(f"damper{k}.F_journal")
            if F is not None and f.F_u > 0:
                trans[k] = np.hypot(F[:, 0], F[:, 1]) / f.F_u
        f.per_bearing(trans, "transmissibility, eq. (23)", "fig11_transmissibility.png",
                      "Transmissibility |F_sfd + F_cs| / F_u", 11, ratio=True)
    elif job == "fig12":
        stress = {k: 1e-6 * S for k in ids if (S := f.get(f"bearing{k}.sigma_max")) is not None}
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


def figures(sc, data, out: Path, F_u: float, speed_rpm: float | None = None, dpi: int | None = None) -> list[str]:
    """Draw every figure into ``out``, in this process, at ``dpi`` (None: :data:`FIGURE_DPI`); returns their
    file names."""
    if data is None or "time" not in data or not len(data["time"]):
        return []
    ctx = context(sc, F_u, speed_rpm, dpi, out)
    return [name for job in JOBS for name in draw(job, data, out, ctx)]
