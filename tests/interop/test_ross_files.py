"""ROSS rotor files (written by ROSS 2.3's Rotor.save) imported without ROSS: the engine they give has ROSS's own
critical speeds and unbalance responses (peer code: the reference numbers in data/ross_reference.json were
computed by ROSS 2.3, tests/interop/make_ross_reference.py), and the files rotorcosim cannot carry are refused
by name."""
from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from rotorcosim.components.rotor import critical, model as fem, response
from rotorcosim.interop import from_ross, write_engine
from rotorcosim.interop.ross_import import RossImportError
from rotorcosim.interop.ross_toml import RossFileError

DATA = Path(__file__).with_name("data")
REF = json.loads((DATA / "ross_reference.json").read_text())


def _engine(tmp_path, name):
    engine = from_ross(DATA / REF[name]["file"])
    path = tmp_path / "engine.toml"
    write_engine(engine, path)
    return engine, fem.load(path)


@pytest.mark.parametrize("name", sorted(n for n in REF if REF[n]["forward_synchronous_rpm"]))
def test_forward_critical_speeds_equal_ross_within_0_1_percent(tmp_path, name):
    """The bound is 0.1 %; the elements are the same beams (rotor_example_6dof: Euler-Bernoulli without rotary
    inertia, as its file says), so they agree far closer. Each of ROSS's is matched to our nearest forward one:
    ROSS labels a nearly circular orbit Forward in one run and not in another."""
    _, m = _engine(tmp_path, name)
    ours = critical.synchronous_critical_speeds(m, None, n=6, max_rpm=1e6)["forward_synchronous_rpm"]
    for b in REF[name]["forward_synchronous_rpm"]:
        assert min(abs(a / b - 1) for a in ours) < 1e-3, (ours, b)


@pytest.mark.parametrize("name", sorted(n for n in REF if "modes_at_first_critical" in REF[n]))
def test_damped_modes_equal_rosss_at_the_first_critical_speed(tmp_path, name):
    """Every whirl mode ROSS's run_modal gives at the first critical speed (its natural frequency |lambda| and
    logarithmic decrement 2 pi zeta / sqrt(1 - zeta^2)) is an eigenvalue of the imported engine's
    lambda^2 M + lambda (C + w G) + K, solved here in its first-order form: rotor_example_with_damping's come
    from its shaft elements' Rayleigh alpha, beta and its bearings' damping (log decs 0.026-0.19), within 1e-6.
    ROSS's modes of no whirl ("None": axial and torsional, which ROSS leaves free and the import holds at the
    first node) are not compared."""
    _, m = _engine(tmp_path, name)
    w = REF[name]["first_critical_rpm"] * 3.141592653589793 / 30
    n = m.K.shape[0]
    A = np.block([[np.zeros((n, n)), np.eye(n)],
                  [-np.linalg.solve(m.M, m.K), -np.linalg.solve(m.M, m.C + w * m.G_pt)]])
    lam = np.linalg.eigvals(A)
    lam = lam[lam.imag > 0]
    compared = 0
    for mode in REF[name]["modes_at_first_critical"]:
        if mode["whirl"] == "None":
            continue
        near = lam[np.argmin(np.abs(np.abs(lam) - mode["wn_rad_s"]))]
        zeta = -near.real / abs(near)
        assert abs(near) == pytest.approx(mode["wn_rad_s"], rel=1e-6)
        assert 2 * np.pi * zeta / np.sqrt(1 - zeta ** 2) == pytest.approx(mode["log_dec"], rel=1e-6, abs=1e-9)
        compared += 1
    assert compared >= 5


@pytest.mark.parametrize("name", sorted(REF))
def test_unbalance_response_at_two_speeds_equals_ross_within_0_5_percent(tmp_path, name):
    engine, m = _engine(tmp_path, name)
    for r in REF[name]["response"]:
        spool, k = _where(engine, r["node"])
        W = r["rpm"] * 3.141592653589793 / 30
        X = response.unbalance_response(m, None, (spool, k), r["me_kgm"] * W * W, r["rpm"])
        for d, key in ((0, "abs_x"), (1, "abs_y")):
            ours = abs(X[m.info["dof"](spool, k, d)])
            assert abs(ours / r[key] - 1) < 5e-3, (r, ours)


