"""The loss of a squeeze film damper's oil supply (``oil_loss_time``, or on a condition, ``oil_loss_eccentricity``):
an event that removes the film, after which the journal runs on the damper land (contact k_wall at the radial
clearance, Coulomb friction ``land_friction``) and the film power is zero.

Verified against two things written apart from the damper: a journal on its centering spring with a rotating
unbalance, co-simulated with ``damper.fast`` (the oil lost at t = 0), against scipy ``solve_ivp`` of the same
journal on a rigid land with its own contact and friction law, and the steady synchronous orbit in closed form
(radial and tangential force balance of a circular orbit of radius r: F0^2 = ((k_s - m W^2) r + F_n)^2 +
(c W r + mu F_n)^2, F_n = k_w (r - c))."""
from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from rotorcosim.components.contract import Component, ContractError, Variable
from rotorcosim.components.damper.component import FastDamper
from rotorcosim.master.core.system import Connection, System
from rotorcosim.master.schedule import Interval, Timeline
from rotorcosim.master.simulation import Simulation

#: the journal: 10 kg on damper #0's centering spring (5.254e6 N/m, clearance 0.635 mm) and a viscous support
#: damping (a damping ratio 0.3: steady within 0.05 s), an unbalance force of 3 kN at 600 rad/s (its free orbit
#: 1.0 mm, past the clearance); the land at 1e8 N/m with friction 0.1
M, K_S, CLEAR, W, F0, K_W, MU = 10.0, 5.254e6, 0.635e-3, 600.0, 3000.0, 1.0e8, 0.1
C_D = 2 * 0.3 * math.sqrt(K_S * M)
STEP, T_END = 5e-6, 0.06


class Journal(Component):
    """A point mass in x, y on a viscous damper, driven by a rotating force F0 (cos W t, sin W t) and the damper's
    force on it, linearly implicit over the step with the damper's K_film and C_film as the engine's bearing
    integrates its journal (trapezoidal: x += h (v + dv / 2), the force at the step's middle)."""

    variables = (Variable("F", "input", 2, "N"), Variable("K", "input", 4, "N/m"), Variable("C", "input", 4, "N.s/m"),
                 Variable("X", "output", 2, "m"), Variable("V", "output", 2, "m/s"))

    def setup(self, t0=0.0):
        super().setup(t0)
        self.state = {"x": np.zeros(2), "v": np.zeros(2)}
        self.y["X"], self.y["V"] = self.state["x"].copy(), self.state["v"].copy()

    def do_step(self, t, h):
        te = t + h
        v = self.state["v"]
        k, c = self.u["K"].reshape(2, 2), self.u["C"].reshape(2, 2)
        # trapezoidal in the damping and the linearised force (second order, no numerical damping)
        f = F0 * np.array([math.cos(W * te), math.sin(W * te)]) + self.u["F"] + 0.5 * h * k @ v - C_D * v
        dv = np.linalg.solve((M / h + 0.5 * C_D) * np.eye(2) - 0.25 * h * k - 0.5 * c, f)
        self.state["x"] = self.state["x"] + h * (v + 0.5 * dv)
        self.state["v"] = v + dv
        self.y["X"], self.y["V"] = self.state["x"].copy(), self.state["v"].copy()
        self.time = te


def _reference():
    """The journal on the rigid land, the oil gone: solve_ivp (Radau, the contact stiff) of its own equations."""
    v_reg = 1e-4

    def rhs(t, s):
        x, y, vx, vy = s
        fx = F0 * math.cos(W * t) - K_S * x - C_D * vx
        fy = F0 * math.sin(W * t) - K_S * y - C_D * vy
        r = math.hypot(x, y)
        if r > CLEAR:
            nx, ny = x / r, y / r
            fn = K_W * (r - CLEAR)
            vn = vx * nx + vy * ny
            tx, ty = vx - vn * nx, vy - vn * ny
            g = MU * fn / math.sqrt(tx * tx + ty * ty + v_reg * v_reg)
            fx -= fn * nx + g * tx
            fy -= fn * ny + g * ty
        return [vx, vy, fx / M, fy / M]

    t = np.linspace(0.0, T_END, int(round(T_END / 1e-4)) + 1)
    sol = solve_ivp(rhs, (0.0, T_END), [0.0, 0.0, 0.0, 0.0], method="Radau", t_eval=t, rtol=1e-8, atol=1e-12)
    return sol.t, np.hypot(sol.y[0], sol.y[1])


