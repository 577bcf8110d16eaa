"""The crossings of a rundown (cases/rundown/results.py: resonance_peaks, label, crossings, fold) on synthetic
response curves whose peaks are known in closed form or by a dense maximisation of the analytic curve: the
single-dof unbalance response (u/m) r^2 / sqrt((1 - r^2)^2 + (2 zeta r)^2), r = Omega / omega_n, whose peak is at
r = 1 / sqrt(1 - 2 zeta^2) with the amplitude (u/m) / (2 zeta sqrt(1 - zeta^2)) (any vibration textbook, e.g.
Genta, Dynamics of Rotating Systems, sect. 4.3), sampled along a falling speed as RundownTrack.table gives it.
The critical speeds are given (cases/rundown/modes.py's ScenarioModes, or damped ones per film temperature as
EngineModes gives them)."""
from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.optimize import minimize_scalar

from rotorcosim.cases.rundown.modes import ScenarioModes
from rotorcosim.cases.rundown.results import (BIN_S, SPEED_BIN, crossings, fold, resonance_peaks,
                                              _layout)

RPM = 30.0 / math.pi
U_M = 1e-5          # u / m [m]
LOCS = {"disk": {"whirl": "rotor.X_brg0"}}


class Damped:
    """Critical speeds as the linearised engine gives them: undamped, and per location (damped, undamped) pairs,
    here the same at every film temperature unless ``by_temperature`` (C -> pairs per location) says otherwise."""

    def __init__(self, undamped, pairs, by_temperature=None):
        self.undamped = list(undamped)
        self.pairs = pairs
        self.by_temperature = by_temperature or {}
        self.asked = []

    def prepare(self, lo, hi):
        self.range = (lo, hi)

    def damped_near(self, loc, speed_rpm, temps):
        """The (damped, undamped) pair at ``loc`` whose damped speed is nearest to ``speed_rpm`` (in ratio)."""
        self.asked.append(dict(temps))
        t = next(iter(temps.values()), None)
        pairs = self.by_temperature.get(round(t) if t is not None else None, self.pairs).get(loc) or []
        return min(pairs, key=lambda p: abs(math.log(speed_rpm / p[0]))) if pairs else None


def sdof(rpm, wn_rpm, zeta):
    """The single-dof unbalance response [m] at rpm."""
    r = np.asarray(rpm, dtype=float) / wn_rpm
    return U_M * r * r / np.sqrt((1.0 - r * r) ** 2 + (2.0 * zeta * r) ** 2)


def table(rpm, whirl, t_end=1.0):
    """A RundownTrack.table of one spool and one location: t, Omega [rad/s], whirl [m], and the whirl's sample's
    t and Omega."""
    t = np.linspace(0.0, t_end, len(rpm))
    w = np.asarray(rpm) / RPM
    return np.column_stack([t, w, whirl, t, w])


def falling(top=9000.0, bottom=3000.0, n=30_001):
    return np.linspace(top, bottom, n)


def test_single_dof_peak_within_a_bin():
    """The peak of a single-dof curve (6040 rev/min, zeta 0.02) within one speed bin of the analytic peak speed,
    its amplitude within 0.1 % of the analytic one, the time that of the sample at the peak."""
    wn, zeta = 6039.5, 0.02
    w = falling()
    tab = table(w, sdof(w, wn, zeta))
    (c,) = crossings(tab, "spool", ScenarioModes([wn]), LOCS, 1)
    exact = wn / math.sqrt(1.0 - 2.0 * zeta ** 2)
    assert c["peak_found"] is True
    assert abs(math.log(c["peak_speed_rpm"] / exact)) <= math.log1p(SPEED_BIN)
    amp = U_M / (2.0 * zeta * math.sqrt(1.0 - zeta ** 2))
    assert c["bearings"]["disk"]["peak_whirl_mm"] == pytest.approx(amp * 1e3, rel=1e-3)
    j = int(np.argmin(abs(w - c["peak_speed_rpm"])))
    assert c["t_s"] == pytest.approx(tab[j, 0])
    assert c["direction"] == "down"
    lo, hi = c["speed_range_rpm"]
    assert lo < c["peak_speed_rpm"] < hi
    # the half-prominence width of a light-damped peak: about +-sqrt(3) zeta around it
    assert hi / lo - 1.0 == pytest.approx(2.0 * math.sqrt(3.0) * zeta, rel=0.1)