def _where(engine, ross_node):
    """The (spool, node) of a ROSS node: spools are numbered on in ROSS's order (the shafts' nodes first)."""
    n = ross_node
    for s, sp in engine["spool"].items():
        count = len(sp["z_mm"])
        if n < count:
            return [s, n]
        n -= count
    raise AssertionError(ross_node)


def _variant(tmp_path, old, new, source="rotor_example.toml"):
    text = (DATA / source).read_text()
    assert old in text
    p = tmp_path / "variant.toml"
    p.write_text(text.replace(old, new, 1))
    return p


@pytest.mark.parametrize("old, new, error, message", [
    ('ross_version = "2.3.0"', 'ross_version = "1.5.0"', RossFileError, "written by ROSS 1.5.0; this importer reads"),
    ('["DiskElement_Disk 0"]', '["MagneticBearingElement_Disk 0"]', RossFileError,
     "is a MagneticBearingElement, which rotorcosim does not carry"),
    ("odr = 0.05", "odr = 0.06", RossImportError, "is tapered"),
    ("kxx = [ 1000000.0,]", "kxx = [ 1000000.0, 2000000.0,]", RossImportError, "but no matching frequency"),
    ("mxx = [ 0,]", "mxx = [ 5.0,]", RossImportError, "added mass mxx is not carried"),
])
def test_files_that_cannot_be_carried_are_named(tmp_path, old, new, error, message):
    with pytest.raises(error, match=message.replace("(", r"\(").replace(")", r"\)")):
        from_ross(_variant(tmp_path, old, new))


def test_speed_dependent_coefficients_at_a_named_speed(tmp_path):
    """Linear interpolation over ROSS's frequency: 1e6 at 0 and 2e6 N/m at 1000 rad/s give 1.5e6 at 500 rad/s."""
    p = _variant(tmp_path, "kxx = [ 1000000.0,]", "kxx = [ 1000000.0, 2000000.0,]\nfrequency = [ 0.0, 1000.0,]")
    e = from_ross(p, speed_rpm_coefficients=500.0 * 30 / 3.141592653589793)
    assert e["support"][0]["kxx"] == pytest.approx(1.5e6, rel=1e-12)


def test_speed_dependent_and_cross_coupled_coefficients_are_carried(tmp_path):
    """A bearing of coefficients over ROSS's frequency becomes a support with a table over speed_rpm (0 and
    1000 rad/s = 9549.3 rev/min), and a cross-coupled one keeps its kxy; at a table's speed the engine has the
    table's value."""
    p = _variant(tmp_path, "kxx = [ 1000000.0,]", "kxx = [ 1000000.0, 2000000.0,]\nfrequency = [ 0.0, 1000.0,]")
    e = from_ross(p)
    s = e["support"][0]
    assert s["speed_rpm"] == pytest.approx([0.0, 1000.0 * 30 / 3.141592653589793])
    assert s["kxx"] == [1e6, 2e6] and s["kyy"] == 8e5
    write_engine(e, tmp_path / "e.toml")
    m = fem.load(tmp_path / "e.toml")
    t = m.info["speed_supports"][0]
    assert fem.support_matrices(t, 1000.0)[0][0, 0] == pytest.approx(2e6)
    e = from_ross(_variant(tmp_path, "kxy = [ 0,]", "kxy = [ 1000.0,]"))
    assert e["support"][0]["kxy"] == 1000.0 and "speed_rpm" not in e["support"][0]