def _steady_radius():
    def balance(r):
        fn = K_W * (r - CLEAR)
        return ((K_S - M * W * W) * r + fn) ** 2 + (C_D * W * r + MU * fn) ** 2 - F0 * F0
    return brentq(balance, CLEAR, 2 * CLEAR)


def _journal_on(damper):
    """The simulation of the journal of :class:`Journal` on ``damper`` (its oil at 70 C, the housing fixed)."""
    comps = {"journal": Journal("journal"), "damper": damper}
    cons = [Connection("journal.X", "damper.X_journal"), Connection("journal.V", "damper.V_journal"),
            Connection("damper.F_journal", "journal.F"), Connection("damper.K_film", "journal.K"),
            Connection("damper.C_film", "journal.C")]
    inputs = {"damper.X_housing": np.zeros(2), "damper.V_housing": np.zeros(2), "damper.T_oil": np.array([343.15])}
    return Simulation(System(comps, cons, inputs=inputs), order=["journal", "damper"])


def test_journal_on_the_land_against_an_independent_integration():
    """Co-simulated (the oil lost at t = 0: a time event at the start) against solve_ivp: the orbit radius within
    0.5 % of the clearance at every 0.1 ms (0.23 % measured, at the first sample), and over the last 10 ms the
    orbit radius and the contact force (normal and friction) within 0.1 % of the closed-form steady orbit (1e-6 and
    5e-6 measured); the film force and power zero throughout, the event recorded."""
    damper = FastDamper("damper", {"damper": 0, "oil_loss_time": 0.0, "k_wall": K_W, "land_friction": MU})
    sim = _journal_on(damper)

    rows = []

    class Watch:
        stride = 20

        def __getattr__(self, name):
            return lambda *a, **k: None

        def block_signals(self, sim):
            return None

        def step(self, sim, t):
            y = damper.y
            rows.append((t, *damper.u["X_journal"], *y["F_contact"], *y["F_film"], y["P_film"][0]))

    sim.observers.append(Watch())
    report = sim.run(Timeline([Interval("TM", duration=T_END, step=STEP)]))
    (ev,) = report.events
    assert (ev["component"], ev["kind"], ev["t_s"]) == ("damper", "oil_supply_loss", 0.0)
    a = np.array(rows)
    t, r = a[:, 0], np.hypot(a[:, 1], a[:, 2])
    assert np.all(a[:, 5:8] == 0.0)               # no film, no film power
    t_ref, r_ref = _reference()
    assert np.max(np.abs(np.interp(t_ref, t, r) - r_ref)) < 5e-3 * CLEAR
    last = t > T_END - 0.01
    r_ss = _steady_radius()
    f_ss = K_W * (r_ss - CLEAR) * math.hypot(1.0, MU)
    assert r[last].mean() == pytest.approx(r_ss, rel=1e-3)
    assert np.hypot(a[last, 3], a[last, 4]).mean() == pytest.approx(f_ss, rel=1e-3)


def test_the_loss_removes_the_film_power_at_its_time():
    """Oil lost at 2 ms: P_film and F_film are the film's before, zero from the event on (what the thermal
    network's P_sfd input is given); the event's values hold the power it had."""
    d = FastDamper("d", {"damper": 0, "oil_loss_time": 2e-3})
    d.setup(0.0)
    d.set_inputs({"X_journal": [2e-4, 0.0], "V_journal": [0.0, 0.1], "T_oil": [343.15]})
    d.do_step(0.0, 1e-3)
    p0 = float(d.y["P_film"][0])
    assert p0 > 0.0 and d.next_event(1e-3) == 2e-3
    what = d.update_discrete(2e-3, [])
    assert what["kind"] == "oil_supply_loss" and what["values"]["P_film_W"] == p0
    assert d.y["P_film"][0] == 0.0 and np.all(d.y["F_film"] == 0.0) and d.next_event(2e-3) is None
    d.do_step(2e-3, 1e-3)
    assert d.y["P_film"][0] == 0.0 and d.y["F_journal"] == pytest.approx(-K_S * np.array([2e-4, 0.0]))


