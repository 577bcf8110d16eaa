"""The paper's Table 4 results of a blade-loss run, for bearings #0 and #5, and figures like its Figs. 9-14.

Definitions (read over the last ``cycles`` rotor cycles of the last thermo-mechanical interval, the steady
state the paper tabulates; temperatures at the end of the run):

1. ``whirl_amplitude_mm``: the largest radius sqrt(x^2 + y^2) of the power turbine at the bearing;
2. ``transmissibility``: eq. (23), the largest |F_sfd + F_cs| over the window divided by the blade-loss force
   amplitude F_u;
3. ``max_contact_load_N``: the largest ball contact load (inner or outer race) over the window;
4. ``max_contact_stress_MPa``: the largest ball contact stress (eq. 10) of the INNER race over the window, in
   the summary and in Fig. 12 alike. The paper's text says its Fig. 12 shows the outer-race
   stress, but its Table 5 load/stress pairs follow the inner-race Hertz law (248 Q^(1/3) MPa at #0, 235 at #5,
   f_i = 0.53; tests/components/test_bearing_hertz.py), so the inner race is the contact its stresses describe,
   and the one whose stress reaches the 3200 MPa of its damage criterion under the blade-loss load. The outer
   race's is reported beside it as ``max_contact_stress_outer_MPa``: here the outer contact also carries the
   ball's centrifugal force (52 N at #0, 98 N at #5 at 16 000 rev/min, eq. 4), so at light loads (bearing #5)
   the outer-race stress is the larger one (measured: #5's inner-race stress is 0.5-0.6 of the paper's below
   rub, its outer-race stress within 10 %; the paper's #5 load, 101-169 N, is the centrifugally loaded
   contact's);
5. ``rub_power_W``, 6. ``drag_power_W``, 7. ``sfd_power_W``: mean power over the window;
8.-11. ``T_inner_race_C``, ``T_ball_C``, ``T_outer_race_C``, ``T_sfd_oil_C``: the final temperatures.

The peaks over the whole run (the blade-loss transient included) are given too, as ``*_peak_*`` keys.
"""
from __future__ import annotations

import importlib
import math
import re
from pathlib import Path

import numpy as np

from rotorcosim.components.contract import COUPLED
from rotorcosim.master import case
from rotorcosim.master.manipulator.error_estimate import RISE_FLOOR_K
from rotorcosim.master.observer import synchronous
from rotorcosim.master.observer.observer import Observer, sampled_rows
from rotorcosim.master.observer.steady_windows import SteadyWindows
from rotorcosim.master.scenario.cycle import cycle_of

from . import thermal_geometry

#: the paper's bearings; a scenario's own are :func:`bearing_ids`
BEARINGS = (0, 5)
#: columns of the bearing's [inner, outer] contact outputs (Q_max, sigma_max): the reported stress is the inner race's
INNER, OUTER = 0, 1
RESULT_KEYS = ("whirl_amplitude_mm", "transmissibility", "max_contact_load_N", "max_contact_stress_MPa",
               "rub_power_W", "drag_power_W", "sfd_power_W", "T_inner_race_C", "T_ball_C", "T_outer_race_C",
               "T_sfd_oil_C")
#: every key of a bearing's entry in ``bearings``: the paper's results, the outer race's stress, the whirl by its
#: reference, the peaks and the first times (:func:`result_paths`; held equal to what :func:`extract` reports by
#: tests/cases/test_result_paths.py)
BEARING_KEYS = (*RESULT_KEYS, "max_contact_stress_outer_MPa", "max_contact_load_peak_N",
                "max_contact_stress_peak_MPa", "whirl_amplitude_peak_mm", "whirl_amplitude_absolute_mm",
                "whirl_amplitude_relative_mm", "whirl_amplitude_absolute_peak_mm", "whirl_amplitude_relative_peak_mm",
                "max_contact_stress_outer_peak_MPa", "transmitted_force_peak_N", "rub_power_peak_W",
                "rub_first_time_s", "plastic_flow_limit_MPa", "plastic_flow_first_time_s")