def test_two_peaks_each_to_its_critical_speed():
    """Two modes, damped peaks above their undamped critical speeds as the engine's squeeze-film dampers put them
    (8500 -> ~9100, 10200 -> ~11400 rev/min, docs/explanation/rundown.md): each peak is labelled with the nearest
    damped critical speed, within a bin of the composite curve's maxima found by a bounded scalar maximisation;
    10 200 is nearer to the lower peak than to the upper one, and the lower peak is not given to it."""
    w = falling(16000.0, 4500.0, 60_001)

    def curve(x):
        return sdof(x, 9100.0, 0.08) + 0.9 * sdof(x, 11400.0, 0.06)

    modes = Damped([8500.0, 10200.0], {"disk": [(9100.0, 8500.0), (11400.0, 10200.0)]})
    got = crossings(table(w, curve(w)), "spool_pt", modes, LOCS, 1)
    assert [c["critical_speed_rpm"] for c in got] == [8500.0, 10200.0]
    assert [c["damped_critical_speed_rpm"] for c in got] == [9100.0, 11400.0]
    assert all(c["peak_found"] and c["location"] == "disk" for c in got)
    for c, (a, b) in zip(got, ((8000.0, 10000.0), (10500.0, 13000.0))):
        ref = minimize_scalar(lambda x: -curve(x), bounds=(a, b), method="bounded", options={"xatol": 1e-3}).x
        assert abs(math.log(c["peak_speed_rpm"] / ref)) <= math.log1p(SPEED_BIN), (c["peak_speed_rpm"], ref)
    assert abs(10200.0 - 9100.0) < abs(11400.0 - 10200.0)


def test_each_location_over_its_own_peak():
    """Two locations as the engine's bearings: #0 with damped peaks at ~9 100 and ~11 400 rev/min, #5 with one
    at ~9 950 (the upper mode seen at #5, its damped critical speed there). The crossing of 10 200 takes #5's values
    over #5's own peak (its analytic maximum, though it lies outside #0's peak width), that of 8 500, where #5 has
    no peak, over #0's peak width."""
    w = falling(16000.0, 4500.0, 60_001)
    w0 = sdof(w, 9100.0, 0.03) + 0.9 * sdof(w, 11400.0, 0.03)
    w5 = 0.15 * sdof(w, 9950.0, 0.05)
    t = np.linspace(0.0, 1.0, len(w))
    tab = np.column_stack([t, w / RPM, w0, t, w / RPM, w5, t, w / RPM])
    locs = {"0": {"whirl": "rotor.X_brg0"}, "5": {"whirl": "rotor.X_brg5"}}
    modes = Damped([8500.0, 10200.0], {"0": [(9100.0, 8500.0), (11400.0, 10200.0)], "5": [(9950.0, 10200.0)]})
    lo, hi = crossings(tab, "spool_pt", modes, locs, 1)
    assert lo["location"] == hi["location"] == "0"
    assert not hi["speed_range_rpm"][0] <= 9950.0 <= hi["speed_range_rpm"][1]
    amp5 = 0.15 * U_M / (2.0 * 0.05 * math.sqrt(1.0 - 0.05 ** 2))
    assert hi["bearings"]["5"]["peak_whirl_mm"] == pytest.approx(amp5 * 1e3, rel=1e-3)
    assert hi["bearings"]["5"]["speed_range_rpm"][0] < 9950.0 < hi["bearings"]["5"]["speed_range_rpm"][1]
    assert lo["bearings"]["5"]["speed_range_rpm"] == lo["speed_range_rpm"] == lo["bearings"]["0"]["speed_range_rpm"]
    sel = (w >= lo["speed_range_rpm"][0]) & (w <= lo["speed_range_rpm"][1])
    assert lo["bearings"]["5"]["peak_whirl_mm"] == pytest.approx(w5[sel].max() * 1e3)


