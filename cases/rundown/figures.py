"""Figures of a rundown, from the recorded time series (``data``: ``time``, ``phase`` and one array per port):

* ``rundown_speed.png``: each spool's speed against time, the held-phase (thermal-only) intervals shaded: (a) from
  the start to a minute after the last fuel cut, (b) the whole run in minutes;
* ``rundown_response.png``: the whirl and the transmitted force (film + centering spring) at each co-simulated
  bearing (by its id) against the first spool's speed through the rundown (the coupled samples; after a held
  interval past the restart's transient: :func:`settled`), the critical speeds
  dashed (the scenario's ``[results] critical_speeds_rpm``, else the engine's: modes.marked_critical_speeds) and the
  crossings' resonance peaks (results.resonance_peaks) marked (a test rotor: its disk's whirl only);
* ``rundown_campbell.png``: the Campbell diagram of the linear engine (components/rotor/critical.py; a test
  rotor: its critical speeds as constant frequencies) with the run's 1x trajectory and each crossing's resonance peak;
* ``rundown_temperatures.png``: the bearing temperatures over the whole run (when recorded), a panel per bearing;
* ``rundown_load_spectra.png`` (a scenario that names ``[results] fatigue_loads`` and records them): the load
  spectrum of each counted load element over the whole run, the cumulative exceedance (the cycles whose range reaches a value,
  log scale) against the range, the held intervals counted from the hold's window (cases/rundown/fatigue.py).

The spools are named as the engine file names them (``[spool.NAME] name``: "power turbine", "gas generator" for
the paper's engine; cases/blade_loss/engine_names.py), the bearings by their ids.
"""
from __future__ import annotations

import math
from pathlib import Path
from typing import NamedTuple

import numpy as np

from rotorcosim.cases.blade_loss.engine_names import spool_name
from rotorcosim.cases.blade_loss.results import KELVIN, NODES, bearing_ids
from rotorcosim.cases.interface import figures as interface_figures
from rotorcosim.master.observer.series import events_of
from rotorcosim.master.run.outputs import check_dpi

from .modes import marked_critical_speeds
from .results import restart_revolutions

RPM = 30.0 / math.pi
#: the Campbell diagram labels its resonance peaks' speeds up to this many peaks (more: marks only)
MAX_PEAK_LABELS = 12
#: the windmilling: from this long after the last fuel cut [s]
WINDMILL_AFTER_CUT_S = 60.0
#: coupled samples per speed bin of the response figure
SPEED_BIN_RPM = 25.0


def _plt():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def _get(data, ref):
    try:
        return np.asarray(data[ref])
    except KeyError:
        return None


def _held_spans(t, phase):
    """(start, end) of each run of held-phase samples (phase code 1)."""
    held = np.asarray(phase) == 1
    if not held.any():
        return []
    d = np.diff(np.concatenate([[0], held.astype(int), [0]]))
    starts, ends = np.flatnonzero(d == 1), np.flatnonzero(d == -1) - 1
    return [(t[max(s - 1, 0)], t[e]) for s, e in zip(starts, ends)]


def _shade(ax, spans, scale=1.0, label=True):
    for i, (a, b) in enumerate(spans):
        ax.axvspan(a * scale, b * scale, color="0.85", lw=0, zorder=0,
                   label="thermal-only (held) intervals" if label and i == 0 else None)


class _Out(NamedTuple):
    """Where the figures go, at which resolution."""
    folder: Path
    dpi: int


def _save(fig, out: _Out, name, rect=(0.0, 0.0, 1.0, 1.0)):
    fig.tight_layout(rect=rect)
    fig.savefig(out.folder / name, dpi=out.dpi)
    _plt().close(fig)
    return name


def _spools(sc):
    r = sc.extra.get("results", {})
    return list(r.get("spools") or [n for n, c in sc.components.items() if c.implementation == "spool.speed"])


def _label(sc, component: str) -> str:
    """A spool component's legend label: the engine's name of its spool, with the component's name."""
    name = spool_name(sc, component)
    return name if name == component else f"{name} ({component})"


def _locations(sc, data):
    """Legend label -> (whirl signal, transmitted-force signal) of each co-simulated bearing recorded; a test
    rotor without bearings: its disk's whirl."""
    out = {}
    for k in bearing_ids(sc.components):
        if _get(data, f"damper{k}.F_journal") is not None and _get(data, f"rotor.X_brg{k}") is not None:
            out[f"bearing #{k}"] = (f"rotor.X_brg{k}", f"damper{k}.F_journal")
    return out or {"disk": ("rotor.X_brg0", None)}