#: the steady windows the results need: the last (the results) and the one before it (their error estimate)
WINDOWS_KEPT = 2
#: rotor cycles of a steady window, the last of a thermo-mechanical interval (``[results] cycles``)
WINDOW_CYCLES = 5.0
KELVIN = 273.15
#: the paper's damage criterion of a ball/race contact: incipient plastic flow at 3200 MPa (its ref. [13]; the
#: line of its Fig. 12). Not the end of the model (the bearing's own envelope is ISO 76's 4200 MPa,
#: components/bearing/component.py): a run above it is reported (``plastic_flow_first_time_s``, ``events``)
PLASTIC_FLOW_MPA = 3200.0
PLASTIC_FLOW_PA = PLASTIC_FLOW_MPA * 1e6
#: the module that draws the figures (a figure pool's workers import it while the run goes)
FIGURES_MODULE = "rotorcosim.cases.blade_loss.figures"
#: order of thermal{k}.T_nodes
NODES = ("shaft", "inner_race", "lub_inner", "ball", "lub_outer", "outer_race", "journal", "sfd_oil", "housing")


def bearing_ids(names) -> tuple[str, ...]:
    """The ids of the co-simulated bearings among component names ``names`` (a scenario's components: every
    ``bearing<ID>``, in their order; the paper's: "0", "5"); an id's damper, rub ring and thermal network are
    ``damper<ID>``, ``rubring<ID>`` (optional), ``thermal<ID>``."""
    return tuple(n[len("bearing"):] for n in names if re.match(r"^bearing[A-Za-z0-9_]+$", n))


def housing_signal(sc, k) -> str | None:
    """``rotor.X_housing<k>``, the housing's displacement at bearing ``k``, where the scenario connects it (the
    rotor offers it for every attached bearing); None for a scenario without it (then no relative whirl)."""
    ref = f"rotor.X_housing{k}"
    if sc is None or any(c.src == ref for c in getattr(sc, "connections", ())):
        return ref
    return None


def window_signals(sc=None) -> list[str]:
    """The outputs the steady windows keep for each bearing of ``sc`` (the paper's without one): whirl, film
    force, contact load and stress, rub (where the bearing has a rub ring), drag and film powers, the housing's
    displacement (the whirl relative to it)."""
    ids = bearing_ids(sc.components) if sc is not None else tuple(map(str, BEARINGS))
    out = []
    for k in ids:
        out += [f"rotor.X_brg{k}", f"damper{k}.F_journal", f"bearing{k}.Q_max", f"bearing{k}.sigma_max"]
        if sc is None or f"rubring{k}" in sc.components:
            out.append(f"rubring{k}.P_rub")
        out += [f"bearing{k}.P_drag", f"damper{k}.P_film"]
        housing = housing_signal(sc, k)
        if housing is not None:
            out.append(housing)
    return out