def test_oil_lost_on_an_eccentricity_against_an_independent_integration():
    """oil_loss_eccentricity = 0.5: the journal, starting at the centre, whirls out under the 3 kN unbalance on its
    film and spring; the loss located where its eccentricity ratio reaches 0.5, within 1 us of solve_ivp's event
    (DOP853 with its own event location on the same force law: the damper's film force as a function, the spring,
    the viscous support; 1.8561 ms, 0.07 us measured), recorded once with its values; from then on no film (F_film
    and P_film zero) and the indicator out."""
    e_loss = 0.5
    damper = FastDamper("damper", {"damper": 0, "oil_loss_eccentricity": e_loss})
    report = _journal_on(damper).run(Timeline([Interval("TM", duration=0.003, step=STEP)]))
    (ev,) = report.events
    assert (ev["component"], ev["kind"], ev["indicators"]) == ("damper", "oil_supply_loss", ["oil_loss"])
    assert ev["values"]["oil_loss_eccentricity"] == e_loss and ev["values"]["P_film_W"] > 0.0
    assert ev["values"]["eccentricity_ratio"] == pytest.approx(e_loss, abs=1e-4)
    mu = damper.viscosity(343.15)

    def rhs(t, s):
        x, y, vx, vy = s
        fx, fy = damper.film_force(x, y, vx, vy, mu)
        return [vx, vy, (fx + F0 * math.cos(W * t) - K_S * x - C_D * vx) / M,
                (fy + F0 * math.sin(W * t) - K_S * y - C_D * vy) / M]

    def reached(t, s):
        return math.hypot(s[0], s[1]) / CLEAR - e_loss

    reached.terminal, reached.direction = True, 1
    sol = solve_ivp(rhs, (0.0, 0.003), [0.0, 0.0, 0.0, 0.0], method="DOP853", events=reached, rtol=1e-10, atol=1e-13)
    (t_ref,) = sol.t_events[0]
    assert ev["t_s"] == pytest.approx(t_ref, abs=1e-6)
    assert np.all(damper.y["F_film"] == 0.0) and damper.y["P_film"][0] == 0.0 and len(damper.indicators()) == 0


def test_the_fe_damper_meets_the_condition_in_its_step():
    """damper.fe (its Python step, the generic loop's): the indicator |d| / c - e_loss after each step, the oil lost
    at the end of the step that reaches the ratio (film power zero), the indicator out once the loss is handed
    over; the event's film power the film's at that motion."""
    from rotorcosim.components.damper.component import FEDamper

    d = FEDamper("d", {"damper": 0, "oil_loss_eccentricity": 0.5, "n_theta": 32, "n_z": 8})
    d.setup(0.0)
    d.set_inputs({"X_journal": [1e-4, 0.0], "V_journal": [0.0, 0.05], "T_oil": [343.15]})
    d.do_step(0.0, 1e-5)
    assert d.indicators() == pytest.approx([1e-4 / CLEAR - 0.5]) and d.y["P_film"][0] > 0.0
    d.set_inputs({"X_journal": [4e-4, 0.0]})
    d.do_step(1e-5, 1e-5)
    assert d.indicators() == pytest.approx([4e-4 / CLEAR - 0.5]) and d.y["P_film"][0] == 0.0
    what = d.update_discrete(2e-5, [0])
    assert what["kind"] == "oil_supply_loss" and what["values"]["P_film_W"] > 0.0
    assert len(d.indicators()) == 0


def test_without_the_condition_the_damper_declares_no_indicator():
    """A damper without oil_loss_eccentricity is no concern of the event location (no indicator: the run builds no
    locator and its compiled loop saves nothing)."""
    d = FastDamper("d", {"damper": 0})
    d.setup(0.0)
    assert d.event_indicators == () and len(d.indicators()) == 0
    assert FastDamper("e", {"damper": 0, "oil_loss_eccentricity": 0.9}).event_indicators == ("oil_loss",)


@pytest.mark.parametrize("params, message", [
    ({"oil_loss_eccentricity": -0.1}, r"d.oil_loss_eccentricity must be within \[0, 1\]"),
    ({"oil_loss_eccentricity": 1.5}, r"d.oil_loss_eccentricity must be within \[0, 1\]"),
    ({"oil_loss_eccentricity": 0.8, "k_wall": 0.0}, "d.k_wall must be > 0 with oil_loss_eccentricity"),
    ({"oil_loss_eccentricity": 0.8, "event_tolerance": 0.0}, "d.event_tolerance must be > 0"),
    ({"land_friction": -0.1}, "d.land_friction must be >= 0"),
    ({"land_friction": float("nan")}, "d.land_friction: value is not finite"),
    ({"oil_loss_time": 0.01, "k_wall": 0.0}, "d.k_wall must be > 0 with oil_loss_time"),
])
def test_bad_oil_loss_inputs_are_named(params, message):
    with pytest.raises(ContractError, match=message):
        FastDamper("d", {"damper": 0, **params}).setup(0.0)


