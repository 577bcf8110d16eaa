"""A ROSS rotor on bearings whose coefficients change with speed and are cross-coupled (ROSS's BearingElement with
``frequency``: the usual fluid-film bearing of a ROSS model), co-simulated: the time-domain rotor takes the
supports' coefficients at its speed (components/rotor/component.py ``reduced_model``; the speed-following
variant at the speed of its inputs, components/rotor/spinning.py).

Peer code as the reference: ROSS's own run_unbalance_response of the same rotor. The time-domain rotor is
integrated from rest under the unbalance and its steady orbit taken as the synchronous Fourier component of the
last 4 s (a whole number of revolutions, after 4 s of decay); the bound is 0.2 % (measured 0.03-0.05 %). The
rotor_example's bearings are replaced by tables of kxx 1e6 -> 4e6 N/m over 0 -> 1000 rad/s (cross-coupled
kxy = -kyx, c 1400-2000 N s/m), steep enough that the coefficients frozen at another speed miss by more than
that (checked below on ROSS's own responses)."""
from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

from rotorcosim.components.rotor import response
from rotorcosim.components.rotor import model as fem
from rotorcosim.components.rotor.component import Rotor
from rotorcosim.components.rotor.spinning import SpinningRotor
from rotorcosim.interop import from_ross, write_engine

RPM = math.pi / 30
#: the engine file's speed (the rotor component's reference speed) [rev/min] and the unbalance force there [N]
SPEED_RPM, FORCE = 1500.0, 100.0
DISK, PROBE = 2, 3        # ROSS nodes: the unbalance at the first disk, the orbit read at the next node


@pytest.fixture(scope="module")
def rs():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")     # ROSS's dependency ccp warns that it finds no REFPROP library
        import ross

    return ross


def _bearings(rs, frozen_at: float | None = None):
    """rotor_example's two bearings as speed tables (``frozen_at`` [rad/s]: their values there, constant)."""
    tables = {"kxx": [1e6, 4e6], "kyy": [8e5, 3e6], "kxy": [5e4, 1.5e5], "kyx": [-5e4, -1.5e5],
              "cxx": [2000.0, 1500.0], "cyy": [1800.0, 1400.0]}
    freq = [0.0, 1000.0]
    if frozen_at is not None:
        tables = {k: float(np.interp(frozen_at, freq, v)) for k, v in tables.items()}
    out = []
    for b in rs.rotor_example().bearing_elements:
        out.append(rs.BearingElement(n=b.n, **tables, **({} if frozen_at is not None else {"frequency": freq}),
                                     tag=f"bearing {b.n}"))
    return out


@pytest.fixture(scope="module")
def rotor(rs):
    r0 = rs.rotor_example()
    return rs.Rotor(r0.shaft_elements, r0.disk_elements, _bearings(rs))


@pytest.fixture(scope="module")
def engine_file(rotor, tmp_path_factory):
    """The rotor imported, with the unbalance at the disk and a co-simulated bearing's ports at the probe node
    (its housing a pedestal of its own, its force input left at zero: the orbit is the linear rotor's)."""
    e = from_ross(rotor, speed_rpm=SPEED_RPM)
    assert all("speed_rpm" in s and s["kxy"] for s in e["support"])
    e["pedestal"] = {"hb": {"mass": 1.0, "k": 1e3}}
    e["attach"] = {"unbalance": {"node": ["shaft", DISK]}, "bearing0": {"node": ["shaft", PROBE], "housing": "hb"}}
    path = tmp_path_factory.mktemp("engine") / "engine.toml"
    write_engine(e, path)
    return path


def _ross_orbit(rotor, rpm: float) -> np.ndarray:
    """ROSS's |x|, |y| at the probe node under the unbalance at ``rpm`` (m e = FORCE / W_ref^2, as the component
    scales its force with the square of the speed)."""
    me = FORCE / (SPEED_RPM * RPM) ** 2
    R = np.asarray(rotor.run_unbalance_response(DISK, me, 0.0, frequency=np.array([rpm * RPM])).forced_resp)[:, 0]
    return np.abs(R[PROBE * rotor.number_dof: PROBE * rotor.number_dof + 2])


def _steady_orbit(comp, w: float, h: float = 2e-4, settle: float = 4.0, window: float = 4.0) -> np.ndarray:
    comp.setup(0.0)
    t, ts, xs = 0.0, [], []
    for _ in range(int(round((settle + window) / h))):
        comp.do_step(t, h)
        t += h
        if t > settle:
            ts.append(t)
            xs.append(np.array(comp.y["X_brg0"][:2]))
    n = int(math.floor((ts[-1] - ts[0]) * w / (2 * math.pi)) * 2 * math.pi / w / h)
    ts, xs = np.array(ts[-n:]), np.array(xs[-n:])
    return np.abs(2.0 * (xs * np.exp(-1j * w * ts)[:, None]).mean(axis=0))


def _parameters(path) -> dict:
    w = SPEED_RPM * RPM
    return {"model_file": str(path), "omega_pt": w, "omega_gg": w, "F_unbalance": FORCE, "t_blade_loss": 0.0}


def test_the_frequency_response_takes_the_tables_at_its_speed(rotor, engine_file):
    """The linear engine's unbalance response (response.py) equals ROSS's at the file's speed and away from it."""
    m = fem.load(engine_file)
    dof = m.info["dof"]
    for rpm in (SPEED_RPM, 900.0):
        X = response.unbalance_response(m, None, ("shaft", DISK), FORCE * (rpm / SPEED_RPM) ** 2, rpm)
        ours = np.abs([X[dof("shaft", PROBE, 0)], X[dof("shaft", PROBE, 1)]])
        assert ours == pytest.approx(_ross_orbit(rotor, rpm), rel=1e-9)


def test_the_constant_speed_rotor_takes_the_tables_at_its_speed(rotor, engine_file):
    ours = _steady_orbit(Rotor("rotor", _parameters(engine_file)), SPEED_RPM * RPM)
    assert ours == pytest.approx(_ross_orbit(rotor, SPEED_RPM), rel=2e-3)


def test_the_speed_following_rotor_takes_the_tables_at_its_input_speed(rs, rotor, engine_file):
    """At 900 rev/min, its input speed, far from the file's 1 500: ROSS's orbit there within 0.2 %, where the
    coefficients frozen at 1 500 rev/min give an orbit more than 1 % away (ROSS's own, on bearings of those
    values)."""
    w = 900.0 * RPM
    comp = SpinningRotor("rotor", _parameters(engine_file))
    for port, v in (("Omega_pt", w), ("Omega_gg", w), ("dOmega_pt", 0.0)):
        comp.u[port] = np.array([v])
    ours = _steady_orbit(comp, w)
    ref = _ross_orbit(rotor, 900.0)
    assert ours == pytest.approx(ref, rel=2e-3)
    r0 = rs.rotor_example()
    frozen = rs.Rotor(r0.shaft_elements, r0.disk_elements, _bearings(rs, frozen_at=SPEED_RPM * RPM))
    assert np.max(np.abs(_ross_orbit(frozen, 900.0) / ref - 1)) > 1e-2