class Peaks(Observer):
    """The largest values over the whole run (every step of the coupled intervals; the held ones change no
    mechanical output), per bearing id: contact load (either race), contact stress of the inner and of the outer
    race, whirl radius of the rotor at the bearing (absolute, and relative to its housing where the housing's
    displacement is connected), transmitted force |F_journal| (film + centering spring) and rub power; and the
    first time the rub power was above zero and the first time a contact stress (either race) was above
    ``plastic_flow_pa``. Nothing is kept but these numbers: a run that records to file holds no series for
    them."""

    def __init__(self, ids=tuple(map(str, BEARINGS)), housing=None, plastic_flow_pa: float = PLASTIC_FLOW_PA):
        self.ids = tuple(ids)
        #: id -> the housing displacement's port name on the rotor (None: no relative whirl)
        self.housing = dict(housing or {})
        self.plastic_flow_pa = float(plastic_flow_pa)
        self.peak = {k: {"Q": 0.0, "sigma": 0.0, "whirl": 0.0, "sigma_outer": 0.0, "whirl_relative": None,
                         "force": 0.0, "rub": None, "t_rub": None, "t_plastic": None} for k in self.ids}

    def interval_start(self, sim, phase, step):
        self.active = phase == COUPLED
        comps = sim.system.components
        self._taps = []
        for k in self.ids:
            b = comps[f"bearing{k}"]
            q = "Q_max_step" if "Q_max_step" in b.y else "Q_max"
            s = "sigma_max_step" if "sigma_max_step" in b.y else "sigma_max"
            d, r = comps.get(f"damper{k}"), comps.get(f"rubring{k}")
            h = self.housing.get(k)
            self._taps.append((self.peak[k], b, q, s, comps["rotor"], f"X_brg{k}",
                               h.partition(".")[2] if h else None,
                               d if d is not None and "F_journal" in d.y else None,
                               r if r is not None and "P_rub" in r.y else None))

    def block_signals(self, sim):
        out = []
        for k, (p, b, q, s, rotor, xb, xh, d, r) in zip(self.ids, self._taps):
            out += [f"bearing{k}.{q}", f"bearing{k}.{s}", f"rotor.{xb}"]
            out += [f"rotor.{xh}"] * (xh is not None) + [f"damper{k}.F_journal"] * (d is not None)
            out += [f"rubring{k}.P_rub"] * (r is not None)
        return out

    def step_block(self, sim, ks, ts, data):
        """As step() over the block (the same maxima: max is exact, and hypot row by row)."""
        if not self.active:
            return
        rows = sampled_rows(ks, self.stride)
        if not len(rows):
            return
        t = np.asarray(ts)[rows]
        for k, (p, b, q, s, rotor, xb, xh, d, r) in zip(self.ids, self._taps):
            p["Q"] = max(p["Q"], float(data[f"bearing{k}.{q}"][rows].max()))
            sig = data[f"bearing{k}.{s}"][rows]
            p["sigma"] = max(p["sigma"], float(sig[:, INNER].max()))
            p["sigma_outer"] = max(p["sigma_outer"], float(sig[:, OUTER].max()))
            if p["t_plastic"] is None:
                over = np.flatnonzero(sig.max(axis=1) > self.plastic_flow_pa)
                if len(over):
                    p["t_plastic"] = float(t[over[0]])
            x = data[f"rotor.{xb}"][rows]
            p["whirl"] = max(p["whirl"], float(np.hypot(x[:, 0], x[:, 1]).max()))
            if xh is not None:
                e = x[:, :2] - data[f"rotor.{xh}"][rows][:, :2]
                p["whirl_relative"] = max(p["whirl_relative"] or 0.0, float(np.hypot(e[:, 0], e[:, 1]).max()))
            if d is not None:
                f = data[f"damper{k}.F_journal"][rows]
                p["force"] = max(p["force"], float(np.hypot(f[:, 0], f[:, 1]).max()))
            if r is not None:
                w = data[f"rubring{k}.P_rub"][rows, 0]
                p["rub"] = max(p["rub"] or 0.0, float(w.max()))
                if p["t_rub"] is None:
                    on = np.flatnonzero(w > 0.0)
                    if len(on):
                        p["t_rub"] = float(t[on[0]])

    def step(self, sim, t):
        if not self.active:
            return
        for p, b, q, s, rotor, xb, xh, d, r in self._taps:
            y = b.y
            p["Q"] = max(p["Q"], *y[q])
            p["sigma"] = max(p["sigma"], y[s][INNER])
            p["sigma_outer"] = max(p["sigma_outer"], float(y[s][OUTER]))
            if p["t_plastic"] is None and max(y[s]) > self.plastic_flow_pa:
                p["t_plastic"] = float(t)
            x = rotor.y[xb]
            p["whirl"] = max(p["whirl"], float(np.hypot(x[0], x[1])))
            if xh is not None:
                h = rotor.y[xh]
                p["whirl_relative"] = max(p["whirl_relative"] or 0.0, float(np.hypot(x[0] - h[0], x[1] - h[1])))
            if d is not None:
                f = d.y["F_journal"]
                p["force"] = max(p["force"], float(np.hypot(f[0], f[1])))
            if r is not None:
                w = float(r.y["P_rub"][0])
                p["rub"] = max(p["rub"] or 0.0, w)
                if p["t_rub"] is None and w > 0.0:
                    p["t_rub"] = float(t)


def window_cycles(sc) -> float:
    """The cycles of a steady window: ``[results] cycles`` (:data:`WINDOW_CYCLES` by default)."""
    return float(sc.extra.get("results", {}).get("cycles", WINDOW_CYCLES))


def observers(sc, cycle):
    """The run's observers for the results: the steady windows over the last ``[results] cycles`` cycles of
    ``cycle`` (the scenario's cycle source, master/core/cycle.py) and the peaks."""
    cycles = window_cycles(sc)
    ids = bearing_ids(sc.components)
    housing = {k: h for k in ids if (h := housing_signal(sc, k)) is not None}
    return [SteadyWindows(window_signals(sc), cycle, cycles, keep=WINDOWS_KEPT), Peaks(ids, housing)]


