"""Rub ring (paper eq. 11, Table 3 clearance): contact force, friction direction and friction power by hand."""
import math

import numpy as np
import pytest

from rotorcosim.components.contract import ContractError
from rotorcosim.components.rubring.component import RubRing

OMEGA = 16000 * 2 * math.pi / 60      # 1675.516 rad/s
K, C_D, MU, R, CLR = 2e8, 4000.0, 0.2, 0.0254, 0.508e-3


def ring(**params):
    r = RubRing("rubring0", {"stiffness": K, "damping": C_D, "friction": MU, "radius": R, "clearance": CLR,
                             "omega": OMEGA, **params})
    r.setup(0.0)
    return r


def evaluate(r, x, v, xh=(0.0, 0.0), vh=(0.0, 0.0)):
    r.set_inputs({"X_rotor": x, "V_rotor": v, "X_housing": xh, "V_housing": vh})
    r.do_step(0.0, 1e-5)
    return {k: v.copy() for k, v in r.get_outputs().items()}


def test_no_force_inside_the_clearance():
    """Any position with |X_rotor - X_housing| <= 0.508 mm, any velocity: zero force and zero power."""
    rng = np.random.default_rng(1)
    r = ring()
    for _ in range(200):
        rad, ang = CLR * math.sqrt(rng.uniform()), rng.uniform(0, 2 * math.pi)
        xh = rng.normal(0, 1e-3, 2)
        y = evaluate(r, xh + rad * np.array([math.cos(ang), math.sin(ang)]), rng.normal(0, 5, 2), xh,
                     rng.normal(0, 5, 2))
        assert not np.any(y["F_rotor"]) and y["P_rub"][0] == 0.0 and y["F_normal"][0] == 0.0


@pytest.mark.parametrize("direction", [+1, -1])
def test_circular_orbit_force_and_power_by_hand(direction):
    """Circular orbit of radius 0.6 mm at the spin speed, forward (+1) and backward (-1) whirl; housing at rest.
    By hand: penetration 0.6 - 0.508 = 0.092 mm, no radial velocity, so F_n = 2e8 * 9.2e-5 = 18 400 N; sliding
    speed omega R + direction * omega r = 42.558 +- 1.005 m/s; friction mu F_n = 3680 N opposing it, tangential;
    P = 3680 * (42.558 +- 1.005) W (eq. 11 with the whirl's share); same at every point of the orbit."""
    r = ring()
    rad, Om = 0.6e-3, direction * OMEGA
    v_slip = OMEGA * R + Om * rad
    for phase in np.linspace(0, 2 * math.pi, 13)[:-1]:
        n = np.array([math.cos(phase), math.sin(phase)])
        t = np.array([-n[1], n[0]])
        y = evaluate(r, rad * n, rad * Om * t)
        assert y["F_normal"][0] == pytest.approx(18400.0, rel=1e-12)
        assert float(y["F_rotor"] @ n) == pytest.approx(-18400.0, rel=1e-12)
        assert float(y["F_rotor"] @ t) == pytest.approx(-3680.0, rel=1e-12)   # spin dominates: opposes +t
        assert y["P_rub"][0] == pytest.approx(3680.0 * v_slip, rel=1e-12)
        assert np.array_equal(y["F_housing"], -y["F_rotor"])
    assert v_slip == pytest.approx(42.558 + direction * 1.005, abs=1e-3)


def test_friction_follows_the_slip_when_backward_whirl_dominates():
    """Non-spinning rotor (omega = 0) in backward whirl (clockwise): the rotor's surface slides in -t, so the
    friction on the rotor points along +t (opposes the sliding), and forward whirl gives -t; power mu F_n |v|."""
    r = ring(omega=0.0)
    rad, Om = 0.55e-3, 300.0
    n, t = np.array([0.0, 1.0]), np.array([-1.0, 0.0])
    fn = K * (rad - CLR)
    back = evaluate(r, rad * n, -rad * Om * t)
    fwd = evaluate(r, rad * n, rad * Om * t)
    assert float(back["F_rotor"] @ t) == pytest.approx(+MU * fn, rel=1e-12)
    assert float(fwd["F_rotor"] @ t) == pytest.approx(-MU * fn, rel=1e-12)
    assert back["P_rub"][0] == pytest.approx(MU * fn * rad * Om, rel=1e-12)


