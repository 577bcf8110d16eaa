"""ROSS itself (the test extra installs ross-rotordynamics): its example rotors, live, to rotorcosim and back.

Peer code as the reference: ROSS's own run_critical_speed (tight rtol) and run_unbalance_response on the same
rotor. The bounds: forward synchronous critical speeds within 0.1 %, unbalance response within 0.5 %."""
from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

from rotorcosim.components.rotor import critical, model as fem, response
from rotorcosim.interop import from_ross, to_ross, write_engine


@pytest.fixture(scope="module")
def rs():
    """ROSS, imported when a test of this module runs, not when the suite is collected (~7 s of CPU)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")     # ROSS's dependency ccp warns that it finds no REFPROP library
        import ross

    return ross


def _ross_roots(rotor) -> list[tuple[float, str]]:
    """ROSS's critical speeds [rev/min] with its whirl labels, ascending (its Newton search, converged far below
    the 0.1 % compared)."""
    cs = rotor.run_critical_speed(num_modes=12, rtol=1e-8)
    return sorted((float(w) * 30 / math.pi, str(d)) for w, d in zip(np.asarray(cs.wn()), cs.whirl_direction))


def _assert_forward(ours, roots, rtol: float) -> None:
    """Our forward critical speeds ``ours`` against ROSS's ``roots`` (:func:`_ross_roots`): each of ours is one of
    ROSS's critical speeds, and each that ROSS labels forward up to our largest is one of ours. ROSS's label of a
    mode whose orbit is nearly circular is a rounding's: rotor_example's 2 868 rev/min mode is "Forward" in one
    process and "Mixed" in another (numpy 2.4, scipy 1.17), so a root's label alone does not decide."""
    speeds = np.array([r for r, _ in roots])
    for w in ours:
        assert np.min(np.abs(speeds / w - 1)) < rtol, (w, roots)
    for r, d in roots:
        if d == "Forward" and r <= max(ours) * (1 + rtol):
            assert np.min(np.abs(np.asarray(ours) / r - 1)) < rtol, (r, ours)


@pytest.fixture(scope="module")
def example_rpm(rs):
    """``example_rpm(name)``: ROSS's critical speeds of its example rotor ``name`` (:func:`_ross_roots`), searched once for
    the tests of this module that compare with them (the search is most of their cost)."""
    found: dict[str, list[float]] = {}

    def get(name: str) -> list[float]:
        if name not in found:
            found[name] = _ross_roots(getattr(rs, name)())
        return found[name]

    return get


@pytest.mark.parametrize("example", ["rotor_example", "coaxrotor_example"])
def test_ross_example_round_trip(tmp_path, example, rs, example_rpm):
    rotor = getattr(rs, example)()
    engine = from_ross(rotor)
    write_engine(engine, tmp_path / "engine.toml")
    m = fem.load(tmp_path / "engine.toml")
    ours = critical.synchronous_critical_speeds(m, None, n=2, max_rpm=1e6)["forward_synchronous_rpm"]
    _assert_forward(ours, example_rpm(example), rtol=1e-3)
    nd = int(rotor.disk_elements[0].n)
    spool, k = next([s, i] for s, sp in engine["spool"].items() for i in range(len(sp["z_mm"]))
                    if sum(len(v["z_mm"]) for v in list(engine["spool"].values())[:list(engine["spool"]).index(s)])
                    + i == nd)
    for rpm in (0.7 * ours[0], 1.6 * ours[0]):
        W = rpm * math.pi / 30
        R = np.asarray(rotor.run_unbalance_response(nd, 1e-3, 0.0, frequency=np.array([W])).forced_resp)[:, 0]
        X = response.unbalance_response(m, None, (spool, k), 1e-3 * W * W, rpm)
        for d in (0, 1):
            assert abs(abs(X[m.info["dof"](spool, k, d)]) / abs(R[nd * rotor.number_dof + d]) - 1) < 5e-3


@pytest.mark.parametrize("example", ["rotor_example", "coaxrotor_example"])
def test_ross_to_rotorcosim_and_back_to_ross(example, rs, example_rpm):
    """The way back: to_ross of the imported engine (a Rotor, or a CoAxialRotor for two spools) has ROSS's own
    forward critical speeds of the original rotor, by ROSS's computation on both."""
    rotor = getattr(rs, example)()
    back = to_ross(from_ross(rotor))
    assert type(back) is type(rotor)
    assert np.allclose([r for r, _ in _ross_roots(back)], [r for r, _ in example_rpm(example)], rtol=1e-6)


def test_compressor_example_live_imports_as_its_saved_file(rs):
    """ROSS's compressor_example (layered sections, seals and a bearing with speed-dependent, cross-coupled
    coefficients), live, gives the engine its saved file gives (whose critical speeds equal ROSS's:
    test_ross_compressor.py)."""
    from pathlib import Path

    live = from_ross(rs.compressor_example())
    saved = from_ross(Path(__file__).with_name("data") / "compressor_example.toml")
    for e in (live, saved):
        e["engine"].pop("name"), e["engine"].pop("source")
    assert live["spool"]["shaft"]["layers"] == saved["spool"]["shaft"]["layers"]
    assert live == saved