def check(sc, sim) -> None:
    """Before the run: ``[schedule] speed_rpm`` (the cycle of the windows and of the hold) is the speed the
    unbalance turns at, the parameter ``[results] speed_parameter`` names (rad/s; its default comes from
    components/speeds.py). A mismatch would read every steady window over a wrong cycle: a clear error. And each
    thermal network has the geometry of the bearing, damper and rub ring whose heat it takes (.thermal_geometry)."""
    thermal_geometry.check(sc, sim.system)
    ref = sc.extra.get("results", {}).get("speed_parameter")
    if not ref:
        return
    comp, _, param = ref.partition(".")
    c = sim.system.components.get(comp)
    if c is None or param not in c.p:
        raise ValueError(f"[results] speed_parameter {ref!r}: no such component parameter")
    rpm = float(c.p[param]) * 30.0 / math.pi
    speed = sc.schedule.get("speed_rpm")
    if speed is None and sc.schedule.get("cycle") is not None:
        period = cycle_of(sc.schedule).constant
        if period is None:  # a speed signal: the windows follow it
            return
        speed = 60.0 / period
    if speed is None or not math.isclose(float(speed), rpm, rel_tol=1e-9):
        raise ValueError(f"scenario {sc.name!r}: [schedule] speed_rpm = {speed} rev/min but {ref} = "
                         f"{float(c.p[param]):.9g} rad/s ({rpm:.9g} rev/min), the speed the unbalance turns at: "
                         f"give them the same speed")


def apply_unbalance(sc, force: float, settings=()) -> None:
    """Set the blade-loss force of ``sc`` to ``force`` [N] (in place; the case's level, ``--unbalance``):
    :func:`rotorcosim.master.case.apply_level`."""
    case.apply_level(sc, force, settings)


def unbalance_force(sc) -> float:
    """The blade-loss force F_u [N] of ``sc``: the parameter its ``[results] unbalance_parameter`` names (NaN
    when the component does not set it)."""
    ref = sc.extra.get("results", {}).get("unbalance_parameter", "rotor.F_unbalance")
    comp, _, param = ref.partition(".")
    return float(sc.components[comp].parameters.get(param, np.nan))


#: the results read over the steady window (the mechanics): their estimated error shares the hand-backs'
#: (master/manipulator/error_estimate.py, HoldReport.mechanics_fraction)
WINDOW_KEYS = ("whirl_amplitude_mm", "transmissibility", "max_contact_load_N", "max_contact_stress_MPa",
               "max_contact_stress_outer_MPa", "rub_power_W", "drag_power_W", "sfd_power_W")
#: the results read over the steady window as a largest value (the others are means over it): a ringing window's
#: largest value is its ringing's crest, where a mean averages the ringing out
PEAK_KEYS = ("whirl_amplitude_mm", "transmissibility", "max_contact_load_N", "max_contact_stress_MPa",
             "max_contact_stress_outer_MPa")
#: what a user reads for each result that has an estimate (the run's printed estimate names its result so)
LABELS = {"whirl_amplitude_mm": "whirl amplitude", "transmissibility": "transmissibility",
          "max_contact_load_N": "contact load", "max_contact_stress_MPa": "inner-race contact stress",
          "max_contact_stress_outer_MPa": "outer-race contact stress", "rub_power_W": "rub power",
          "drag_power_W": "drag power", "sfd_power_W": "squeeze-film power",
          "T_inner_race_C": "inner-race temperature", "T_ball_C": "ball temperature",
          "T_outer_race_C": "outer-race temperature", "T_sfd_oil_C": "squeeze-film oil temperature"}
#: the powers read over the steady window and the hand-off each one is (its estimate: the hold's
#: ``handoff_errors_end_pct``, where the hold follows it with a law)
POWERS = {"drag_power_W": "bearing{}.P_drag", "sfd_power_W": "damper{}.P_film"}
#: the final temperatures and the thermal network's output each one is
TEMPERATURES = {"T_inner_race_C": "T_inner_race", "T_ball_C": "T_ball", "T_outer_race_C": "T_outer_race",
                "T_sfd_oil_C": "T_sfd_oil"}


