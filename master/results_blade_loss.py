"""The paper's Table 4 results of a blade-loss run, for bearings #0 and #5, and figures like its Figs. 9-14.

Definitions (read over the last ``cycles`` rotor cycles of the last thermo-mechanical interval, the steady
state the paper tabulates; temperatures at the end of the run):

1. ``whirl_amplitude_mm``: the largest radius sqrt(x^2 + y^2) of the power turbine at the bearing;
2. ``transmissibility``: eq. (23), the largest |F_sfd + F_cs| over the window divided by the blade-loss force
   amplitude F_u;
3. ``max_contact_load_N`` / 4. ``max_contact_stress_MPa``: the largest ball contact load / stress (inner or
   outer race) over the window;
5. ``rub_power_W``, 6. ``drag_power_W``, 7. ``sfd_power_W``: mean power over the window;
8.-11. ``T_inner_race_C``, ``T_ball_C``, ``T_outer_race_C``, ``T_sfd_oil_C``: the final temperatures.

The peaks over the whole run (the blade-loss transient included) are given too, as ``*_peak_*`` keys.
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from .observers import Observer, SteadyWindows

BEARINGS = (0, 5)
RESULT_KEYS = ("whirl_amplitude_mm", "transmissibility", "max_contact_load_N", "max_contact_stress_MPa",
               "rub_power_W", "drag_power_W", "sfd_power_W", "T_inner_race_C", "T_ball_C", "T_outer_race_C",
               "T_sfd_oil_C")
KELVIN = 273.15
#: order of thermal{k}.T_nodes
NODES = ("shaft", "inner_race", "lub_inner", "ball", "lub_outer", "outer_race", "journal", "sfd_oil", "housing")
RUB_CLEARANCE_MM = 0.508  # Table 3, for the orbit figures


def window_signals(sc=None) -> list[str]:
    out = []
    for k in BEARINGS:
        out += [f"rotor.X_brg{k}", f"damper{k}.F_journal", f"bearing{k}.Q_max", f"bearing{k}.sigma_max",
                f"rubring{k}.P_rub", f"bearing{k}.P_drag", f"damper{k}.P_film"]
    return out


class Peaks(Observer):
    """Largest contact load and stress, whirl radius and rub power over the whole run (TM intervals)."""

    def __init__(self):
        self.peak = {k: {"Q": 0.0, "sigma": 0.0, "whirl": 0.0} for k in BEARINGS}

    def interval_start(self, sim, phase, step):
        self.active = phase == "TM"
        comps = sim.system.components
        self._taps = []
        for k in BEARINGS:
            b = comps[f"bearing{k}"]
            q = "Q_max_step" if "Q_max_step" in b.y else "Q_max"
            s = "sigma_max_step" if "sigma_max_step" in b.y else "sigma_max"
            self._taps.append((self.peak[k], b, q, s, comps["rotor"], f"X_brg{k}"))

    def step(self, sim, t):
        if not self.active:
            return
        for p, b, q, s, rotor, xb in self._taps:
            y = b.y
            p["Q"] = max(p["Q"], *y[q])
            p["sigma"] = max(p["sigma"], *y[s])
            x = rotor.y[xb]
            p["whirl"] = max(p["whirl"], math.hypot(x[0], x[1]))


def observers(sc, speed_rpm: float):
    cycles = float(sc.extra.get("results", {}).get("cycles", 5))
    return [SteadyWindows(window_signals(sc), speed_rpm, cycles), Peaks()]


def unbalance_force(sc) -> float:
    ref = sc.extra.get("results", {}).get("unbalance_parameter", "rotor.F_unbalance")
    comp, _, param = ref.partition(".")
    return float(sc.components[comp].parameters.get(param, np.nan))


def extract(sc, sim, obs, report) -> dict:
    windows, peaks = obs
    if not windows.windows:
        return {"bearings": {}, "note": "no thermo-mechanical interval completed: no results"}
    w = windows.windows[-1]
    F_u = unbalance_force(sc)
    out = {}
    for k in BEARINGS:
        X = w[f"rotor.X_brg{k}"]
        F = w[f"damper{k}.F_journal"]
        T = sim.value(f"thermal{k}.T_nodes")
        r = {
            "whirl_amplitude_mm": 1e3 * float(np.max(np.hypot(X[:, 0], X[:, 1]))),
            "transmissibility": float(np.max(np.hypot(F[:, 0], F[:, 1]))) / F_u if F_u > 0 else None,
            "max_contact_load_N": float(np.max(w[f"bearing{k}.Q_max"])),
            "max_contact_stress_MPa": 1e-6 * float(np.max(w[f"bearing{k}.sigma_max"])),
            "rub_power_W": float(np.mean(w[f"rubring{k}.P_rub"])),
            "drag_power_W": float(np.mean(w[f"bearing{k}.P_drag"])),
            "sfd_power_W": float(np.mean(w[f"damper{k}.P_film"])),
            "T_inner_race_C": float(T[NODES.index("inner_race")]) - KELVIN,
            "T_ball_C": float(T[NODES.index("ball")]) - KELVIN,
            "T_outer_race_C": float(T[NODES.index("outer_race")]) - KELVIN,
            "T_sfd_oil_C": float(T[NODES.index("sfd_oil")]) - KELVIN,
            "max_contact_load_peak_N": peaks.peak[k]["Q"],
            "max_contact_stress_peak_MPa": 1e-6 * peaks.peak[k]["sigma"],
            "whirl_amplitude_peak_mm": 1e3 * peaks.peak[k]["whirl"],
        }
        out[str(k)] = r
    return {"unbalance_N": F_u, "window": {"t_start": float(w["t"][0]), "t_end": float(w["t"][-1])},
            "bearings": out}


# -- figures ------------------------------------------------------------------------------------------
def _tm_blocks(t, phase):
    """(start, end) index pairs of the consecutive thermo-mechanical samples."""
    tm = phase == 0
    edges = np.flatnonzero(np.diff(np.r_[0, tm.astype(int), 0]))
    return list(zip(edges[::2], edges[1::2]))


def figures(sc, data: dict, out: Path) -> list[str]:
    """PNG figures like the paper's Figs. 9-14 from the recorded time series (``data``: ``time``, ``phase`` and
    one array per recorded port, as :meth:`Recorder.data` gives them); returns their file names."""
    if data is None or "time" not in data or not len(data["time"]):
        return []
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    F_u = unbalance_force(sc)
    names = []
    f = data
    if True:
        t = f["time"][:]
        phase = f["phase"][:]
        blocks = _tm_blocks(t, phase)
        if not blocks:
            return []
        first, last = blocks[0], blocks[-1]
        get = lambda ref: f[ref][:] if ref in f else None  # noqa: E731

        for k, fig_no in ((0, 9), (5, 10)):
            X = get(f"rotor.X_brg{k}")
            if X is None:
                continue
            fig, ax = plt.subplots(1, 3, figsize=(15, 4.2))
            for a, (i0, i1), title in ((ax[0], first, "(a) transient"), (ax[1], last, "(b) steady state")):
                a.plot(t[i0:i1], 1e3 * X[i0:i1, 0], "-", lw=0.8, label="x")
                a.plot(t[i0:i1], 1e3 * X[i0:i1, 1], ":", lw=0.8, label="y")
                a.set_xlabel("time [s]"); a.set_ylabel("displacement [mm]"); a.set_title(title); a.legend()
            i0, i1 = last
            n = max(2, int((i1 - i0) * 0.5))
            ax[2].plot(1e3 * X[i1 - n:i1, 0], 1e3 * X[i1 - n:i1, 1], lw=0.8)
            th = np.linspace(0, 2 * np.pi, 200)
            ax[2].plot(RUB_CLEARANCE_MM * np.cos(th), RUB_CLEARANCE_MM * np.sin(th), "k:", label="rub ring clearance")
            ax[2].set_aspect("equal"); ax[2].set_xlabel("x [mm]"); ax[2].set_ylabel("y [mm]")
            ax[2].set_title("(c) orbit"); ax[2].legend(loc="upper right", fontsize=8)
            fig.suptitle(f"Power turbine at bearing #{k}, F_u = {F_u:g} N (paper Fig. {fig_no})")
            fig.tight_layout()
            name = f"fig{fig_no:02d}_response_bearing{k}.png"
            fig.savefig(out / name, dpi=110); plt.close(fig); names.append(name)

        fig, ax = plt.subplots(2, 2, figsize=(12, 7))
        for row, k in enumerate(BEARINGS):
            F = get(f"damper{k}.F_journal")
            if F is None:
                continue
            tr = np.hypot(F[:, 0], F[:, 1]) / F_u
            for col, (i0, i1), title in ((0, first, "transient"), (1, last, "steady state")):
                ax[row, col].plot(t[i0:i1], tr[i0:i1], lw=0.8)
                ax[row, col].set_title(f"bearing #{k}: {title}"); ax[row, col].set_xlabel("time [s]")
                ax[row, col].set_ylabel("transmissibility, eq. (23)")
        fig.suptitle("Transmissibility |F_sfd + F_cs| / F_u (paper Fig. 11)"); fig.tight_layout()
        fig.savefig(out / "fig11_transmissibility.png", dpi=110); plt.close(fig); names.append("fig11_transmissibility.png")

        fig, ax = plt.subplots(2, 2, figsize=(12, 7))
        for row, k in enumerate(BEARINGS):
            S = get(f"bearing{k}.sigma_max")
            if S is None:
                continue
            s = 1e-6 * S[:, 1]  # outer race / ball, as the paper's Fig. 12
            for col, (i0, i1), title in ((0, first, "transient"), (1, last, "steady state")):
                ax[row, col].plot(t[i0:i1], s[i0:i1], lw=0.8)
                ax[row, col].axhline(3200, color="r", ls=":", lw=0.8)
                ax[row, col].set_title(f"bearing #{k}: {title}"); ax[row, col].set_xlabel("time [s]")
                ax[row, col].set_ylabel("max contact stress, outer race [MPa]")
        fig.suptitle("Maximum ball / outer race contact stress (paper Fig. 12; dotted: 3200 MPa)"); fig.tight_layout()
        fig.savefig(out / "fig12_contact_stress.png", dpi=110); plt.close(fig); names.append("fig12_contact_stress.png")

        for fig_no, pair in ((13, (("inner_race", "(a) inner race"), ("ball", "(b) ball"))),
                             (14, (("outer_race", "(a) outer race"), ("sfd_oil", "(b) squeeze film damper oil")))):
            fig, ax = plt.subplots(1, 2, figsize=(12, 4.2))
            for a, (node, title) in zip(ax, pair):
                for k, style in ((0, "-"), (5, ":")):
                    T = get(f"thermal{k}.T_nodes")
                    if T is not None:
                        a.plot(t, T[:, NODES.index(node)] - KELVIN, style, label=f"bearing #{k}")
                a.set_xlabel("time [s]"); a.set_ylabel("temperature [C]"); a.set_title(title); a.legend()
            fig.suptitle(f"Temperatures (paper Fig. {fig_no})"); fig.tight_layout()
            name = f"fig{fig_no}_temperatures.png"
            fig.savefig(out / name, dpi=110); plt.close(fig); names.append(name)
    return names