def test_to_ross_gives_rosss_critical_speeds_of_the_linearised_engine(tmp_path):
    """The textbook engine of new-engine, its co-simulated bearings linearised (contacts, journal, O-ring, film),
    in ROSS: ROSS's forward critical speeds of the undamped rotor equal rotorcosim's critical-speeds within
    0.1 %."""
    from rotorcosim.cases.blade_loss import critical_speeds, new_engine
    from rotorcosim.master.api import load_scenario

    engine, scenario = new_engine.new_engine(tmp_path / "e")[:2]   # engine.toml, blade_loss.toml (then rundown.toml)
    rotor = to_ross(engine, scenario=scenario, damped=False)
    ours = critical_speeds.critical_speeds(str(engine), count=2, max_rpm=1e6,
                                           scenario=load_scenario(scenario))["forward_synchronous_rpm"]
    _assert_forward(ours, _ross_roots(rotor), rtol=1e-3)


def test_to_ross_refuses_a_casing_by_name():
    with pytest.raises(ValueError, match="casing shell"):
        to_ross(fem.DEFAULT_FILE)


def test_compressor_example_back_to_ross_has_rosss_matrices_at_every_speed(rs):
    """The way back for layered sections and coefficient tables: to_ross of the imported compressor has ROSS's
    own mass, gyroscopic, stiffness and damping matrices of the original, the bearings' and seals' coefficients
    taken at several speeds (ROSS's assembly on both sides)."""
    r = rs.compressor_example()
    b = to_ross(from_ross(r))
    assert b.ndof == r.ndof and len(b.shaft_elements) == len(r.shaft_elements)
    for A, B in ((b.M(), r.M()), (b.G(), r.G())):
        assert np.allclose(A, B, rtol=0, atol=1e-12 * np.abs(B).max())
    for w in (300.0, 1000.0, 1500.0, 2200.0):                 # rad/s, within and beyond the tables' speeds
        for A, B in ((b.K(w), r.K(w)), (b.C(w), r.C(w))):
            assert np.allclose(A, B, rtol=0, atol=1e-10 * np.abs(B).max())


@pytest.mark.slow
def test_to_ross_of_a_fused_engine_gives_rosss_critical_speeds_intact_and_broken(tmp_path):
    """(~60 s of CPU: ROSS's critical-speed search, twice; slow.) The textbook engine with bearing #0's housing on a fuse (1.5 kg; 1e9 N/m intact, 1e7 N/m broken) in ROSS
    (the housing a PointMass, the fuse a BearingElement to the pedestal's node): ROSS's forward critical speeds
    of the undamped rotor equal rotorcosim's with the fuse intact and with it broken (fuse_states) within 0.1 %;
    the broken fuse lowers the first."""
    from rotorcosim.cases.blade_loss import critical_speeds, new_engine
    from rotorcosim.master.api import load_scenario

    engine, scenario = new_engine.new_engine(tmp_path / "e")[:2]
    engine.write_text(engine.read_text() + "\n[fuse.0]\nhousing_mass_kg = 1.5\nk_intact = 1.0e9\n"
                      "damping = 2000.0\nbreak_load_N = 600.0\nk_broken = 1.0e7\n")
    ours = critical_speeds.critical_speeds(str(engine), count=2, max_rpm=1e6, scenario=load_scenario(scenario))
    for stage, speeds in ((0, ours["forward_synchronous_rpm"]),
                          (1, ours["fuse_states"][0]["forward_synchronous_rpm"][:2])):
        _assert_forward(speeds, _ross_roots(to_ross(engine, scenario=scenario, damped=False, fuse_stage=stage)),
                        rtol=1e-3)
    assert ours["fuse_states"][0]["forward_synchronous_rpm"][0] < 0.9 * ours["forward_synchronous_rpm"][0]


@pytest.mark.parametrize("example", ["rotor_example_with_damping", "rotor_example_6dof"])
def test_element_options_go_to_ross_and_back(example, rs):
    """ROSS's rotors with shaft element options (rotor_example_with_damping: Rayleigh alpha = 8.0501 1/s,
    beta = 1e-5 s on every element; rotor_example_6dof: Euler-Bernoulli elements without rotary inertia) come back
    from to_ross of their import with ROSS's own modes: natural frequencies and logarithmic decrements of
    run_modal at 1 000 rev/min, by ROSS's computation on both, within 1e-6 (ROSS's sparse eigensolver moves the
    log decs' 9th digit from process to process)."""
    rotor = getattr(rs, example)()
    back = to_ross(from_ross(rotor))
    w = 1000.0 * math.pi / 30
    a, b = rotor.run_modal(w, num_modes=12), back.run_modal(w, num_modes=12)
    assert np.allclose(b.wn, a.wn, rtol=1e-6)
    assert np.allclose(b.log_dec, a.log_dec, rtol=1e-6, atol=1e-9)
    assert max(a.log_dec) > 0.1 if example == "rotor_example_with_damping" else np.allclose(a.log_dec, 0, atol=1e-9)