def _peak_signals(w, k, F_u) -> dict:
    """The signals of bearing ``k`` whose largest value over the steady window ``w`` is a result (``PEAK_KEYS``),
    sample by sample in the result's unit (None: no transmissibility without a blade-loss force)."""
    X = w[f"rotor.X_brg{k}"]
    F = w[f"damper{k}.F_journal"]
    sigma = w[f"bearing{k}.sigma_max"]
    return {
        "whirl_amplitude_mm": 1e3 * np.hypot(X[:, 0], X[:, 1]),
        "transmissibility": np.hypot(F[:, 0], F[:, 1]) / F_u if F_u > 0 else None,
        "max_contact_load_N": np.max(w[f"bearing{k}.Q_max"], axis=1),
        "max_contact_stress_MPa": 1e-6 * sigma[:, INNER],
        "max_contact_stress_outer_MPa": 1e-6 * sigma[:, OUTER],
    }


def _window_results(w, k, F_u) -> dict:
    """The results of bearing ``k`` read over the steady window ``w`` (SteadyWindows' dict)."""
    peaks = {key: None if y is None else float(np.max(y)) for key, y in _peak_signals(w, k, F_u).items()}
    return {
        **peaks,
        # a bearing without a rub ring: no rub power (null)
        "rub_power_W": float(np.mean(w[f"rubring{k}.P_rub"])) if f"rubring{k}.P_rub" in w else None,
        "drag_power_W": float(np.mean(w[f"bearing{k}.P_drag"])),
        "sfd_power_W": float(np.mean(w[f"damper{k}.P_film"])),
    }


def extract(sc, sim, obs, report) -> dict:
    """The results of a finished run (summary.json's ``unbalance_N``, ``window``, ``bearings`` and
    ``estimated_error``): for each bearing (by id; #0 and #5 for the paper's engine) the paper's Table 4
    quantities over the last steady window (mm, N, MPa, W, degrees C) and the peaks over the run, and the
    staggered scheme's estimated error of each (:func:`estimated_errors`). ``obs``: the :func:`observers` of the
    run; ``sim``, ``report``: the simulation and its report."""
    windows, peaks = obs
    if not windows.windows:
        return {"bearings": {}, "note": "no thermo-mechanical interval completed: no results"}
    w = windows.windows[-1]
    F_u = unbalance_force(sc)
    out = {}
    for k in peaks.ids:
        X = w[f"rotor.X_brg{k}"]
        T = sim.value(f"thermal{k}.T_nodes")
        H = w.get(peaks.housing[k]) if k in peaks.housing else None
        whirl = 1e3 * float(np.max(np.hypot(X[:, 0], X[:, 1])))
        pk = peaks.peak[k]
        r = {
            **_window_results(w, k, F_u),
            "T_inner_race_C": float(T[NODES.index("inner_race")]) - KELVIN,
            "T_ball_C": float(T[NODES.index("ball")]) - KELVIN,
            "T_outer_race_C": float(T[NODES.index("outer_race")]) - KELVIN,
            "T_sfd_oil_C": float(T[NODES.index("sfd_oil")]) - KELVIN,
            "max_contact_load_peak_N": pk["Q"],
            "max_contact_stress_peak_MPa": 1e-6 * pk["sigma"],
            "whirl_amplitude_peak_mm": 1e3 * pk["whirl"],
            # the whirl named by its reference: absolute (the housing's own motion included; the Table 4 value
            # above) and relative to the bearing's housing (the rotor's excursion inside its support)
            "whirl_amplitude_absolute_mm": whirl,
            "whirl_amplitude_relative_mm": (None if H is None else
                                            1e3 * float(np.max(np.hypot(X[:, 0] - H[:, 0], X[:, 1] - H[:, 1])))),
            "whirl_amplitude_absolute_peak_mm": 1e3 * pk["whirl"],
            "whirl_amplitude_relative_peak_mm": None if pk["whirl_relative"] is None else 1e3 * pk["whirl_relative"],
            "max_contact_stress_outer_peak_MPa": 1e-6 * pk["sigma_outer"],
            "transmitted_force_peak_N": pk["force"],
            "rub_power_peak_W": pk["rub"],
            # a rub at any time (the blade-loss transient's included), and a contact stress above the paper's
            # plastic-flow limit at any time: the first time, null for never
            "rub_first_time_s": pk["t_rub"],
            "plastic_flow_limit_MPa": PLASTIC_FLOW_MPA,
            "plastic_flow_first_time_s": pk["t_plastic"],
        }
        out[str(k)] = r
    res = {"unbalance_N": F_u, "window": {"t_start": float(w["t"][0]), "t_end": float(w["t"][-1])},
           "bearings": out, "events": events(out)}
    est = estimated_errors(windows.windows, out, report.hold, F_u, windows.cycles,
                           {k: ripple_periods(sim, k) for k in peaks.ids})
    if est is not None:
        res["estimated_error"] = est
    return res


