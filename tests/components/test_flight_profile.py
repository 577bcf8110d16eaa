"""The diversion profile's windmilling law (components/spool: atmosphere.py, flight_profile.py, windmill.py): the
ISA against the published table of ICAO Doc 7488 / U.S. Standard Atmosphere 1976, the two forms of a profile giving
the same flight condition, the spool's torque law at a changed flight condition against the analytic solution of
J dW/dt = -c (W - W_wm)^2 with the similarity-scaled c and W_wm, and every bad profile named on one line."""
from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from rotorcosim.components.contract import ContractError
from rotorcosim.components.spool.atmosphere import isa, total_ratios
from rotorcosim.components.spool.component import Spool
from rotorcosim.components.spool.flight_profile import read_profile
from rotorcosim.components.spool.profile import RPM
from rotorcosim.components.spool.windmill import referred_windmill_fraction, scales

SHIPPED = Path(__file__).parents[2] / "scenarios" / "diversion_180min.csv"
TORQUES = ("T_drag1", "T_drag2", "T_rub1", "T_rub2")


def _write(tmp_path, text, name="p.csv"):
    path = tmp_path / name
    path.write_text(text)
    return str(path)


@pytest.mark.parametrize("h, T, p, rho", [
    # U.S. Standard Atmosphere 1976 (NOAA-S/T 76-1562): the pressures at its layers' bases (geopotential
    # altitude), the densities of its table there
    (0.0, 288.150, 101325.0, 1.2250),
    (11000.0, 216.650, 22632.06, 0.36392),
    (20000.0, 216.650, 5474.889, 0.088035),
])
def test_isa_against_the_standard_atmosphere_table(h, T, p, rho):
    t, pp, r = isa(h)
    assert float(t) == pytest.approx(T, abs=1e-3)
    assert float(pp) == pytest.approx(p, rel=2e-4)
    assert float(r) == pytest.approx(rho, rel=2e-4)


def test_both_forms_of_a_profile_give_the_same_condition(tmp_path):
    """An altitude and Mach profile and the same flight as true airspeed and density (the ISA's density and speed of
    sound there, computed here from the table's formulas): the same Mach number, theta and delta."""
    h = np.array([10668.0, 6096.0, 457.2])
    mach = np.array([0.8, 0.65, 0.25])
    T, p, rho = isa(h)
    tas = mach * np.sqrt(1.4 * 287.05287 * T)
    a = read_profile(_write(tmp_path, "time_s, altitude_ft, mach\n" + "".join(
        f"{t}, {float(x) / 0.3048!r}, {float(m)!r}\n" for t, x, m in zip((0, 60, 600), h, mach))))
    b = read_profile(_write(tmp_path, "# comment\ntime_s, airspeed_m_s, density_kg_m3  # columns\n" + "".join(
        f"{t}, {float(v)!r}, {float(r)!r}\n" for t, v, r in zip((0, 60, 600), tas, rho)), "b.csv"))
    for x, y in zip(a[1:], b[1:]):
        np.testing.assert_allclose(x, y, rtol=1e-9)
    theta, delta = total_ratios(T, p, mach)
    np.testing.assert_allclose(a.theta, theta, rtol=1e-12)
    # theta at M 0.8, 35 000 ft: 0.856, the value blade_loss_rundown.toml's windmill speed was computed with
    assert a.theta[0] == pytest.approx(0.856, abs=1e-3)


def test_windmill_speed_follows_the_correlation_and_torque_the_total_density():
    """At sea level and M 0.2 against M 0.4: twice the referred windmill speed (0.5 M below the knee), times
    sqrt(theta); the torque coefficient as delta / theta (the inlet's total density)."""
    assert referred_windmill_fraction(np.array([0.2, 0.4, 0.8])) == pytest.approx([0.1, 0.2, 0.332])
    T, p, _ = isa(np.zeros(2))
    mach = np.array([0.4, 0.2])
    theta, delta = total_ratios(T, p, mach)
    speed, torque = scales(mach, theta, delta)
    assert speed[1] == pytest.approx(0.5 * np.sqrt(theta[1] / theta[0]), rel=1e-12)
    assert torque[1] == pytest.approx((delta[1] / theta[1]) / (delta[0] / theta[0]), rel=1e-12)


