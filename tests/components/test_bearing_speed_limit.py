"""The ball bearing model over its whole declared speed range (bore x speed <= dn_limit, data/bearings.toml).

The preload offset z0 falls with speed and below zero at high speed (the balls' centrifugal force, thrown onto the
outer race's inclined contact, presses them on the inner race axially with no offset): the one-ball solve's
bracket follows it. Verified against the direct static solve (static.preload_offset: every ball and the inner
race in equilibrium, Newton with a finite-difference Jacobian, an independent algorithm sharing only the contact
law) and against the ball's own equilibrium (Harris & Kotzalas' high-speed ball: Q_e cos a_e - Q_i cos a_i = F_c,
Z Q_i sin a_i = P). A speed above the limit, and a failed internal solve, is one line naming the bearing, the
speed and the parameter."""
from __future__ import annotations

import math

import numpy as np
import pytest

from rotorcosim.components.bearing import static
from rotorcosim.components.bearing.component import BallBearing
from rotorcosim.components.bearing.geometry import BEARINGS, DN_LIMIT, build_geometry, speed_limit
from rotorcosim.components.bearing.spinning import SpinningBearing
from rotorcosim.components.contract import ContractError

RPM = math.pi / 30.0


def test_speed_limit_is_the_dn_limit():
    assert speed_limit(0.0508) / RPM == pytest.approx(DN_LIMIT / 50.8)
    assert speed_limit(0.0838) / RPM == pytest.approx(29832.9, abs=0.1)


@pytest.mark.parametrize("bearing", [0, 5])
def test_preload_offset_over_the_whole_range_against_the_direct_solve(bearing):
    g = build_geometry(bearing)
    top = 1.5 * speed_limit(BEARINGS[bearing]["bore_mm"] * 1e-3)
    rest = static.preload_offset(g, 0.0)[0]
    signs = set()
    for w in np.linspace(0.0, top, 9):
        Fc = g.centrifugal_force(w)
        # from a guess far off (the secant fails, the bracket takes over) and from the rest state's
        for guess in (rest, -3.0 * rest):
            z = static.axisymmetric_preload_offset(g, Fc, guess)
            z_direct, st = static.preload_offset(g, Fc)
            # the direct solve stops at a force residual of 1e-9 of the preload: ~1e-14 m of offset
            assert z == pytest.approx(z_direct, abs=1e-8 * rest), (w / RPM, z, z_direct)
        signs.add(z > 0)
        # the ball's own equilibrium at that offset (radial and axial), and the preload carried
        radial = st.Q_e * np.cos(st.alpha_e) - st.Q_i * np.cos(st.alpha_i)
        assert np.allclose(radial, Fc, atol=1e-6 * max(Fc, 1.0))
        assert g.Z * st.Q_i[0] * np.sin(st.alpha_i[0]) == pytest.approx(g.preload, rel=1e-8)
    assert signs == {True, False} if bearing == 5 else True in signs


def test_spinning_bearing_sets_up_up_to_its_limit():
    """Up to the speed limit the speed-following bearing sets up (its table stops at the limit); bearing 0 at
    40 000 rev/min ended in scipy's 'f(a) and f(b) must have different signs' before the bracket followed z0."""
    for bearing, rpm in ((0, 40000.0), (0, 49000.0), (5, 22000.0), (5, 29800.0)):
        b = SpinningBearing("brg", {"bearing": bearing, "omega": rpm * RPM})
        b.setup(0.0)
        assert b.table_top <= b.omega_max
        assert np.isfinite(b.preload_offset(b.table_top))


@pytest.mark.parametrize("cls", [BallBearing, SpinningBearing])
def test_speed_above_the_limit_is_one_line(cls):
    b = cls("bearing3", {"bearing": 5, "omega": 31000.0 * RPM})
    with pytest.raises(ContractError) as exc:
        b.setup(0.0)
    msg = str(exc.value)
    assert "\n" not in msg
    for word in ("bearing3.omega", "31000 rev/min", "29833 rev/min", "83.8 mm", "dn_limit"):
        assert word in msg


def test_a_failed_solve_names_bearing_speed_and_parameter(monkeypatch):
    from rotorcosim.components.bearing import component

    def fail(g, Fc):
        raise RuntimeError("static equilibrium did not converge (residual 1.0e+01 N)")

    monkeypatch.setattr(component, "preload_offset", fail)
    b = BallBearing("bearing7", {"bearing": 0, "omega": 20000.0 * RPM, "preload": 900.0})
    with pytest.raises(ContractError) as exc:
        b.setup(0.0)
    msg = str(exc.value)
    assert "\n" not in msg
    for word in ("bearing7", "20000 rev/min", "preload = 900 N", "did not converge"):
        assert word in msg
