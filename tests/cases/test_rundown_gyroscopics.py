"""Gyroscopics in a rundown: the response peaks of a slow prescribed rundown of the engine (blade_loss_ramp_712:
12 000 -> 7 000 rev/min in 5 s, 712 N, no rub contact) against the linear engine (cases/blade_loss/linear_engine.py:
the same rotor model with bearings #0/#5 linearised, the gyroscopic matrices of both spools at their own speeds),
an independent steady harmonic solve sharing no code with the time integration.

The squeeze-film dampers are heavily damping (c_film 5 000 and 12 100 N s/m at 30 deg C): the damped response peaks
are not at the undamped critical speeds (8 500 / 10 200 rev/min) but at the damped ones `rotorcosim critical-speeds`
also reports, 9 100 and 11 400 rev/min at bearing #0 and 9 950 rev/min at bearing #5 (docs/explanation/rundown.md). Without the film the
linear engine's peaks are at the critical speeds, which ties the two references together."""
from __future__ import annotations

import numpy as np
import pytest
from scipy.signal import find_peaks

from rotorcosim.cases.blade_loss import critical_speeds, linear_engine
from rotorcosim.components.rotor import model as fem
from rotorcosim.master.api import simulate

F_REF, RPM_REF = 712.0, 16000.0
RPM = np.arange(7500.0, 11801.0, 10.0)


def _linear_peaks(sup):
    """Peak speeds [rev/min] of the linear engine's steady synchronous whirl at bearings 0 and 5, the unbalance
    force m e Omega^2 (F_REF at RPM_REF) as in the rundown."""
    full = fem.build(fem.load_data(None)[0])
    amp = {"0": [], "5": []}
    for n in RPM:
        r = linear_engine.response(full, sup, F_REF * (n / RPM_REF) ** 2, n)
        for b in amp:
            amp[b].append(r[b]["whirl_mm"])
    return {b: sorted(RPM[find_peaks(np.array(a))[0]]) for b, a in amp.items()}


def _rundown_peaks(res):
    """Peak speeds [rev/min] of the whirl envelope (max orbit radius over 10 ms) at bearings 0 and 5 below
    11 800 rev/min (above it the start transient from rest)."""
    w = np.asarray(res["spool_pt.Omega"]).reshape(-1) * 30.0 / np.pi
    out = {}
    for b in ("0", "5"):
        x = np.asarray(res[f"rotor.X_brg{b}"])
        r = np.hypot(x[:, 0], x[:, 1])
        n = len(r) // 10 * 10
        env, ws = r[:n].reshape(-1, 10).max(1), w[:n].reshape(-1, 10).mean(1)
        env = np.where((ws < 11800.0) & (ws > 7500.0), env, 0.0)
        out[b] = sorted(ws[find_peaks(env, prominence=0.03 * env.max())[0]])
    return out


@pytest.mark.slow   # ~69 s of CPU time (measured): the linear response scanned over the whole speed range
def test_undamped_linear_peaks_at_the_critical_speeds():
    """Without the film the linear engine's response peaks at bearing #0 are the forward critical speeds
    (within 1 %)."""
    sup = {k: dict(s, c_film=0.0) for k, s in linear_engine.supports().items()}
    crit = linear_engine.critical_speeds(fem.build(fem.load_data(None)[0]), sup)["forward_synchronous_rpm"][:2]
    p0 = _linear_peaks(sup)["0"]
    assert len(p0) == 2
    assert p0 == pytest.approx(crit, rel=0.01)


@pytest.mark.slow   # ~21 s of CPU time (measured): the linear response scanned over the whole speed range
def test_damped_critical_speeds_are_the_linear_response_peaks():
    """``critical-speeds``' damped critical speeds (cases/blade_loss/response_peaks: a 1.5 % grid refined by a
    bounded search) are the peaks of the linear engine's response scanned here on a 10 rev/min grid."""
    damped = critical_speeds.critical_speeds()["damped_critical_speeds_rpm"]
    ref = _linear_peaks(linear_engine.supports())
    for b in ("0", "5"):
        got = [w for w in damped[b] if RPM[0] < w < RPM[-1]]
        assert len(got) == len(ref[b]), (b, got, ref[b])
        assert got == pytest.approx(ref[b], abs=10.0), (b, got, ref[b])


@pytest.mark.slow   # ~30 s of CPU time: the whole shipped ramp (blade_loss_ramp_712)
def test_slow_rundown_peaks_at_the_damped_critical_speeds():
    """Every whirl peak of the rundown within 2 % of the damped critical speed that ``rotorcosim critical-speeds``
    reports at that bearing (two at bearing #0, one at #5). The undamped ones (8 500 / 10 200 rev/min) are 7-12 %
    lower: the squeeze films' damping moves the peaks (docs/explanation/rundown.md)."""
    res = simulate("blade_loss_ramp_712", figures=False)
    got = _rundown_peaks(res)
    damped = critical_speeds.critical_speeds()["damped_critical_speeds_rpm"]
    ref = {b: [w for w in damped[b] if 7500.0 < w < 11800.0] for b in ("0", "5")}
    for b in ("0", "5"):
        assert len(got[b]) == len(ref[b]), (b, got[b], ref[b])
        assert got[b] == pytest.approx(ref[b], rel=0.02), (b, got[b], ref[b])
    # the power turbine's gyroscopic matrix moves the lower peak at #0 by 0.7 % (9 040 rev/min without it, the
    # linear engine), the gas generator's by nothing: 0.3 % tells a rundown with the gyroscopics from one without
    assert got["0"][0] == pytest.approx(ref["0"][0], rel=0.003)
