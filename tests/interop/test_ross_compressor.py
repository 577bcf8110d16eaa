"""ROSS's compressor_example (layered shaft sections, seals and a bearing with speed-dependent, cross-coupled
coefficients) imported without ROSS from the file ROSS 2.3 saved: its critical speeds equal ROSS's own
run_critical_speed within 0.1 % (peer code: data/ross_compressor_reference.json, computed by ROSS 2.3,
tests/interop/make_ross_compressor_reference.py). Both of ROSS's definitions, the fixed points in speed of the
damped natural frequency |lambda| (wn) and of the damped frequency Im lambda (wd), the coefficients taken at each
speed. ROSS's modes are all lateral (whirl forward, backward or mixed: its mixed mode is one of our backward
ones by the orbits' energy). And the other places these engines go: the co-simulated rotor takes the tables at its speed;
ROSS's coaxial rotor's bearings attach to their pedestals; an intershaft bearing is refused in one line."""
from __future__ import annotations

import json
from pathlib import Path

import pytest
from threadpoolctl import threadpool_limits

from rotorcosim.components.rotor import critical, engine_check, model as fem
from rotorcosim.interop import from_ross, write_engine
from rotorcosim.master.cli import main

DATA = Path(__file__).with_name("data")
REF = json.loads((DATA / "ross_compressor_reference.json").read_text())


@pytest.fixture(scope="module")
def compressor(tmp_path_factory):
    engine = from_ross(DATA / REF["file"])
    path = tmp_path_factory.mktemp("c") / "engine.toml"
    write_engine(engine, path)
    return engine, fem.load(path)


def test_layers_and_coefficient_tables_are_carried(compressor):
    engine, m = compressor
    (spool,) = engine["spool"].values()
    assert len(spool["layers"]) == 36                     # ROSS's 36 layered sections (the sleeves)
    tables = [s for s in engine["support"] if "speed_rpm" in s]
    assert len(tables) == len(engine["support"]) == len(m.info["speed_supports"])
    seal = next(s for s in tables if s["name"] == "Seal 10")
    assert len(seal["speed_rpm"]) == len(seal["kxy"]) == 9 and seal["kxy"][0] == -seal["kyx"][0] != 0
    assert engine_check.problems(engine) == []


@pytest.mark.parametrize("natural", ["wn", "wd"])
def test_critical_speeds_equal_rosss_within_0_1_percent(compressor, natural):
    _, m = compressor
    with threadpool_limits(limits=1):
        ours = critical.speed_dependent_critical_speeds(m, None, 22000.0, natural=natural)
    ref = REF[f"{natural}_rpm"]
    assert len(ours) == len(ref)
    for r in ref:
        best = min(ours, key=lambda o: abs(o["rpm"] / r - 1))
        assert abs(best["rpm"] / r - 1) < 1e-3, (r, ours)
    for o, (r, w) in zip(sorted(ours, key=lambda o: o["rpm"]), sorted(zip(ref, REF["whirl"]))):
        assert w == "Mixed" or o["whirl"] == w.lower(), (o, r, w)


def test_the_co_simulated_rotor_takes_the_tables_at_its_speed(compressor, tmp_path):
    """The co-simulated rotor of the compressor (with an unbalance and one co-simulated bearing's ports added) at
    12 000 rev/min, away from the file's 10 000: its reduced stiffness and damping are the projection on its basis
    of the full matrices with every table at that speed, as the linear engine takes them (speed_support_delta),
    the seals' cross-coupled terms included (model.projected_support_delta projects support by support)."""
    import copy

    import numpy as np

    from rotorcosim.components.rotor.component import full_model, reduced_model

    engine = copy.deepcopy(compressor[0])
    engine["pedestal"] = {"hb": {"mass": 1.0, "k": 1e3}}
    engine["attach"] = {"unbalance": {"node": ["shaft", 20]}, "bearing0": {"node": ["shaft", 30], "housing": "hb"}}
    path = tmp_path / "e.toml"
    write_engine(engine, path)
    w = 12000.0 * fem.RPM
    red = reduced_model(str(path), 12, w, w)
    full = full_model(str(path), w, w)
    dK, dC = fem.speed_support_delta(full, w)
    B = red["basis"]
    assert not np.allclose(dK, dK.T)          # the seals' cross-coupled terms moved with the speed
    K = B.T @ (full.K + dK) @ B
    C = B.T @ (full.C + dC + w * (full.G_pt + full.G_gg)) @ B
    assert np.allclose(red["K"], K, rtol=0, atol=1e-9 * np.abs(K).max())
    assert np.allclose(red["C"], C, rtol=0, atol=1e-9 * np.abs(C).max())


def test_coaxial_rotor_bearings_attach_to_their_pedestals(tmp_path, capsys):
    """ROSS's coaxial rotor holds its inner shaft's ends by bearings linked to pedestals (point masses on their
    own bearings to ground): those pedestals become the co-simulated bearings' housings."""
    out = tmp_path / "coax.toml"
    parts = tmp_path / "parts.toml"
    parts.write_text("".join(f"[bearing.{i}]\nballs = 21\nball_diameter_mm = 8.73\nbore_mm = 50.8\n"
                             f"outside_diameter_mm = 90.0\nwidth_mm = 20.0\ncontact_angle_deg = 15.0\n"
                             f"preload_N = 800.0\n[damper.{i}]\nradius_mm = 80.0\nlength_mm = 32.0\n"
                             f"clearance_mm = 0.635\nsupply_pressure_MPa = 0.2\nk_spring = 5.254e6\n"
                             f"[rubring.{i}]\nclearance_mm = 0.508\n" for i in (0, 5)))
    assert main(["import-ross", str(DATA / "coaxrotor_example.toml"), "--out", str(out), "--attach", "0=0,5=10",
                 "--speed", "16000", "--parts", str(parts)]) == 0
    capsys.readouterr()
    data, _ = fem.load_data(out)
    assert data["attach"]["bearing0"] == {"node": ["inner", 0], "housing": "n18"}
    assert data["attach"]["bearing5"] == {"node": ["inner", 10], "housing": "n19"}
    assert data["pedestal"]["n18"]["mass"] == 20.0              # ROSS's point mass
    assert not any(s["name"] in ("Bearing 0", "Bearing 1") for s in data.get("support", []))
    assert engine_check.problems(data) == []
    m = fem.load(out)
    assert {"brg0", "brg5", "housing0", "housing5"} <= set(m.ports)


def test_an_intershaft_bearing_is_refused_in_one_line(tmp_path, capsys):
    out = tmp_path / "coax.toml"
    rc = main(["import-ross", str(DATA / "coaxrotor_example.toml"), "--out", str(out), "--attach", "0=8"])
    err = capsys.readouterr().err
    assert rc == 2 and len(err.strip().splitlines()) == 1 and not out.exists()
    assert "intershaft bearing" in err and "attach a bearing to ground or to a pedestal instead (ROSS nodes 0, 10" in err
