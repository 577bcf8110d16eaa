"""Ball bearing, static load distribution (eqs. 1-8 at rest) against the classical results of Stribeck and
Harris, thermal growth direction, and the ``bearing-static`` command."""
import json
import math

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.optimize import brentq

from rotorcosim.components.bearing.cli import evaluate
from rotorcosim.components.bearing.geometry import build_geometry
from rotorcosim.components.bearing.hertz import series_stiffness
from rotorcosim.components.bearing.static import ball_state, preload_offset, static_equilibrium
from rotorcosim.master.cli import main


def _radial_bearing(Z=21):
    # bearing #0's balls and grooves, contact angle 0, no preload, zero clearance: a deep groove ball bearing
    return build_geometry(None, Z=Z, D=8.73e-3, d_m=70.4e-3, alpha0_deg=0.0, preload=0.0)


@pytest.mark.parametrize("Z", [12, 21])
def test_stribeck_radial_load_distribution(Z):
    """Zero clearance, pure radial load: Stribeck/Harris load zone of half the bearing (epsilon = 0.5) with
    Q(psi) = Q_max cos(psi)^1.5. (a) Against the discrete sum Fr = Q_max sum_{cos psi > 0} cos(psi)^2.5 (exact for
    the ball positions); (b) against the continuous integral J_r(0.5) = 0.2288 (Harris & Kotzalas Table 7.1;
    NSK's Q_max = 4.37 Fr / Z) to the accuracy of replacing the sum by the integral (~1 %); (c) the loaded balls
    follow cos(psi)^1.5 and the others carry nothing."""
    g = _radial_bearing(Z)
    Fr = 3000.0
    X, st = static_equilibrium(g, np.array([Fr, 0.0, 0.0]))
    psi = st.phi
    c = np.cos(psi)
    discrete = Z / np.sum(np.where(c > 0, c, 0.0) ** 2.5)
    Qmax = st.Q_i.max()
    assert Qmax * Z / Fr == pytest.approx(discrete, rel=1e-6)
    Jr = quad(lambda p: math.cos(p) ** 2.5, -math.pi / 2, math.pi / 2)[0] / (2 * math.pi)
    assert Jr == pytest.approx(0.2288, abs=5e-5)
    assert Qmax * Z / Fr == pytest.approx(1.0 / Jr, rel=0.012)
    assert Qmax * Z / Fr == pytest.approx(4.37, rel=0.012)
    expected = Qmax * np.where(c > 1e-9, c, 0.0) ** 1.5
    assert np.allclose(st.Q_i, expected, rtol=1e-6, atol=1e-9 * Qmax)
    # Hertz in series: delta_max = (Q_max / K_n)^(2/3) equals the radial displacement (zero clearance)
    assert X[0] == pytest.approx((Qmax / series_stiffness(g.K_i, g.K_e)) ** (2 / 3), rel=1e-6)


@pytest.mark.parametrize("bearing, Fa", [(0, 800.0), (5, 1100.0), (0, 5000.0)])
def test_pure_axial_load_matches_harris_thrust_equation(bearing, Fa):
    """Angular-contact bearing under pure thrust, no speed: all balls equal, with the loaded contact angle alpha
    from Harris & Kotzalas' equation Fa / (Z K_n (B D)^1.5) = sin(alpha) (cos(alpha0)/cos(alpha) - 1)^1.5,
    B = f_i + f_o - 1 (solved here by brentq), and Q = Fa / (Z sin alpha)."""
    g = build_geometry(bearing)
    Kn = series_stiffness(g.K_i, g.K_e)
    BD = (g.f_i + g.f_o - 1) * g.D
    rhs = Fa / (g.Z * Kn * BD ** 1.5)
    alpha = brentq(lambda a: math.sin(a) * (math.cos(g.alpha0) / math.cos(a) - 1) ** 1.5 - rhs,
                   g.alpha0 + 1e-12, math.radians(60))
    X, st = static_equilibrium(g, np.array([0.0, 0.0, Fa]))
    assert np.allclose(st.alpha_i, alpha, rtol=1e-7)
    assert np.allclose(st.alpha_e, alpha, rtol=1e-7)
    assert np.allclose(st.Q_i, Fa / (g.Z * math.sin(alpha)), rtol=1e-7)
    assert np.allclose(st.Q_e, st.Q_i, rtol=1e-9)