def test_a_mode_seen_at_one_location_only():
    """The 14 252 N rundown's shape: one peak at #0 (the lower mode, damped ~9 100 there) and one at #5 (the upper
    mode, damped ~9 950 there) close together: both modes are found, each from the location where it peaks."""
    w = falling(16000.0, 4500.0, 60_001)
    t = np.linspace(0.0, 1.0, len(w))
    w0, w5 = sdof(w, 9360.0, 0.08), 0.3 * sdof(w, 9650.0, 0.06)
    tab = np.column_stack([t, w / RPM, w0, t, w / RPM, w5, t, w / RPM])
    locs = {"0": {"whirl": "rotor.X_brg0"}, "5": {"whirl": "rotor.X_brg5"}}
    modes = Damped([8500.0, 10200.0], {"0": [(9100.0, 8500.0), (11400.0, 10200.0)], "5": [(9950.0, 10200.0)]})
    lo, hi = crossings(tab, "spool_pt", modes, locs, 1)
    assert (lo["critical_speed_rpm"], lo["location"], lo["peak_found"]) == (8500.0, "0", True)
    assert (hi["critical_speed_rpm"], hi["location"], hi["peak_found"]) == (10200.0, "5", True)
    assert hi["peak_speed_rpm"] == pytest.approx(9650.0 / math.sqrt(1 - 2 * 0.06 ** 2), rel=2 * SPEED_BIN)


def test_label_follows_the_film_temperature():
    """A peak at 9 800 rev/min is the lower mode's with the films at 30 C (damped 9 100 / 11 400) and the upper
    mode's at 40 C (8 690 / 10 700): the label is that of the damped critical speeds at the film temperature of
    the peak's sample, which the crossing reports."""
    w = falling(16000.0, 4500.0, 30_001)
    by_t = {30: {"0": [(9100.0, 8500.0), (11400.0, 10200.0)]}, 40: {"0": [(8690.0, 8500.0), (10700.0, 10200.0)]}}
    locs = {"0": {"whirl": "rotor.X_brg0", "film": "thermal0.T_sfd_oil"}}
    for T, mode, damped in ((30.0, 8500.0, 9100.0), (40.0, 10200.0, 10700.0)):
        t = np.linspace(0.0, 1.0, len(w))
        tab = np.column_stack([t, w / RPM, sdof(w, 9800.0, 0.05), t, w / RPM, np.full(len(w), T + 273.15)])
        got = [c for c in crossings(tab, "spool_pt", Damped([8500.0, 10200.0], None, by_t), locs, 1)
               if c["peak_found"]]
        assert [(c["critical_speed_rpm"], c["damped_critical_speed_rpm"]) for c in got] == [(mode, damped)]
        assert got[0]["film_temperature_C"] == {"0": pytest.approx(T)}


def test_fast_passage_far_below_its_critical_is_found():
    """A fast rundown's peak 23 % below the critical speed (the Jeffcott rotor run down in 0.1 s: 4 640 against
    6 040 rev/min) is a crossing of that critical speed: no band around it decides."""
    w = falling(9000.0, 3000.0)
    (c,) = crossings(table(w, sdof(w, 4640.0, 0.1)), "spool", ScenarioModes([6039.5]), LOCS, 1)
    assert c["peak_found"] is True and c["peak_speed_rpm"] == pytest.approx(4640.0, rel=0.02)