def events(bearings: dict) -> list[dict]:
    """What happened at some time of the run that its end values do not show, one entry per bearing and kind
    (summary.json ``events``; each is also one ``warning:`` line on stderr): ``"rub"``, the rotor touched its
    rub ring (rub power above zero) but no longer rubs at the end (a transient rub); ``"plastic_flow"``, a ball
    contact stress (either race) above the plastic-flow limit at some time. Keys: ``kind``, ``bearing``,
    ``time_s`` (the first time), ``peak`` and ``unit`` (the run's peak of that quantity), ``limit`` (the
    plastic-flow limit; 0 W for a rub) and ``message``."""
    out = []
    for k, r in bearings.items():
        if r["rub_first_time_s"] is not None and not r["rub_power_W"]:
            out.append({"kind": "rub", "bearing": k, "time_s": r["rub_first_time_s"], "peak": r["rub_power_peak_W"],
                        "limit": 0.0, "unit": "W",
                        "message": f"bearing {k}: the rotor rubbed its rub ring from t = {r['rub_first_time_s']:.6g} s "
                                   f"(peak rub power {r['rub_power_peak_W']:.5g} W), though not at the end of the "
                                   "run (rub_power_W 0)"})
        stress = max(r["max_contact_stress_peak_MPa"], r["max_contact_stress_outer_peak_MPa"])
        if r["plastic_flow_first_time_s"] is not None:
            out.append({"kind": "plastic_flow", "bearing": k, "time_s": r["plastic_flow_first_time_s"],
                        "peak": stress, "limit": PLASTIC_FLOW_MPA, "unit": "MPa",
                        "message": f"bearing {k}: a ball contact stress above the {PLASTIC_FLOW_MPA:.0f} MPa of "
                                   f"incipient plastic flow from t = {r['plastic_flow_first_time_s']:.6g} s (peak "
                                   f"{stress:.5g} MPa)"})
    return out


def ripple_periods(sim, k) -> tuple[float, ...]:
    """The periods [s] of bearing ``k``'s own ripple: its balls passing the inner and the outer race
    (``ball_pass_frequencies`` of the bearing component; none for a bearing that does not report them, whose
    ripple then counts as unsteadiness: an estimate on the safe side)."""
    comp = sim.system.components.get(f"bearing{k}")
    freqs = getattr(comp, "ball_pass_frequencies", None)
    return tuple(1.0 / f for f in freqs() if f > 0.0) if freqs is not None else ()


def unsteadiness(w, k, F_u, cycles: float, ripple=()) -> dict[str, float]:
    """How far the window ``w`` of bearing ``k`` is from a steady state, for each result read over it as a largest
    value (``PEAK_KEYS``): the largest deviation of its signal from its time-synchronous average over the window's
    whole cycles, the bearing's own ball-pass ripple (``ripple``: its periods, :func:`ripple_periods`) left out
    (master/observer/synchronous.py), percent of the result. A settled response repeats each cycle up to that
    ripple (0); what a restart or the release left ringing does not, and the window's largest value stands at
    most that far from the largest value of its repeating part. A slow decay shows only its part that departs
    from the window's mean. Empty for a window of fewer than 2 cycles or samples."""
    t = w["t"]
    if cycles < 2.0 or len(t) < 2 * cycles or not t[-1] > t[0]:
        return {}
    out = {}
    for key, y in _peak_signals(w, k, F_u).items():
        q = None if y is None else float(np.max(y))
        if q:
            out[key] = 100.0 * synchronous.largest_residual(t, y, cycles, ripple) / abs(q)
    return out