def test_centrifugal_force_loads_the_outer_race():
    """At speed, each ball's equilibrium (eq. 4) has Q_e cos(a_e) - Q_i cos(a_i) = F_c and the outer contact
    angle drops below the inner one (Harris & Kotzalas, high-speed ball bearings); F_c = m_b d_m omega_c^2 / 2
    is ~52 N for bearing #0 at 16 000 rev/min (physics-notes)."""
    g = build_geometry(0)
    omega = 16000 * math.pi / 30
    Fc = g.centrifugal_force(omega)
    assert Fc == pytest.approx(52.0, rel=0.01)
    z0, st = preload_offset(g, Fc)
    lhs = st.Q_e * np.cos(st.alpha_e) - st.Q_i * np.cos(st.alpha_i)
    assert np.allclose(lhs, Fc, rtol=1e-7)
    assert np.all(st.alpha_e < st.alpha_i)
    assert np.sum(st.Q_i * np.sin(st.alpha_i)) == pytest.approx(g.preload, rel=1e-9)


def test_thermal_growth_changes_contact_loads_in_the_right_direction():
    """Inner race and ball growth close the contacts and raise the loads; outer race growth opens them
    (eqs. 6-8, inner race held at its preloaded position, as a rigidly preloaded pair)."""
    g = build_geometry(0)
    z0, st0 = preload_offset(g)
    X = np.array([0.0, 0.0, z0])
    base = st0.Q_i.mean()
    up_i = ball_state(g, X, eps=(1e-6, 0.0, 0.0)).Q_i.mean()
    up_b = ball_state(g, X, eps=(0.0, 0.0, 1e-6)).Q_i.mean()
    down_e = ball_state(g, X, eps=(0.0, 1e-6, 0.0)).Q_i.mean()
    assert up_i > 1.05 * base and up_b > 1.05 * base and down_e < 0.95 * base
    # a uniform radial growth of the inner race equals the same growth of the outer race's opposite
    both = ball_state(g, X, eps=(1e-6, 1e-6, 0.0)).Q_i.mean()
    assert both == pytest.approx(base, rel=1e-9)


def test_ball_losing_contact_carries_nothing():
    """Under a heavy radial load the balls opposite the load lose contact (delta < 0) and carry no load."""
    g = build_geometry(0)
    X, st = static_equilibrium(g, np.array([8000.0, 0.0, 800.0]))
    unloaded = (st.delta_i <= 0.0) & (st.delta_e <= 0.0)
    assert unloaded.sum() >= 3
    assert np.all(st.Q_i[unloaded] == 0.0) and np.all(st.Q_e[unloaded] == 0.0)
    assert np.all(st.delta_i[st.Q_i > 0] > 0)


def test_bearing_static_command_json(capsys):
    """``rotorcosim bearing-static --json``: the documented keys, consistent with the equilibrium (the ball loads
    balance the applied load) and with eq. (10) for the reported stresses."""
    assert main(["bearing-static", "--bearing", "0", "--radial-load", "2000", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    for key in ("radial_load_N", "axial_load_N", "ball_diameter_m", "pitch_diameter_m", "groove_curvature_inner",
                "groove_curvature_outer", "max_contact_load_N", "max_contact_stress_MPa",
                "radial_stiffness_N_per_m", "balls"):
        assert key in out
    assert len(out["balls"]) == 21
    assert set(out["balls"][0]) == {"phi_deg", "Q_inner_N", "Q_outer_N", "alpha_inner_deg", "alpha_outer_deg",
                                    "stress_inner_MPa", "stress_outer_MPa"}
    fr = sum(b["Q_inner_N"] * math.cos(math.radians(b["alpha_inner_deg"])) * math.cos(math.radians(b["phi_deg"]))
             for b in out["balls"])
    fa = sum(b["Q_inner_N"] * math.sin(math.radians(b["alpha_inner_deg"])) for b in out["balls"])
    assert fr == pytest.approx(2000.0, rel=1e-7) and fa == pytest.approx(800.0, rel=1e-7)
    assert out["max_contact_load_N"] == pytest.approx(max(b["Q_inner_N"] for b in out["balls"]))
    assert out["radial_stiffness_N_per_m"] > 0


def test_bearing_static_command_rejects_bad_input(capsys):
    assert main(["bearing-static", "--bearing", "0", "--radial-load", "-1"]) == 2
    assert "radial load" in capsys.readouterr().err
    assert main(["bearing-static", "--bearing", "0", "--radial-load", "nan"]) == 2
    with pytest.raises(ValueError, match=r"--bearing 3: the paper's Table 3 has bearings \[0, 5\]; for another "
                                         r"bearing give its engine \(--engine FILE\)"):
        evaluate(3, 100.0)