def test_time_and_speed_of_the_largest_sample():
    """Per-step samples folded into bins of BIN_S (RundownTrack): a crossing's time and speed are those of the sample
    where the whirl is largest, not the end of its bin."""
    n = 200_001
    t = np.linspace(0.0, 2.0, n)
    rpm = 9000.0 - 3000.0 * t
    whirl = sdof(rpm, 6000.0, 0.03)
    locs = {"disk": {"whirl": "rotor.X_brg0"}}
    raw = np.column_stack([t, rpm / RPM, whirl, t, rpm / RPM])
    cols = _layout(locs)
    tab = np.vstack([fold(raw[i:i + 3000], 1, cols) for i in range(0, n, 3000)])
    tab = fold(tab, 1, cols)
    assert len(tab) == pytest.approx(2.0 / BIN_S, abs=2)
    (c,) = crossings(tab, "spool", ScenarioModes([6000.0]), locs, 1)
    j = int(np.argmax(whirl))
    assert c["t_s"] == t[j] and c["peak_speed_rpm"] == pytest.approx(rpm[j], rel=1e-12)


def test_no_peak_is_said_not_a_band_edge():
    """A whirl that rises monotonically with speed (a mode far above the run's speeds) has no peak: the crossings
    within the run's speeds say so (peak_found false, a note, no speed), none outside them is made up."""
    w = falling(12000.0, 3000.0)
    tab = table(w, sdof(w, 30000.0, 0.05))
    got = crossings(tab, "spool", ScenarioModes([8500.0, 10200.0, 14000.0]), LOCS, 1)
    assert [c["critical_speed_rpm"] for c in got] == [8500.0, 10200.0]
    for c in got:
        assert c["peak_found"] is False and c["peak_speed_rpm"] is None and c["t_s"] is None
        assert "no resonance peak" in c["note"]
        assert c["bearings"]["disk"]["peak_whirl_mm"] is None


def test_band_edge_maximum_is_not_a_peak():
    """One damped peak at 11 400 rev/min (critical 10 200) on a whirl that falls from 9 000 down: the largest
    whirl within +-15 % of 8 500 (half way to 10 200: 9 350) is at that band's edge, which the crossing of 8 500
    must not report; 10 200 gets 11 400."""
    w = falling(16000.0, 4500.0, 60_001)
    whirl = sdof(w, 11400.0, 0.06)
    band = (w >= 8500 * 0.85) & (w <= 9350.0)
    assert w[band][np.argmax(whirl[band])] == pytest.approx(9350.0, abs=1.0)   # what a band's maximum gives
    lo, hi = crossings(table(w, whirl), "spool", ScenarioModes([8500.0, 10200.0]), LOCS, 1)
    assert lo["peak_found"] is False and lo["peak_speed_rpm"] is None
    assert hi["peak_found"] is True
    exact = 11400.0 / math.sqrt(1.0 - 2.0 * 0.06 ** 2)
    assert abs(math.log(hi["peak_speed_rpm"] / exact)) <= math.log1p(SPEED_BIN)


def test_ripple_below_the_prominence_is_no_peak():
    """A monotone whirl with a 0.2 % ripple (the per-bin maximum of an elliptic orbit) has no peak; the same
    ripple on a resonance curve leaves its one peak."""
    w = falling(9000.0, 3000.0)
    ripple = 1.0 + 0.002 * np.sin(w / 7.0)
    assert resonance_peaks(w, sdof(w, 30000.0, 0.05) * ripple) == []
    (p,) = resonance_peaks(w, sdof(w, 6000.0, 0.05) * ripple)
    assert p.speed == pytest.approx(6000.0 / math.sqrt(1.0 - 2.0 * 0.05 ** 2), rel=2 * SPEED_BIN)