def test_spool_windmills_at_the_scaled_law_analytic(tmp_path):
    """A profile that changes the flight from M 0.8 at 35 000 ft to M 0.3 at 5 000 ft within 1 ms and holds it:
    after the fuel cut J dW/dt = -c (W - W_wm)^2 with W_wm and c scaled by windmill.scales (separable ODE:
    W_wm + D0 / (1 + c D0 t / J)); without a profile the same spool follows the unscaled law bit for bit."""
    path = _write(tmp_path, "time_s, altitude_ft, mach\n0, 35000, 0.8\n0.001, 5000, 0.3\n")
    J, T0, w0, wm = 0.04, 30.0, 16000 * RPM, 4900 * RPM
    prof = read_profile(path)
    speed, torque = scales(prof.mach, prof.theta, prof.delta)
    s = Spool("spool", {"inertia": J, "profile": "torque", "speed_rpm": 16000.0, "t_fuel_cut": 0.1,
                        "windmill_rpm": 4900.0, "aero_torque": T0, "flight_profile": path})
    s.setup(0.0)
    for k in TORQUES:
        s.u[k] = np.array([0.0])
    h = 1e-4
    for i in range(21000):
        s.do_step(i * h, h)
    c, w_wm = T0 / (w0 - wm) ** 2 * torque[-1], wm * speed[-1]
    D0 = w0 - w_wm
    assert s.y["Omega"][0] == pytest.approx(w_wm + D0 / (1.0 + c * D0 * 2.0 / J), rel=1e-4)
    assert w_wm < 0.5 * wm and c > 1.5 * T0 / (w0 - wm) ** 2      # the law did move


def test_shipped_diversion_profile():
    """180 minutes after the 15 s at speed and the one-minute rundown; starts at the rundown scenario's reference,
    M 0.8 at FL350."""
    p = read_profile(str(SHIPPED))
    assert p.t[0] == 0.0 and p.t[-1] == 75.0 + 180 * 60.0
    assert p.mach[0] == 0.8 and p.theta[0] == pytest.approx(0.8566, abs=1e-4)


@pytest.mark.parametrize("text, message", [
    ("time_s, altitude_ft, mach\n0, 35000, 0.8\n10, 30000, 0.7\n10, 20000, 0.6\n",
     r"line 4: time_s = 10 s does not increase"),
    ("time_s, airspeed_m_s, density_kg_m3\n0, 240, 0.38\n60, 200, -0.5\n", r"line 3: density_kg_m3 = -0.5, must be > 0"),
    ("time_s, altitude_m, mach\n0, 25000, 0.8\n", r"altitude_m = 25000, must be within"),
    ("time_s, altitude_m, mach\n0, 10000, 1.2\n", r"mach = 1.2, must be >= 0 and < 1"),
    ("time_s, altitude_m, speed\n0, 10000, 0.8\n", r"columns time_s, altitude_m, speed; accepted"),
    ("time_s, altitude_m, mach\n0, 10000\n", r"line 2: 2 values for the 3 columns"),
    ("time_s, altitude_m, mach\n0, 10000, fast\n", r"line 2: .* is not a row of numbers"),
    ("time_s, altitude_m, mach\n0, nan, 0.8\n", r"non-finite altitude_m"),
    ("# nothing\n", r"no rows"),
    ("time_s, altitude_m, mach\n0, 10000, 0.0\n", r"first row .* Mach number > 0"),
])
def test_bad_profiles_are_one_line_errors_naming_the_parameter(tmp_path, text, message):
    path = _write(tmp_path, text)
    with pytest.raises(ContractError, match=message) as err:
        Spool("spool", {"inertia": 0.04, "profile": "torque", "speed_rpm": 16000.0, "windmill_rpm": 4900.0,
                        "aero_torque": 30.0, "flight_profile": path}).setup(0.0)
    assert "\n" not in str(err.value) and str(err.value).startswith("spool.flight_profile: ")


def test_a_spreadsheets_byte_order_mark_is_dropped_and_other_bytes_named(tmp_path):
    """A profile saved as "CSV UTF-8" by a spreadsheet starts with a byte-order mark: it used to make the header
    ('3 values for the 1 columns \\ufeff'); bytes that are not UTF-8 ended in the codec's message, naming no file."""
    text = "time_s, altitude_ft, mach\n0, 35000, 0.8\n600, 30000, 0.7\n"
    plain = read_profile(_write(tmp_path, text))
    bom = read_profile(_write(tmp_path, "\ufeff" + text, "bom.csv"))
    assert np.array_equal(plain.t, bom.t) and np.array_equal(plain.mach, bom.mach)
    bad = tmp_path / "bad.csv"
    bad.write_bytes(b"\xff\xfetime_s")
    with pytest.raises(ValueError) as err:
        read_profile(str(bad))
    assert str(err.value) == f"flight profile {bad}: not UTF-8 text (byte 0xff at position 0): save it as CSV, UTF-8"