def estimated_errors(windows, bearings, hold, F_u, cycles: float = 0.0, ripple=None) -> dict | None:
    """The staggered scheme's estimated error of each Table 4 result [%] (None without a charged thermal-only
    interval; master/manipulator/hold.py and error_estimate.py have the estimator): a temperature's is the hold's estimated error of the
    thermal network's output, percent of its rise above the run's initial temperature (at least the hold's
    RISE_FLOOR_K); a result read over the steady window takes the share in error of the values its bearing's
    thermal network hands back to the mechanics (``mechanics_fraction`` of ``thermal<ID>``: its oil temperature
    and growths) of its own change between the last two thermo-mechanical intervals, percent of its value: the
    mechanics follow those values quasi-statically, so an error that is a share of their move over the held
    interval is that share of the result's move (not estimated where the speed changed between those intervals:
    the hold gives no fraction then); a result read as the window's largest value adds the window's
    :func:`unsteadiness` (``ripple``: bearing id -> the periods of its own ripple, :func:`ripple_periods`).
    ``largest_pct`` and ``largest`` ("bearing.key") are the run's estimate, ``largest_label`` names its result
    for a reader ("bearing #0 drag power")."""
    if hold is None or hold.estimated_error_pct is None:
        return None
    per: dict[str, dict[str, float]] = {}
    for k, r in bearings.items():
        e = {}
        for key, port in TEMPERATURES.items():
            ref = f"thermal{k}.{port}"
            err, rise = hold.output_errors.get(ref), hold.output_rise.get(ref)
            if err is not None and rise is not None:
                e[key] = 100.0 * abs(err[0]) / max(abs(rise[0]), RISE_FLOOR_K)
        f = hold.mechanics_fraction.get(f"thermal{k}")
        if len(windows) >= 2 and f is not None:
            prev = _window_results(windows[-2], k, F_u)
            for key in WINDOW_KEYS:
                q, q0 = r.get(key), prev.get(key)
                if q is not None and q0 is not None and q != 0.0:
                    e[key] = 100.0 * f * abs(q - q0) / abs(q)
        # a power the hold follows with a law: that law's own sensitivity to the erring temperatures and growths
        for key, ref in POWERS.items():
            d = hold.handoff_errors_end_pct.get(ref.format(k))
            if d is not None and r.get(key) is not None:
                e[key] = abs(d)
        # and the last window's own unsteadiness, the transient the mechanics still carry (not where the speed
        # moved: then the results change from cycle to cycle with it)
        if windows and f is not None:
            for key, u in unsteadiness(windows[-1], k, F_u, cycles, (ripple or {}).get(k, ())).items():
                if key in e:
                    e[key] += u
        per[k] = e
    flat = [(v, f"{k}.{key}") for k, e in per.items() for key, v in e.items()]
    if not flat:
        return None
    largest, which = max(flat)
    k, _, key = which.partition(".")
    return {"largest_pct": largest, "largest": which, "largest_label": f"bearing #{k} {LABELS.get(key, key)}",
            "per_result_pct": per}


# -- figures ------------------------------------------------------------------------------------------
def result_paths(sc) -> list[str]:
    """The results :func:`extract` reports for scenario ``sc``, as dotted paths into summary.json (a study's
    SPEC is checked against them before its first run)."""
    return ["unbalance_N", "window.t_start", "window.t_end", "events.",
            *(f"bearings.{k}.{key}" for k in bearing_ids(sc.components) for key in BEARING_KEYS)]


def figures(sc, data, out: Path, pool=None, dpi: int | None = None) -> list[str]:
    """PNG figures like the paper's Figs. 9-14 from the recorded time series (``data``: ``time``, ``phase`` and
    one array per recorded port, as :meth:`Recorder.data` gives them, or the run's
    :class:`~rotorcosim.master.observer.series.SeriesFile`); returns their file names. The drawing is in
    :mod:`rotorcosim.cases.blade_loss.figures`; with a usable :class:`~rotorcosim.master.run.figure_pool.FigurePool`
    and a file, the figures are drawn in its worker processes. ``dpi``: their resolution (None: the default,
    :data:`~rotorcosim.master.run.outputs.FIGURE_DPI`)."""
    from rotorcosim.master.observer.series import SeriesFile

    fb = importlib.import_module(FIGURES_MODULE)

    F_u, speed = unbalance_force(sc), sc.schedule.get("speed_rpm")
    if pool is not None and pool.usable and isinstance(data, SeriesFile) and len(data["time"]):
        return pool.draw(fb, fb.JOBS, data.path, out, fb.context(sc, F_u, speed, dpi, out))
    return fb.figures(sc, data, out, F_u, speed, dpi)