def test_samples_in_any_order_and_stopped_samples():
    """The peaks do not depend on the samples' order (a rundown, a run-up, shuffled); samples at 0 rev/min (a
    stopped rotor) are left out."""
    w = np.concatenate([falling(), np.zeros(50)])
    a = sdof(w, 6000.0, 0.03)
    ref = resonance_peaks(w, a)
    perm = np.random.default_rng(1).permutation(len(w))
    got = resonance_peaks(w[perm], a[perm])
    assert [p.speed for p in got] == [p.speed for p in ref] and len(ref) == 1
    assert perm[got[0].index] == ref[0].index or w[perm][got[0].index] == w[ref[0].index]


def test_bad_shapes_are_a_clear_error():
    """Speed and amplitude of different lengths: a clear error, not an index error."""
    with pytest.raises(ValueError, match="differ in length"):
        resonance_peaks([1.0, 2.0], [1.0])


def test_locations_are_the_engines_bearing_ids():
    """Any engine's co-simulated bearings are read, by its own ids, in the rotor's port order, each with its
    contact outputs, its damper's transmitted force and the film temperature fed to the damper; a rotor without
    co-simulated bearings is a test rotor's disk."""
    from types import SimpleNamespace as NS

    from rotorcosim.cases.rundown.results import _locations
    from rotorcosim.master.core.system import Connection

    def comp(*outs):
        return NS(y={o: None for o in outs})

    comps = {"rotor": comp("X_brg2", "X_brg7", "X_brg11", "F_u"), "bearing2": comp("Q_max", "sigma_max"),
             "bearing7": comp("Q_max_step", "sigma_max_step", "Q_max"), "bearing11": comp("Q_max"),
             "damper2": comp("F_journal"), "damper7": comp("F_journal")}
    cons = [Connection("thermal2.T_sfd_oil", "damper2.T_oil"), Connection("thermal7.T_sfd_oil", "damper7.T_oil")]
    locs = _locations(NS(system=NS(components=comps, connections=cons)))
    assert list(locs) == ["2", "7", "11"]
    assert locs["2"] == {"whirl": "rotor.X_brg2", "load": "bearing2.Q_max", "stress": "bearing2.sigma_max",
                         "force": "damper2.F_journal", "film": "thermal2.T_sfd_oil"}
    assert locs["7"]["load"] == "bearing7.Q_max_step" and locs["11"] == {"whirl": "rotor.X_brg11",
                                                                         "load": "bearing11.Q_max"}
    assert _locations(NS(system=NS(components={"rotor": comp("X_brg0")}, connections=[]))) == {
        "disk": {"whirl": "rotor.X_brg0"}}


def test_peaks_after_an_event_are_labelled_with_that_configurations_critical_speeds():
    """A rundown whose support breaks half way (at 0.5 s, 6 000 rev/min): a single-dof peak at 7 000 rev/min
    before the break and one at 4 000 after. The configuration before has critical speeds 7 000 and 4 200, the
    one after 4 000 and 6 500 (StagedModes, as a fuse's break gives): the first peak is labelled 7 000 in the
    initial configuration, the second 4 000 (not the nearer-by-the-old-engine 4 200) after the break; the old
    configuration's 4 200, never reached while it was in force, and the new one's 6 500, likewise, are not listed."""
    from rotorcosim.cases.rundown.modes import StagedModes

    w = falling(9000.0, 3000.0)
    t = np.linspace(0.0, 1.0, len(w))
    whirl = np.where(t < 0.5, sdof(w, 7000.0, 0.03), sdof(w, 4000.0, 0.03))
    modes = StagedModes([(-math.inf, None, ScenarioModes([7000.0, 4200.0])),
                         (0.5, "after fuse break at 0.5 s", ScenarioModes([4000.0, 6500.0]))])
    got = crossings(table(w, whirl), "spool", modes, LOCS, 1)
    assert [(c["critical_speed_rpm"], c["configuration"], c["peak_found"]) for c in got] == [
        (7000.0, "initial", True), (4000.0, "after fuse break at 0.5 s", True)]
    assert got[0]["t_s"] < 0.5 < got[1]["t_s"]
    assert got[1]["peak_speed_rpm"] == pytest.approx(4000.0, rel=0.01)
