"""The one engine model: the linear engine behind ``critical-speeds`` and the calibration is the
co-simulated system linearised, and its forced response is the co-simulation's."""
import math

import pytest

from rotorcosim.components.rotor import model as fem
from rotorcosim.cases.blade_loss import linear_engine
from rotorcosim.master.cli.run import execute, resolve
from rotorcosim.cases.blade_loss.results import apply_unbalance


@pytest.fixture(scope="module")
def engine():
    full = fem.load()
    return full, linear_engine.supports()


def test_supports_are_the_simulated_components(engine):
    """Film damping of the damper component, linearised about the centred journal, against the short-damper
    full-film (2 pi) value pi mu R L^3 / c^3 (physics-notes; L/D = 0.2 is near the short limit, which slightly
    overestimates); the journal mass and the O-ring are the bearing's and the damper's parameters."""
    from rotorcosim.components.damper.viscosity import sae30_viscosity

    _, sup = engine
    mu = sae30_viscosity(30.0 + 273.15)
    for key, (R, L) in (("h0", (0.08, 0.032)), ("h5", (0.10, 0.04))):
        s = sup[key]
        short = math.pi * mu * R * L ** 3 / 0.635e-3 ** 3
        assert 0.95 * short < s["c_film"] < short
        assert s["oil_temperature_C"] == 30.0
    # outer race + 5 mm journal ring (bearings.toml journal_wall_mm), by hand: 7800 pi/4 ((90^2 - 79.13^2) 20 +
    # (160^2 - 150^2) 32) mm^3 = 0.833 kg; #5 7800 pi/4 ((110^2 - 106.43^2) 16 + (200^2 - 190^2) 40) = 1.031 kg
    assert sup["h0"]["m_journal"] == pytest.approx(0.833, rel=2e-3)
    assert sup["h5"]["m_journal"] == pytest.approx(1.031, rel=2e-3)
    assert sup["h0"]["k_spring"] == sup["h5"]["k_spring"] == 5.254e6


def test_linear_whirl_at_712N_matches_the_cosimulation(engine, tmp_path):
    """A short thermo-mechanical run (monolithic, 0.1 s: the 712 N response is steady within 0.5 % from 0.08 s,
    measured to 0.2 s) against the linear engine's harmonic response at the co-simulation's force (blade loss
    and residual unbalance in quadrature) and the oil temperature it runs at (30 C): whirl at #0 and #5 within
    10 %."""
    full, sup = engine
    sc = resolve("blade_loss")
    apply_unbalance(sc, 712.0)
    from rotorcosim.master.scenario.build import create_component

    rotor = create_component(sc.components["rotor"])
    F_res = rotor.p["F_residual"]
    assert rotor.p["unbalance_phase"] == pytest.approx(math.pi / 2)      # quadrature: amplitudes add as below
    s = execute(sc, tmp_path, "monolithic", 0.1, figures=False, quiet=True)
    lin = linear_engine.response(full, sup, math.hypot(712.0, F_res))
    for k in ("0", "5"):
        ours = s["bearings"][k]
        assert abs(ours["T_sfd_oil_C"] - 30.0) < 1.0              # the film's linearisation temperature holds
        assert ours["whirl_amplitude_mm"] == pytest.approx(lin[k]["whirl_mm"], rel=0.10)