def test_damping_on_the_penetration_rate_and_no_pull():
    """Moving outwards at 0.5 m/s adds c v = 2000 N to k delta; moving inwards fast enough to make
    k delta + c v negative gives no force at all (the contact never pulls)."""
    r = ring(friction=0.0)
    x = np.array([0.51e-3, 0.0])
    y = evaluate(r, x, [0.5, 0.0])
    assert y["F_normal"][0] == pytest.approx(K * 0.002e-3 + C_D * 0.5, rel=1e-9)
    y = evaluate(r, x, [-1.0, 0.0])            # 400 N - 4000 N < 0
    assert y["F_normal"][0] == 0.0 and not np.any(y["F_rotor"]) and y["P_rub"][0] == 0.0


def test_relative_motion_only():
    """Moving rotor and housing together (same displacement and velocity) changes nothing."""
    r = ring()
    a = evaluate(r, [0.6e-3, 0.1e-3], [0.3, -0.7])
    b = evaluate(r, [0.6e-3 + 2e-3, 0.1e-3 - 1e-3], [0.3 + 5.0, -0.7 + 2.0], [2e-3, -1e-3], [5.0, 2.0])
    assert np.allclose(a["F_rotor"], b["F_rotor"], rtol=1e-9) and a["P_rub"][0] == pytest.approx(b["P_rub"][0])


def test_ring_5_and_explicit_parameters():
    r = RubRing("rubring5", {"bearing": 5})
    r.setup(0.0)
    assert r.p["radius"] == pytest.approx(0.0419) and r.p["clearance"] == pytest.approx(0.508e-3)
    r = RubRing("rubring5", {"bearing": 5, "radius": 0.05})
    r.setup(0.0)
    assert r.p["radius"] == 0.05


@pytest.mark.parametrize("params, message", [
    ({"bearing": 0, "clearance": -1e-4}, "clearance must be > 0"),
    ({"bearing": 0, "stiffness": 0.0}, "stiffness must be > 0"),
    ({"friction": -0.1}, r"friction: -0.1 is outside the declared range \[0, 2\]"),
    # 50 was accepted: no dry metal pair comes near (handbooks: at most ~1.4)
    ({"friction": 50.0}, r"friction: 50.0 is outside the declared range \[0, 2\]"),
    ({"bearing": 2}, "bearing must be one of"),
    # Table 3's 0.508 mm given as metres: wider than the shaft, refused with the conversion
    ({"bearing": 0, "clearance": 0.508}, r"clearance = 0.508 m is not smaller than the rotor's radius at the ring "
     r"\(0.0254 m\); lengths are in metres: 0.508 mm = 0.000508 m"),
])
def test_bad_parameters(params, message):
    with pytest.raises(ContractError, match=message):
        RubRing("r", params).setup(0.0)


def test_non_finite_motion_is_rejected():
    r = ring()
    r.set_inputs({"X_rotor": [float("nan"), 0.0]})
    with pytest.raises(ContractError, match="non-finite"):
        r.do_step(0.0, 1e-5)


def test_contact_stiffness_by_finite_differences():
    """On a static contact at +x without friction, dF_x/dx = -k (the contact stiffness) and dF_x/dv_x = -c_d;
    the normal force turns with the position, so dF_y/dy = -F_n / r = -k (r - c) / r (by hand). Central
    differences of the component's output (1e-9 m, 1e-6 m/s: inside the smooth part of the contact)."""
    r = ring(friction=0.0)

    def F(x, v):
        evaluate(r, x, v)
        return r.y["F_rotor"].copy()

    x0, dx, dv = 0.6e-3, 1e-9, 1e-6
    dFx_dx = (F([x0 + dx, 0.0], [0.0, 0.0])[0] - F([x0 - dx, 0.0], [0.0, 0.0])[0]) / (2 * dx)
    dFy_dy = (F([x0, dx], [0.0, 0.0])[1] - F([x0, -dx], [0.0, 0.0])[1]) / (2 * dx)
    dFx_dv = (F([x0, 0.0], [dv, 0.0])[0] - F([x0, 0.0], [-dv, 0.0])[0]) / (2 * dv)
    assert dFx_dx == pytest.approx(-K, rel=1e-5)
    assert dFy_dy == pytest.approx(-K * (x0 - CLR) / x0, rel=1e-5)
    assert dFx_dv == pytest.approx(-C_D, rel=1e-5)