@pytest.mark.slow
@pytest.mark.parametrize("t_loss", [0.0100025, 0.01])
def test_oil_loss_in_the_engine_compiled_as_generic(t_loss):
    """The paper's engine (blade_loss_2850, monolithic, 20 ms), damper #0's oil lost at 10.0025 ms (inside a base
    step of a multi-rate interval: the film goes at that step's end) or at 10 ms (on the grid: the compiled loop
    records it at the step's start and goes on): the event recorded once at its time, the film power zero from then
    on in what the thermal network is fed (P_film, thermal0's P_sfd), and the compiled and the generic loop's time
    series equal bit for bit. ~3 s of CPU each (measured: slow), most of it the generic loop."""
    from rotorcosim.master.api import load_scenario, simulate

    sc = load_scenario(None).set({"damper0.oil_loss_time": t_loss})
    runs = {e: simulate(sc, duration=0.02, schedule="monolithic", figures=False, engine=e,
                        record=["damper0.P_film", "damper0.F_film", "thermal0.T_sfd_oil"]) for e in ("compiled", "python")}
    c, g = runs["compiled"], runs["python"]
    (ev,) = c.summary["events"]
    assert (ev["component"], ev["kind"], ev["t_s"]) == ("damper0", "oil_supply_loss", t_loss)
    assert c.summary["events"] == g.summary["events"] and c.summary["engine"] == "compiled"
    t, p = c.time, np.asarray(c["damper0.P_film"]).ravel()
    assert p[(t > 0.005) & (t < 0.01)].min() > 0.0 and np.all(p[t > t_loss + 5e-6] == 0.0)
    for ref in c.signals:
        assert np.array_equal(c[ref], g[ref]), ref


@pytest.mark.slow
def test_oil_lost_on_an_eccentricity_in_the_engine_compiled_as_generic():
    """The paper's engine (blade_loss_2850, monolithic, 30 ms; the thermal networks at 1 ms, a multi-rate interval),
    damper #0's oil lost when its eccentricity ratio reaches 0.3 (in the blade loss's transient, 11.24 ms): the
    event located once, its ratio 0.3 within the tolerance's motion, the film power zero from then on in what the
    thermal network is fed, and the compiled loop (the damper's kernel reports it, EVENT) and the generic loop's
    time series equal bit for bit. ~2.5 s of CPU (measured: slow), most of it the generic loop."""
    from rotorcosim.master.api import load_scenario, simulate

    sc = load_scenario(None).set({"damper0.oil_loss_eccentricity": 0.3})
    runs = {e: simulate(sc, duration=0.03, schedule="monolithic", figures=False, engine=e,
                        record=["damper0.P_film", "damper0.F_film", "thermal0.T_sfd_oil"]) for e in ("compiled", "python")}
    c, g = runs["compiled"], runs["python"]
    (ev,) = c.summary["events"]
    assert (ev["component"], ev["kind"], ev["indicators"]) == ("damper0", "oil_supply_loss", ["oil_loss"])
    assert 0.01 < ev["t_s"] < 0.02 and ev["values"]["eccentricity_ratio"] == pytest.approx(0.3, abs=1e-4)
    assert c.summary["events"] == g.summary["events"] and c.summary["engine"] == "compiled"
    t, p = c.time, np.asarray(c["damper0.P_film"]).ravel()
    assert p[(t > 0.005) & (t < ev["t_s"])].min() > 0.0 and np.all(p[t > ev["t_s"] + 5e-6] == 0.0)
    for ref in c.signals:
        assert np.array_equal(c[ref], g[ref]), ref


@pytest.mark.slow
def test_a_bad_oil_loss_eccentricity_of_a_run_is_one_line(tmp_path):
    """(~3 s of CPU: the engine's set-up, slow.) On the command line: one line naming the key, exit 2, nothing
    written."""
    import subprocess
    import sys

    out = tmp_path / "o"
    r = subprocess.run([sys.executable, "-m", "rotorcosim.master.cli", "run", "--set",
                        "damper0.oil_loss_eccentricity=1.5", "--duration", "0.001", "--quiet", "--no-figures",
                        "--out", str(out)], capture_output=True, text=True)
    assert r.returncode == 2 and "Traceback" not in r.stderr
    assert r.stderr.strip().splitlines() == ["rotorcosim run: error: damper0.oil_loss_eccentricity must be within "
                                             "[0, 1] (an eccentricity ratio; 0: never), got 1.5"]
    assert not out.exists()
