"""The whole workflow on an engine that is not the paper's.

* ``new-engine``'s three files run as written (short durations), its rundown reports the engine's own inertia
  (the polar inertia of its shaft and disks, components/rotor/spool_inertia.py) and only its own spool, and
  nothing of the paper's engine reaches its parameters (the residual unbalance is its file's, the speeds its
  spool's);
* an engine with bearing ids 1, 2, 3 (docs/examples/three_bearings) through check-engine (no scenario needed:
  the engine file carries its bearings), a short blade-loss run, a short rundown and the per-bearing commands.
"""
from __future__ import annotations

import json
from pathlib import Path

import pytest

import rotorcosim
from rotorcosim.components.rotor.spool_inertia import polar_inertia
from rotorcosim.master.cli.program import main

ROOT = Path(__file__).resolve().parents[2]
THREE = ROOT / "docs" / "examples" / "three_bearings"


def test_new_engine_files_run_as_written(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)        # check-engine draws its Campbell diagram into the working folder
    d = tmp_path / "mine"
    assert main(["new-engine", str(d)]) == 0
    assert sorted(p.name for p in d.iterdir()) == ["blade_loss.toml", "engine.toml", "rundown.toml"]
    assert main(["check-engine", str(d / "engine.toml"), "--json"]) == 0
    capsys.readouterr()
    sc = rotorcosim.load_scenario(d / "blade_loss.toml")
    p = sc.components["rotor"].parameters
    assert p["F_residual"] == 176.0 and p["model_file"] == str((d / "engine.toml").resolve())
    assert sc.components["rubring0"].parameters["radius"] == 0.030
    assert sc.components["rubring5"].parameters["radius"] == pytest.approx(0.0419)     # bore / 2 by default
    assert main(["run", str(d / "blade_loss.toml"), "--duration", "0.01", "--no-figures", "--out",
                 str(tmp_path / "bl")]) == 0
    s = json.loads((tmp_path / "bl" / "summary.json").read_text())
    assert s["status"] == "complete" and s["provenance"]["engine"]["file"] == str((d / "engine.toml").resolve())
    defaults = {e["parameter"]: e["source"] for e in s["provenance"]["defaults"]}
    assert "thermal0.shaft_length" not in defaults          # the engine's [thermal.0] gives it
    assert "thermal5.shaft_length" in defaults and "thermal.toml" in defaults["thermal5.shaft_length"]
    assert main(["run", str(d / "rundown.toml"), "--duration", "0.02", "--no-figures", "--out",
                 str(tmp_path / "rd")]) == 0
    r = json.loads((tmp_path / "rd" / "summary.json").read_text())
    assert list(r["speeds"]) == ["spool"]                    # its one spool, no gas generator
    J = polar_inertia(str(d / "engine.toml"), "rotor")
    assert r["speeds"]["spool"]["inertia_kgm2"] == J == r["energy"]["spool"]["inertia_kg_m2"]
    assert J == pytest.approx(0.184, abs=5e-4) and J != pytest.approx(polar_inertia("", "pt"))
    assert r["speeds"]["spool"]["start_rpm"] == pytest.approx(16000.0)


def test_new_engine_refuses_an_empty_folder_name(capsys):
    assert main(["new-engine", ""]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "give the folder" in err[0]


def test_an_engine_with_bearings_1_2_3(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert main(["check-engine", str(THREE / "engine.toml"), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    # its own bearings 1, 2, 3 linearised from engine.toml, no scenario given
    assert sorted(out["critical_speeds"]["support_model"]["bearings"]) == ["1", "2", "3"]
    assert out["critical_speeds"]["forward_synchronous_rpm"][:2] == pytest.approx([4619, 5985], abs=1)
    assert main(["critical-speeds", "--model", str(THREE / "engine.toml"), "--json"]) == 0
    capsys.readouterr()
    for args in (["bearing-static", "--engine", str(THREE / "engine.toml"), "--bearing", "3", "--radial-load",
                  "2000"],
                 ["damper-force", "--scenario", str(THREE / "blade_loss.toml"), "--damper", "2", "--position",
                  "2e-4", "0", "--velocity", "0", "0.05", "--temperature", "40"],
                 ["thermal-steady", "--engine", str(THREE / "engine.toml"), "--bearing", "1", "--drag-power", "600",
                  "--sfd-power", "1"]):
        assert main([*args, "--json"]) == 0, args
        got = json.loads(capsys.readouterr().out)
        assert got.get("bearing", got.get("damper")) in (1, 2, 3)
    b3 = json.loads((lambda: (main(["bearing-static", "--engine", str(THREE / "engine.toml"), "--bearing", "3",
                                    "--radial-load", "2000", "--json"]), capsys.readouterr().out)[1])())
    assert b3["axial_load_N"] == 1100.0 and b3["ball_diameter_m"] == 0.00953     # engine.toml's [bearing.3]
    assert main(["bearing-static", "--bearing", "3", "--radial-load", "2000"]) == 2   # no engine: not the paper's
    assert "--engine FILE" in capsys.readouterr().err
    assert main(["run", str(THREE / "blade_loss.toml"), "--duration", "0.01", "--no-figures", "--out",
                 str(tmp_path / "bl")]) == 0
    assert main(["run", str(THREE / "rundown.toml"), "--duration", "0.02", "--no-figures", "--out",
                 str(tmp_path / "rd")]) == 0
    r = json.loads((tmp_path / "rd" / "summary.json").read_text())
    assert list(r["speeds"]) == ["spool"]
    assert r["speeds"]["spool"]["inertia_kgm2"] == polar_inertia(str(THREE / "engine.toml"), "rotor")
    # every bearing's drag reaches the spool (one input per bearing on it): the drag the spool's balance books
    # equals the drag power all three bearings dissipate (their P_drag, recorded, integrated apart), and bearing 2
    # carries its share of it
    import h5py
    import numpy as np

    with h5py.File(tmp_path / "rd" / "timeseries.h5") as f:
        t = f["time"][()]
        p = {k: f[f"bearing{k}.P_drag"][()].reshape(len(t)) for k in "123"}
    e = r["energy"]["spool"]
    whole = sum(float(np.trapezoid(p[k], t)) for k in p)
    assert e["drag_dissipated_J"] == pytest.approx(whole, rel=0.02)
    assert e["work_J"]["drag"] == pytest.approx(e["drag_dissipated_J"], rel=1e-6)
    assert float(np.trapezoid(p["2"], t)) / whole > 0.2
