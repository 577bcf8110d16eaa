"""Fatigue content of a load series (master/observer/fatigue.py) against independent references: a
constant-amplitude sine against the closed-form damage-equivalent load and Miner damage, and a slow linear sweep
through a one-degree-of-freedom resonance against the damage of the quasi-steady closed form."""
from __future__ import annotations

import numpy as np
import pytest
from scipy import integrate, signal

from rotorcosim.master.observer import fatigue as fg


@pytest.mark.parametrize("periods, samples", [(250, 40), (1000, 16)])
def test_constant_amplitude_sine_closed_form(periods, samples):
    """``n`` periods of ``a cos`` (peak to peak): ``n`` cycles of range ``2 a``, DEL = 2 a (n / N_ref)^(1/m) and
    Miner D = n (2 a / S_c)^m / N_c (fatigue.py's docstring), for two Woehler exponents; at 16 samples a period as
    at 40 (the samples fall on the peaks: the series' own values are counted, not load classes' centres)."""
    a = 2.5e3
    y = a * np.cos(np.linspace(0.0, 2.0 * np.pi * periods, periods * samples + 1))
    c = fg.rainflow(y)
    assert c.n.sum() == pytest.approx(periods, abs=1e-12)
    assert np.all(np.abs(c.S - 2 * a) <= 1e-9 * a)
    for m, n_ref in ((4.0, 1e7), (8.0, 2e6)):
        assert fg.del_load(c, m, n_ref) == pytest.approx(2 * a * (periods / n_ref) ** (1 / m), rel=1e-12)
        s_c, n_c = 4.0e4, 2e6
        assert fg.miner_damage(c, m, s_c, n_c) == pytest.approx(periods * (2 * a / s_c) ** m / n_c, rel=1e-12)


def test_spectrum_counts_every_cycle():
    """Two amplitudes, 30 cycles of range 2 and 10 of range 6: the histogram holds 40 cycles, the exceedance
    reaches 10 at range 6 and 40 at range 2."""
    y = np.concatenate([np.tile([0.0, 2.0], 30), np.tile([-2.0, 4.0], 10), [0.0]])
    sp = fg.spectrum(fg.rainflow(y), bins=12)
    assert sp.bin_n.sum() == pytest.approx(40.0, abs=0.6)
    assert sp.exceed_n[np.searchsorted(-sp.exceed_S, -6.0, side="right") - 1] == pytest.approx(10.0, abs=0.6)
    assert sp.exceed_n[-1] == pytest.approx(sp.bin_n.sum())


def test_slow_sweep_through_a_resonance_against_the_quasi_steady_damage():
    """A 1-DOF oscillator (10 Hz, damping ratio 0.05) forced by F0 sin of a linear sweep 5 -> 15 Hz over 100 s:
    its spring force, integrated independently of the module (the exact discretisation of the linear ODE under a
    piecewise-linear force, scipy.signal.cont2discrete 'foh', filtered at 4 kHz), counted by the module, against
    the damage of the quasi-steady closed form, integrated with scipy's quad:

        D = int f(t) (2 F0 |H(f(t))|)^m / (N_c S_c^m) dt,  |H| = 1 / sqrt((1 - r^2)^2 + (2 zeta r)^2)

    (cycles at the rate f(t), each of the steady range at that frequency). The sweep crosses the half-power band
    (1 Hz) in 10 s, 30 decay times: quasi-steady. Measured: 0.21 % apart at m = 4; 1 % asked."""
    fn, zeta, F0 = 10.0, 0.05, 1.0e3
    wn = 2 * np.pi * fn
    f0, f1, T, fs = 5.0, 15.0, 100.0, 4000.0
    rate = (f1 - f0) / T
    t = np.arange(0.0, T, 1.0 / fs)
    F = F0 * np.sin(2 * np.pi * (f0 * t + 0.5 * rate * t * t))
    A = np.array([[0.0, 1.0], [-wn ** 2, -2 * zeta * wn]])
    sys_d = signal.cont2discrete((A, np.array([[0.0], [1.0]]), np.array([[wn ** 2, 0.0]]), np.array([[0.0]])),
                                 1.0 / fs, method="foh")
    b, a = signal.ss2tf(*sys_d[:4])
    spring = signal.lfilter(b[0], a, F)            # k x, unit mass
    m, s_c, n_c = 4.0, 2.0e4, 2e6
    d = fg.miner_damage(fg.rainflow(spring), m, s_c, n_c)

    def rate_of_damage(tt):
        r = (f0 + rate * tt) / fn
        return (f0 + rate * tt) * (2 * F0 / np.sqrt((1 - r * r) ** 2 + (2 * zeta * r) ** 2)) ** m / (n_c * s_c ** m)

    ref = integrate.quad(rate_of_damage, 0.0, T, points=[50.0], limit=400)[0]
    assert d == pytest.approx(ref, rel=0.01)
    assert spring.max() > 9.0 * F0            # the resonance was crossed: 1 / (2 zeta) = 10 x the static force


@pytest.mark.parametrize("y", [np.linspace(0.0, 1.0, 10), [300.0, 300.0, 300.0 + 1e-9, 300.0 + 1e-9],
                               [1.0, 1.0, 2.0, 2.0], [0.0, 1.0, 1.0 - 1e-9]])
def test_a_monotone_series_is_one_half_cycle(y):
    """A series without a reversal between its ends (a thermal node's temperature over a short run, a load over a
    short coupled interval; the last one monotone at the load classes' resolution): one half cycle from its first
    value to its last. fatpack's find_reversals raised an IndexError, which ended a run after it had written its
    time series and figures ('rotorcosim run: error: index -2 is out of bounds for axis 0 with size 1')."""
    c = fg.rainflow(y)
    assert list(c.n) == [0.5] and c.S[0] == pytest.approx(abs(y[-1] - y[0]), rel=1e-12, abs=0.0)
