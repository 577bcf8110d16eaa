"""The speed-following bearing's preload offset z0 (components/bearing/spinning.py): the spline the kernel reads
against the direct static solve (static.preload_offset: every ball and the inner race in equilibrium, Newton with
a finite-difference Jacobian, sharing nothing with the one-ball solve and the spline but the contact law) at
speeds between the table's knots; its physics (the balls' centrifugal force lowers it); the kernel carrying the
preload at another speed than the set-up's; a speed beyond the table is a one-line error."""
from __future__ import annotations

import math

import numpy as np
import pytest

from rotorcosim.components.bearing.spinning import TABLE_TOLERANCE, TABLE_TOP, SpinningBearing
from rotorcosim.components.bearing.static import ball_state, preload_offset
from rotorcosim.components.contract import ContractError

RPM = math.pi / 30.0
H = 1e-5


def make(bearing):
    b = SpinningBearing("brg", {"bearing": bearing})
    b.setup(0.0)
    return b


def direct(b, w):
    g = b.geometry
    return preload_offset(g, g.centrifugal_force(w))[0]


@pytest.mark.parametrize("bearing", [0, 5])
def test_interpolated_offset_against_static_solve(bearing):
    """At 25 speeds off the knots over 0-1.5 x omega (the knot spacing is omega / 32: these are not knots) the
    kernel's z0 within TABLE_TOLERANCE (1e-6) of the static solve; at the set-up speed it is the static solve's
    own number (the constant-speed bearing's z0)."""
    b = make(bearing)
    top = TABLE_TOP * b.p["omega"]
    speeds = np.concatenate([top * (np.arange(24) + 0.37) / 24.0, [top]])
    err = max(abs(b.preload_offset(w) / direct(b, w) - 1.0) for w in speeds)
    assert err <= TABLE_TOLERANCE
    assert b.z0_table_error <= TABLE_TOLERANCE
    assert b.preload_offset() == b.z0 == direct(b, b.p["omega"])


def test_offset_at_rest_and_at_speed():
    """Bearing #5 (1100 N): z0 at rest and at 16 000 rev/min from the spline as the static solve gives them
    (22.46 and 16.22 um); the centrifugal force lowers it: the balls pushed outward carry the preload at a smaller
    axial offset, and the offset of 16 000 rev/min at rest would carry far less than the preload."""
    b = make(5)
    g = b.geometry
    z_rest, z_run = b.preload_offset(0.0), b.preload_offset(16000.0 * RPM)
    assert z_rest == pytest.approx(direct(b, 0.0), rel=TABLE_TOLERANCE)
    assert z_run == pytest.approx(direct(b, 16000.0 * RPM), rel=TABLE_TOLERANCE)
    assert z_rest * 1e6 == pytest.approx(22.46, abs=0.01) and z_run * 1e6 == pytest.approx(16.22, abs=0.01)
    # each carries the preload at its own speed, and not at the other's
    at_rest = ball_state(g, [0.0, 0.0, z_rest], Fc=0.0)
    assert np.sum(at_rest.Q_i * np.sin(at_rest.alpha_i)) == pytest.approx(g.preload, rel=1e-6)
    wrong = ball_state(g, [0.0, 0.0, z_run], Fc=0.0)
    assert np.sum(wrong.Q_i * np.sin(wrong.alpha_i)) < 0.7 * g.preload


@pytest.mark.parametrize("bearing", [0, 5])
def test_kernel_carries_the_preload_at_another_speed(bearing):
    """Stepped at 9 600 rev/min (set up at 16 000) with the inner race at rest and the journal on a damped spring:
    the balls settle to the preload carried at that speed (the force on the rotor back to zero axially) and the
    kernel's z0 is that speed's; with the set-up's z0 kept the balls would carry another axial load."""
    b = make(bearing)
    g = b.geometry
    w = 9600.0 * RPM
    k, c, t = 5.254e6, 1e3, 0.0
    for _ in range(3000):
        x, v = b.y["X_journal"], b.y["V_journal"]
        b.set_inputs({"X_inner": [0.0, 0.0, 0.0], "V_inner": [0.0, 0.0, 0.0], "F_journal": -k * x - c * v,
                      "K_journal": [-k, 0.0, 0.0, -k], "C_journal": [-c, 0.0, 0.0, -c], "Omega": [w]})
        b.do_step(t, H)
        t += H
    assert b.preload_offset() == pytest.approx(direct(b, w), rel=TABLE_TOLERANCE)
    assert abs(b.y["F_rotor"][2]) < 1e-5 * g.preload
    kept = ball_state(g, [0.0, 0.0, b.z0], Fc=g.centrifugal_force(w))
    assert abs(np.sum(kept.Q_i * np.sin(kept.alpha_i)) - g.preload) > 0.1 * g.preload


def test_speed_beyond_the_table_is_one_line():
    b = make(0)
    w = 1.01 * TABLE_TOP * b.p["omega"]
    assert math.isnan(b.preload_offset(w))
    b.set_inputs({"Omega": [w]})
    with pytest.raises(ContractError, match=r"beyond the preload offset's table .* brg\.omega") as exc:
        b.do_step(0.0, H)
    assert "\n" not in str(exc.value)