def figures(sc, data, out, dpi: int | None = None) -> list[str]:
    """Draw the figures (module docstring) into the folder ``out`` at ``dpi`` (None: the default,
    :data:`~rotorcosim.master.run.outputs.FIGURE_DPI`); returns the file names."""
    out = _Out(Path(out), check_dpi(dpi))
    t = _get(data, "time")
    if t is None or not len(t):
        return []
    phase = _get(data, "phase")
    spools = [s for s in _spools(sc) if _get(data, f"{s}.Omega") is not None]
    if not spools:
        return []
    names = [_speed(sc, data, t, phase, spools, out, events_of(data))]
    w = _get(data, f"{spools[0]}.Omega").reshape(len(t), -1)[:, 0] * RPM
    crit = marked_critical_speeds(sc, spools[0], float(np.nanmax(w)))
    coupled = phase == 0 if phase is not None else np.ones(len(t), bool)
    # as the response track of the summary's crossings leaves them out: a restart's first revolutions
    shown = settled(t, w, phase, restart_revolutions(sc)) if phase is not None else coupled
    locs = _locations(sc, data)
    peaks = _peaks(data, locs, w, shown)
    first = spool_name(sc, spools[0])
    names.append(_response(data, locs, w, shown, crit, peaks, out, first))
    names.append(_campbell(sc, w, crit, peaks, out, first, windmilling_range(sc, t, w, spools)))
    ids = [k for k in bearing_ids(sc.components) if _get(data, f"thermal{k}.T_nodes") is not None]
    if ids:
        names.append(_temperatures(data, t, phase, out, ids))
    if sc.extra.get("results", {}).get("fatigue_loads"):
        spectra = _spectra(sc, data, out)
        if spectra is not None:
            names.append(spectra)
    # an engine on an airframe: the interface loads and the response points' vibration
    return names + interface_figures.figures(sc, data, out.folder, out.dpi, spools[0])