def test_import_ross_command(tmp_path, capsys):
    from rotorcosim.master.cli import main

    out = tmp_path / "engine.toml"
    assert main(["import-ross", str(DATA / "rotor_example.toml"), "--out", str(out)]) == 0
    assert fem.load(out).info["spools"] == {"shaft": 7}
    assert main(["import-ross", str(DATA / "rotor_example.toml"), "--out", str(out)]) == 2
    assert "already exists" in capsys.readouterr().err
    bad = _variant(tmp_path, '["DiskElement_Disk 0"]', '["FooElement_Disk 0"]')
    assert main(["import-ross", str(bad), "--out", str(tmp_path / "no.toml")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "FooElement" in err[0]
    assert not (tmp_path / "no.toml").exists() and not list(tmp_path.glob(".no.toml*"))


def test_attach_makes_two_ross_bearings_the_cosimulated_ones(tmp_path):
    """--attach 0=0,5=6: the ROSS bearings at nodes 0 and 6 become pedestals h0/h5 with their coefficients; the
    drive and axial node moves off them; the engine builds every port of the rotor component."""
    e = from_ross(DATA / "rotor_example.toml", attach={"bearing0": 0, "bearing5": 6})
    assert "support" not in e
    assert e["pedestal"]["h0"] == {"mass": 3.0, "kxx": 1e6, "kyy": 8e5, "c": 0.0}
    assert e["spool"]["shaft"]["drive_node"] == 5
    write_engine(e, tmp_path / "e.toml")
    m = fem.load(tmp_path / "e.toml")
    fem.require_ports(m, ("brg0", "brg5", "housing0", "housing5", "rub0", "rub5", "unbalance"))


def test_attach_takes_any_bearing_ids(tmp_path, capsys, monkeypatch):
    """--attach with one id of another name: that ROSS bearing becomes pedestal h<ID> under bearing<ID> (and its
    rub ring), the other stays a linear support; the rotor component's ports follow (attach.py). A bad id is one
    line."""
    from rotorcosim.components.rotor.component import Rotor
    from rotorcosim.master.cli import main

    e = from_ross(DATA / "rotor_example.toml", attach={"bearingfront": 0})
    assert list(e["attach"])[:2] == ["bearingfront", "rubringfront"] and "hfront" in e["pedestal"]
    assert len(e["support"]) == 1
    write_engine(e, tmp_path / "e.toml")
    rotor = Rotor("rotor", {"model_file": str(tmp_path / "e.toml")})
    ports = {v.name for v in rotor.variables if v.causality == "input"}
    assert ports == {"F_brgfront", "F_sfd_housingfront", "F_rub_housingfront", "F_rubfront"}
    # what each attached part is comes from --parts (ROSS describes no ball bearing): the file check-engine accepts
    assert main(["import-ross", str(DATA / "rotor_example.toml"), "--out", str(tmp_path / "n.toml"),
                 "--attach", "1=0,2=6"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "--attach without --parts FILE" in err[0] and not (tmp_path / "n.toml").exists()
    # every missing table and required key is named, per attached id
    assert "[bearing.1] balls, ball_diameter_mm, bore_mm" in err[0] and "[damper.2] radius_mm" in err[0]
    assert "[rubring.2] clearance_mm" in err[0]
    half = tmp_path / "half.toml"
    half.write_text("[bearing.1]\nballs = 21\n")
    assert main(["import-ross", str(DATA / "rotor_example.toml"), "--out", str(tmp_path / "n.toml"),
                 "--attach", "1=0,2=6", "--parts", str(half)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and f"--parts {half}: the co-simulated parts lack [bearing.1] ball_diameter_mm" in err[0]
    assert not (tmp_path / "n.toml").exists()
    parts = tmp_path / "parts.toml"
    parts.write_text("".join(f"[bearing.{i}]\nballs = 21\nball_diameter_mm = 8.73\nbore_mm = 50.8\n"
                             f"outside_diameter_mm = 90.0\nwidth_mm = 20.0\ncontact_angle_deg = 15.0\n"
                             f"preload_N = 800.0\n[damper.{i}]\nradius_mm = 80.0\nlength_mm = 32.0\n"
                             f"clearance_mm = 0.635\nsupply_pressure_MPa = 0.2\nk_spring = 5.254e6\n"
                             f"[rubring.{i}]\nclearance_mm = 0.508\n" for i in (1, 2)))
    assert main(["import-ross", str(DATA / "rotor_example.toml"), "--out", str(tmp_path / "x.toml"),
                 "--attach", "1=0,2=6", "--parts", str(parts)]) == 0
    assert [k for k in fem.load_data(tmp_path / "x.toml")[0]["attach"] if k.startswith("b")] == ["bearing1", "bearing2"]
    assert fem.load_data(tmp_path / "x.toml")[0]["damper"]["2"]["clearance_mm"] == 0.635
    capsys.readouterr()
    monkeypatch.chdir(tmp_path)
    assert main(["check-engine", str(tmp_path / "x.toml")]) == 0
    capsys.readouterr()
    assert main(["import-ross", str(DATA / "rotor_example.toml"), "--out", str(tmp_path / "y.toml"),
                 "--attach", "a-b=0"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "expected ID=NODE" in err[0] and not (tmp_path / "y.toml").exists()
