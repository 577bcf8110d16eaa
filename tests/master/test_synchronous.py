"""The time-synchronous average's residual (master/observer/synchronous.py) on signals whose parts are known: a
response that repeats each cycle leaves nothing, a ringing at its own frequency leaves its amplitude, a ripple of a
period of its own is taken out by the moving mean over that period (not a whole number of samples) and kept
without it."""
import numpy as np
import pytest

from rotorcosim.master.observer import synchronous

T = 3.75e-3                                 # a cycle: 16 000 rev/min
CYCLES = 5


def window(*parts, samples_per_cycle=750):
    t = np.linspace(0.0, CYCLES * T, CYCLES * samples_per_cycle + 1)
    return t, sum(p(t) for p in parts)


def periodic(t):
    """A cycle's response with harmonics, as a contact load under an unbalance."""
    ph = 2.0 * np.pi * t / T
    return 200.0 + 5.0 * np.cos(ph) + 1.5 * np.sin(2.0 * ph + 0.3) + 0.4 * np.cos(7.0 * ph)


def test_a_repeating_response_has_no_residual():
    t, y = window(periodic)
    assert synchronous.largest_residual(t, y, CYCLES) < 1e-9 * 200.0


def test_a_ringing_leaves_its_amplitude():
    """A ringing at 1.8 times the cycle's frequency, as the axial mode the release leaves: its 5 cycles average to
    sin(5 pi 1.8) / (5 sin(pi 1.8)) = 0.2 of it, so the residual's largest value is within 20 % of its amplitude
    (a ringing whose frequency is a whole multiple of the cycle's would repeat, and is no transient)."""
    f, a = 1.8 / T, 0.37
    t, y = window(periodic, lambda t: a * np.sin(2.0 * np.pi * f * t + 0.4))
    got = synchronous.largest_residual(t, y, CYCLES)
    assert 0.8 * a <= got <= 1.2 * a


@pytest.mark.parametrize("orders", [(11.796,), (11.796, 9.242)])
def test_a_ripple_of_its_own_period_is_taken_out(orders):
    """The balls' ripple at 11.796 (and 9.242) times the cycle's frequency, a sawtooth (all harmonics), its
    period 63.6 (81.2) samples: kept without its periods (three quarters of its amplitude at least), taken out
    with them down to a tenth of it (what is left is the share of the ripple the synchronous average took in:
    58.98 passes in the 5 cycles, not a whole number), while a ringing beside it keeps 0.7 of its amplitude at
    least (the moving means pass 1.8 x the cycle's frequency at sin(pi f P) / (pi f P) = 0.96 each, and the
    synchronous average takes up to 0.2)."""
    def ripple(t):
        return sum(2.0 * ((o * t / T) % 1.0 - 0.5) for o in orders)
    t, y = window(periodic, ripple)
    periods = [T / o for o in orders]
    assert synchronous.largest_residual(t, y, CYCLES) >= 0.75
    assert synchronous.largest_residual(t, y, CYCLES, periods) < 0.1
    a = 0.37
    t, y = window(periodic, ripple, lambda t: a * np.sin(2.0 * np.pi * 1.8 * t / T + 0.4))
    assert 0.7 * a <= synchronous.largest_residual(t, y, CYCLES, periods) <= 1.2 * a


def test_the_moving_mean_of_a_period_that_is_no_whole_number_of_samples():
    """The mean of a sinusoid over its own period is zero, and of a constant the constant, for a period of 63.6
    samples (the running integral read back by interpolation, not a whole number of samples)."""
    s = np.arange(3000) * 5e-6
    p = 63.6 * 5e-6
    _, m = synchronous.moving_mean(s, np.sin(2.0 * np.pi * s / p), p)
    assert np.max(np.abs(m)) < 1e-3
    _, m = synchronous.moving_mean(s, np.full(len(s), 3.0), p)
    assert np.allclose(m, 3.0, rtol=1e-12)


def test_periods_the_window_cannot_resolve_are_left_out():
    """A period shorter than two samples, or not shorter than half the window, leaves the residual as it is."""
    t, y = window(periodic, lambda t: 0.37 * np.sin(2.0 * np.pi * 1.8 * t / T))
    plain = synchronous.largest_residual(t, y, CYCLES)
    step = t[1] - t[0]
    assert synchronous.largest_residual(t, y, CYCLES, [step, 3.0 * T]) == plain


def test_a_window_of_less_than_a_cycle_is_refused():
    t = np.linspace(0.0, 0.5 * T, 100)
    with pytest.raises(ValueError, match="a whole cycle at least"):
        synchronous.largest_residual(t, np.sin(t), 0.5)