def _spectra(sc, data, out):
    from rotorcosim.master.observer.fatigue import spectrum

    from .fatigue import recorded_counts

    plt = _plt()
    counts = recorded_counts(data, sc)
    if not counts:
        return None
    fig, ax = plt.subplots(figsize=(8, 5))
    for key, c in counts.items():
        sp = spectrum(c)
        if sp.exceed_n.size:
            ax.step(sp.exceed_n, sp.exceed_S / 1e3, where="post", label=key)
    ax.set_xscale("log")
    ax.set_xlabel("cycles whose range reaches the value (cumulative exceedance)")
    ax.set_ylabel("load range [kN]")
    ax.set_title("load spectra over the run (rainflow; held intervals from the hold's window)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    return _save(fig, out, "rundown_load_spectra.png")


def _speed(sc, data, t, phase, spools, out, events):
    plt = _plt()
    cuts = [float(sc.components[s].parameters.get("t_fuel_cut", -1.0)) for s in spools]
    cuts = [c for c in cuts if c >= 0.0]
    t_zoom = min(t[-1], (max(cuts) if cuts else 0.0) + 60.0)
    spans = _held_spans(t, phase) if phase is not None else []
    long_run = t[-1] > 2.0 * t_zoom
    fig, axes = plt.subplots(1, 2 if long_run else 1, figsize=(11 if long_run else 7, 4), squeeze=False)
    panels = [(axes[0, 0], 1.0, "time [s]", t_zoom, "(a) release, fuel cut, rundown")]
    if long_run:
        panels.append((axes[0, 1], 1.0 / 60.0, "time [min]", t[-1], "(b) the whole run"))
    for ax, scale, xlabel, t_end, title in panels:
        _shade(ax, spans, scale)
        for s in spools:
            ax.plot(t * scale, _get(data, f"{s}.Omega").reshape(len(t), -1)[:, 0] * RPM, lw=1.2, label=_label(sc, s))
        for c in cuts:
            ax.axvline(c * scale, color="tab:red", ls=":", lw=1)
        for e in events:
            ax.axvline(e["t_s"] * scale, color="k", ls="--", lw=0.8)
            ax.annotate(f"{e['component']} {e['kind']}", (e["t_s"] * scale, 0.98), xycoords=("data", "axes fraction"),
                        fontsize=7, rotation=90, va="top", ha="right")
        ax.set_xlim(0, t_end * scale)
        ax.set_ylim(bottom=0)
        ax.set_xlabel(xlabel)
        ax.set_ylabel("speed [rev/min]")
        ax.set_title(title, fontsize=9)
        ax.grid(alpha=0.3)
    axes[0, 0].legend(fontsize=8, loc="lower left")
    fig.suptitle(f"{sc.name}: spool speeds (dotted: fuel cut" + ("; dashed: events" if events else "") + ")",
                 fontsize=10)
    return _save(fig, out, "rundown_speed.png")


def _binned(w, y, sel):
    """The largest y per speed bin of the selected samples: (bin centre speed, max)."""
    if not sel.any():
        return np.array([]), np.array([])
    b = np.floor(w[sel] / SPEED_BIN_RPM).astype(np.int64)
    order = np.argsort(b, kind="stable")
    b, ys = b[order], y[sel][order]
    starts = np.concatenate([[0], np.flatnonzero(np.diff(b)) + 1])
    return (b[starts] + 0.5) * SPEED_BIN_RPM, np.maximum.reduceat(ys, starts)


def settled(t, w, phase, skip: float) -> np.ndarray:
    """The samples a response curve shows (``w`` the speed [rev/min] at times ``t`` [s]; ``phase``: 0 coupled,
    1 held): every coupled sample, less the first ``skip`` revolutions of a coupled stretch that follows a held
    interval (of a stretch that ends before, all but its last revolution), as results.RundownTrack. After a TM
    restart the rotor starts from the orbit it was frozen on at a higher speed and rings down to the new one
    over a few revolutions; drawn per speed, that transient stood as a step at every restart of the
    windmilling."""
    phase = np.asarray(phase)
    keep = phase == 0
    d = np.diff(np.concatenate([[0], keep.astype(np.int8), [0]]))
    for s, e in zip(np.flatnonzero(d == 1), np.flatnonzero(d == -1)):
        if s == 0 or phase[s - 1] != 1:
            continue
        # revolutions from the stretch's start to each sample (trapezoids of the speed)
        rev = np.concatenate([[0.0], np.cumsum(np.diff(t[s:e]) * 0.5 * (np.abs(w[s:e - 1]) + np.abs(w[s + 1:e])))
                              / 60.0])
        keep[s:e] = rev >= skip if rev[-1] >= skip else rev > rev[-1] - 1.0
    return keep


def _radius(a, n):
    a = a.reshape(n, -1)
    return np.hypot(a[:, 0], a[:, 1])


def _peaks(data, locs, w, shown):
    """(speed, whirl) of every resonance peak of the whirl at each location over the ``shown`` samples (coupled,
    a restart's first revolutions left out: :func:`settled`): the peaks the summary's crossings are labelled from
    (results.resonance_peaks), with no window around a critical speed deciding which are drawn."""
    from .results import resonance_peaks

    sel = np.flatnonzero(shown)
    out = []
    for xref, _ in locs.values():
        r = _radius(_get(data, xref), len(w))
        out += [(w[sel][p.index], r[sel][p.index]) for p in resonance_peaks(w[sel], r[sel])]
    return out


def _response(data, locs, w, shown, crit, peaks, out, spool):
    plt = _plt()
    forces = any(f is not None for _, f in locs.values())
    fig, axes = plt.subplots(2 if forces else 1, 1, figsize=(8, 6.5 if forces else 3.8), sharex=True, squeeze=False)
    n = len(w)
    for name, (xref, fref) in locs.items():
        s, y = _binned(w, _radius(_get(data, xref), n) * 1e3, shown)
        axes[0, 0].plot(s, y, lw=1.2, label=f"{name}")
        if fref is not None:
            s, y = _binned(w, _radius(_get(data, fref), n), shown)
            axes[1, 0].plot(s, y, lw=1.2, label=f"{name}")
    for i, (s_pk, r_pk) in enumerate(peaks):
        axes[0, 0].plot(s_pk, r_pk * 1e3, "x", color="tab:red", ms=8, mew=2,
                        label="resonance peaks (every location)" if i == 0 else None)
    axes[0, 0].set_ylabel("whirl (largest radius) [mm]")
    if forces:
        axes[1, 0].set_ylabel("transmitted force [N]")
    for ax in axes[:, 0]:
        for c in crit:
            ax.axvline(c, color="tab:red", ls="--", lw=0.8)
        ax.grid(alpha=0.3)
        ax.set_ylim(bottom=0)
    axes[-1, 0].set_xlabel(f"{spool} speed [rev/min] (dashed: undamped critical speeds)")
    axes[0, 0].set_title("response through the rundown: largest value per 25 rev/min of speed", fontsize=9)
    # one legend below the panels: inside, a fixed corner covered the peak of a run that crosses a low critical
    # speed at its largest whirl (a broken fuse's 5 600 rev/min)
    handles, labels = axes[0, 0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=len(labels), fontsize=8, frameon=False)
    return _save(fig, out, "rundown_response.png", rect=(0.0, 0.05, 1.0, 1.0))


def windmilling_range(sc, t, w, spools) -> tuple[float, float] | None:
    """The first spool's speeds [rev/min] from a minute after the last fuel cut on (the rundown is over by then:
    the speed figure's zoom), the windmilling; None when the run has no fuel cut or ends before."""
    cuts = [float(sc.components[s].parameters.get("t_fuel_cut", -1.0)) for s in spools]
    cuts = [c for c in cuts if c >= 0.0]
    if not cuts:
        return None
    sel = (t >= max(cuts) + WINDMILL_AFTER_CUT_S) & np.isfinite(w)
    return (float(w[sel].min()), float(w[sel].max())) if sel.any() else None


def _campbell(sc, w, crit, peaks, out, spool, windmill=None):
    plt = _plt()
    top = 1.1 * float(np.nanmax(w))
    fig, ax = plt.subplots(figsize=(10, 5))
    rpm = np.linspace(0.0, top, 41)
    drawn = False
    if "rotor" in sc.components:
        try:
            from rotorcosim.cases.blade_loss import linear_engine
            from rotorcosim.components.airframe.installed import installed_model
            from rotorcosim.components.rotor import critical

            # the run's own engine ("" for a rotor component without one: the shipped engine), on its airframe
            # when it has one
            m = installed_model(sc.components["rotor"].parameters.get("model_file") or "")
            extra = m.info.get("airframe_modes", 0)
            f, kind = critical.campbell(m, rpm, linear_engine.supports(sc, data=m.data), n_modes=min(80 + extra, m.n),
                                        n_show=24 + extra)
            styles = ((1, "tab:blue", "forward whirl"), (-1, "tab:orange", "backward whirl"))
            if extra:
                styles += ((0, "0.75", "the airframe's and the casing's modes (no rotor whirl)"),)
            for code, colour, label in styles:
                sel = kind == code
                ax.scatter(np.broadcast_to(rpm[:, None], f.shape)[sel], f[sel], s=5, c=colour, label=label)
            drawn = True
        except Exception:  # the figure still shows the trajectory and the crossings
            drawn = False
    if not drawn:
        for c in crit:
            ax.axhline(c / 60.0, color="tab:blue", lw=1)
    ax.plot([np.nanmin(w), np.nanmax(w)], [np.nanmin(w) / 60.0, np.nanmax(w) / 60.0], color="k", lw=2.5,
            alpha=0.6, label=f"the run's trajectory (1x {spool})")
    if windmill is not None:
        ax.axvspan(windmill[0], windmill[1], color="tab:cyan", alpha=0.3, lw=0,
                   label=f"windmilling: {windmill[0]:.0f}-{windmill[1]:.0f} rev/min")
    for c in crit:
        ax.plot(c, c / 60.0, "o", mfc="none", mec="tab:red", ms=9)
    labelled = len(peaks) <= MAX_PEAK_LABELS
    for i, s in enumerate(sorted(s for s, _ in peaks)):
        ax.plot(s, s / 60.0, "x", color="tab:red", ms=9, mew=2)
        if not labelled:      # an engine on an airframe: a peak per airframe mode; their speeds are the summary's
            continue
        # above-left of the mark: the trajectory runs up-right from it, the mode lines run flat beside it;
        # neighbouring peaks' labels alternate below-right so that two peaks of one crossing stay readable
        off, ha = ((-8, 6), "right") if i % 2 == 0 else ((8, -12), "left")
        ax.annotate(f"peak {s:.0f}", (s, s / 60.0), textcoords="offset points", xytext=off, ha=ha,
                    fontsize=8, color="tab:red")
    ax.set_xlim(0, top)
    ax.set_ylim(0, 1.3 * top / 60.0)
    ax.set_xlabel(f"{spool} speed [rev/min]")
    ax.set_ylabel("whirl frequency [Hz]")
    ax.set_title("Campbell diagram (o: critical speeds, x: the resonance peaks of the run's whirl, the crossings)",
                 fontsize=9)
    ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0))   # outside: mode lines fill the axes
    ax.grid(alpha=0.3)
    return _save(fig, out, "rundown_campbell.png")


def _temperatures(data, t, phase, out, ids):
    plt = _plt()
    fig, axes = plt.subplots(1, len(ids), figsize=(5.5 * max(len(ids), 2), 4.4), sharey=True, squeeze=False)
    axes = axes[0]
    spans = _held_spans(t, phase) if phase is not None else []
    for i, (ax, k) in enumerate(zip(axes, ids)):
        T = _get(data, f"thermal{k}.T_nodes")
        if T is None:
            continue
        _shade(ax, spans, 1.0 / 60.0, label=i == 0)
        for node in ("inner_race", "ball", "outer_race", "sfd_oil"):
            ax.plot(t / 60.0, T[:, NODES.index(node)] - KELVIN, lw=1.2, label=node.replace("_", " "))
        ax.set_title(f"bearing #{k}", fontsize=9)
        ax.set_xlabel("time [min]")
        ax.grid(alpha=0.3)
    axes[0].set_ylabel("temperature [deg C]")
    # below the panels, never over a curve (and no search of the best place over every point of hours of data)
    handles, labels = axes[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=len(labels), fontsize=8, frameon=False)
    return _save(fig, out, "rundown_temperatures.png", rect=(0.0, 0.07, 1.0, 1.0))
