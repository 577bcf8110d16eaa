"""An engine of three spools (docs/examples/three_spools): checked, its third spool's gyroscopic terms at its own
speed, a blade-loss run, and the limit on the number of spools named."""
from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from rotorcosim.components.rotor import model as fem
from rotorcosim.master.cli import main

EXAMPLE = Path(__file__).resolve().parents[2] / "docs" / "examples" / "three_spools"


def _eigenvalues(full: fem.FullModel) -> np.ndarray:
    """The complex eigenvalues of the model at its files' speeds (first-order form, damping and gyroscopics)."""
    n = full.n
    C = full.C + full.omega_pt * full.G_pt + full.omega_gg * full.G_gg
    Minv = np.linalg.inv(full.M)
    A = np.block([[np.zeros((n, n)), np.eye(n)], [-Minv @ full.K, -Minv @ C]])
    return np.linalg.eigvals(A)


def test_check_engine_reports_three_spools(tmp_path, capsys):
    assert main(["check-engine", str(EXAMPLE / "engine.toml"), "--scenario", str(EXAMPLE / "blade_loss.toml"),
                 "--campbell", str(tmp_path / "c.png"), "--json"]) == 0
    rep = json.loads(capsys.readouterr().out)
    assert rep["problems"] == [] and list(rep["spools"]) == ["lp", "ip", "hp"]
    assert [rep["spools"][s]["speed_rpm"] for s in ("lp", "ip", "hp")] == [16000.0, 15000.0, 20000.0]
    assert len(rep["critical_speeds"]["forward_synchronous_rpm"]) >= 2 and (tmp_path / "c.png").stat().st_size > 0


def test_third_spool_turns_at_its_own_speed(tmp_path):
    """The hp spool touches the others through nothing (its own supports to ground), so its whirl modes in the
    three-spool model must be those of a model of the hp spool alone at its 20 000 rev/min: an independent
    assembly, where it is the first spool. Each of those eigenvalues is found in the three-spool model's
    (relative 1e-7); at the second spool's 15 000 rev/min instead they would differ (checked: not found)."""
    data, _ = fem.load_data(EXAMPLE / "engine.toml")
    three = _eigenvalues(fem.build(data))
    alone = {k: data[k] for k in ("engine", "material", "damping")}
    alone["spool"] = {"hp": data["spool"]["hp"]}
    alone["support"] = [s for s in data["support"] if s["a"][0] == "hp"]

    def found(ev) -> bool:
        return bool(np.all([np.min(np.abs(three - e)) <= 1e-7 * abs(e) for e in ev if abs(e) > 1.0]))

    assert found(_eigenvalues(fem.build(alone)))
    slow = dict(alone, spool={"hp": dict(data["spool"]["hp"], speed_rpm=15000.0)})
    assert not found(_eigenvalues(fem.build(slow)))


def test_three_spool_blade_loss_runs(tmp_path):
    out = tmp_path / "out"
    assert main(["run", str(EXAMPLE / "blade_loss.toml"), "--duration", "0.3", "--no-figures",
                 "--out", str(out)]) == 0
    s = json.loads((out / "summary.json").read_text())
    assert s["status"] == "complete" and list(s["bearings"]) == ["0", "5"]
    assert s["bearings"]["0"]["whirl_amplitude_mm"] > 0


def test_more_spools_than_carried_is_one_line(tmp_path, capsys):
    text = (EXAMPLE / "engine.toml").read_text()
    extra = "".join(f'\n[spool.x{i}]\nspeed_rpm = 9000.0\nmaterial = "steel"\nz_mm = [0, 10]\nd_out_mm = [20]\n'
                    f"d_in_mm = [0]\ndrive_node = 0\n" for i in range(fem.MAX_SPOOLS))
    f = tmp_path / "many.toml"
    f.write_text(text + extra)
    assert main(["check-engine", str(f)]) == 2
    out = capsys.readouterr()
    assert f"{fem.MAX_SPOOLS + 3} spools; the engine format carries at most {fem.MAX_SPOOLS}" in out.out + out.err
    assert main(["critical-speeds", "--model", str(f)]) == 2
    err = capsys.readouterr().err
    assert "spools" in err and len(err.strip().splitlines()) == 1
