"""An engine with three co-simulated ball bearings (docs/examples/three_bearings): the nonlinear co-simulation
against the linear engine's harmonic response, and the linearised engine in ROSS against our critical speeds."""
from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

import rotorcosim
from rotorcosim.cases.blade_loss import critical_speeds, linear_engine
from rotorcosim.components.rotor import model as fem

EXAMPLE = Path(__file__).resolve().parents[2] / "docs" / "examples" / "three_bearings"
IDS = ("1", "2", "3")


def _isothermal(tmp_path: Path) -> Path:
    """The example with the thermal feedback cut: the films at the linear engine's 30 C and no thermal growth of
    the races (the linear engine's state), so that only the mechanics are compared."""
    p = tmp_path / "isothermal.toml"
    lines = [f'[scenario]\nextends = "{EXAMPLE / "blade_loss.toml"}"\nname = "isothermal"',
             "remove_connections = [" + ", ".join(f'"damper{k}.T_oil", "bearing{k}.eps"' for k in IDS) + "]",
             "[inputs]"]
    lines += [f'"damper{k}.T_oil" = 303.15\n"bearing{k}.eps" = [0.0, 0.0, 0.0]' for k in IDS]
    p.write_text("\n".join(lines) + "\n")
    return p


def _major_semi_axis(t, X, W, cycles=10):
    """The 1x (synchronous) orbit's major semi-axis over the last ``cycles`` whole cycles (Fourier projection)."""
    m = t >= t[-1] - cycles * 2 * math.pi / W
    e = np.exp(-1j * W * t[m])
    ax, ay = 2 * np.mean(X[m, 0] * e), 2 * np.mean(X[m, 1] * e)
    return (abs(ax + 1j * ay) + abs(ax - 1j * ay)) / 2


def test_three_bearings_nonlinear_run_matches_the_linear_harmonic_response(tmp_path):
    """At a small unbalance (30 N, so the Hertz contacts and the film stay in their linear range) the steady
    synchronous whirl at each of the three bearings of the co-simulation (time integration of the nonlinear
    bearings, dampers and rotor, 0.6 s) equals the linear engine's direct harmonic solve (the bearings linearised:
    contact stiffness at the preloaded rest, journal mass, O-ring, film at 30 C) within 2 % (measured: 0.1-0.4 %)."""
    F = 30.0
    sc = rotorcosim.load_scenario(_isothermal(tmp_path))
    assert [n for n in sc.components if n.startswith("bearing")] == [f"bearing{k}" for k in IDS]
    sc = sc.set({"rotor.F_unbalance": F, "rotor.F_residual": 0.0, "rotor.t_blade_loss": 0.0})
    res = rotorcosim.simulate(sc, duration=0.6, schedule="monolithic")
    W = sc.components["rotor"].parameters.get("omega_pt", 16000 * math.pi / 30)
    full = fem.load(EXAMPLE / "engine.toml")
    lin = linear_engine.response(full, linear_engine.supports(sc, data=full.data), F)
    assert set(lin) == set(IDS)
    for k in IDS:
        ours = 1e3 * _major_semi_axis(res.time, res[f"rotor.X_brg{k}"], W)
        assert ours == pytest.approx(lin[k]["whirl_mm"], rel=0.02), (k, ours, lin[k])


def test_three_bearings_summary_has_every_bearing(tmp_path):
    """The results (the paper's 11 categories) come per bearing id; a bearing without a rub ring has no rub
    power (null), and the response figures are one per bearing."""
    out = tmp_path / "out"
    from rotorcosim.master.cli import main

    assert main(["run", str(EXAMPLE / "blade_loss.toml"), "--duration", "0.3",
                 "--out", str(out)]) == 0

    s = json.loads((out / "summary.json").read_text())
    assert s["status"] == "complete" and list(s["bearings"]) == list(IDS)
    assert s["bearings"]["1"]["rub_power_W"] is not None and s["bearings"]["2"]["rub_power_W"] is None
    assert all(s["bearings"][k]["whirl_amplitude_mm"] > 0 for k in IDS)
    assert (out / "fig09_response_bearing1.png").is_file() and (out / "fig10_response_bearing3.png").is_file()


@pytest.mark.slow   # ~23 s of CPU time (measured; ROSS's import and its critical-speed search)
def test_three_bearings_critical_speeds_equal_rosss_of_to_ross():
    """The linearised three-bearing engine handed to ROSS (to_ross): ROSS's own forward critical speeds (its
    Newton search, rtol 1e-12) equal check-engine's (our eigen-solve) to 1e-9 (measured ~1e-12)."""
    from rotorcosim.interop import to_ross   # ROSS is in the test extra: imported plainly, its absence fails

    sc = rotorcosim.load_scenario(EXAMPLE / "blade_loss.toml")
    rotor = to_ross(EXAMPLE / "engine.toml", scenario=sc, damped=False)
    ours = critical_speeds.critical_speeds(str(EXAMPLE / "engine.toml"), count=3, max_rpm=1e6,
                                           scenario=sc)["forward_synchronous_rpm"]
    cs = rotor.run_critical_speed(num_modes=12, rtol=1e-12)
    ref = sorted(float(w) * 30 / math.pi for w, d in zip(np.asarray(cs.wn()), cs.whirl_direction)
                 if d == "Forward")[:len(ours)]
    assert len(ours) == 3 and np.allclose(ours, ref, rtol=1e-9, atol=0.0), (ours, ref)
