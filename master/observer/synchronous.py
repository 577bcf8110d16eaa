"""What a steady window holds that does not repeat each cycle: the residual of its time-synchronous average.

A response settled at a constant speed repeats every cycle (a revolution of period ``T``), up to sources of a
period of their own that the machine carries for good, such as rolling elements passing the load (``periods``:
1 / their passing frequency). What repeats neither way is what is left of a transient: the ringing of a
mode at its own frequency, a drift. Over the last ``n`` whole cycles of the window, starting at ``t0``:

    p(s)   = 1/n sum_{i<n} y(t0 + (i + s) T),   0 <= s < 1        time-synchronous average (one cycle)
    r(t)   = y(t) - p((t - t0)/T mod 1)                             its residual
    r_P(t) = 1/P int_{t-P}^{t} r(tau) d tau                         moving mean over a period P of its own source:
                                                                    removes it and its harmonics, keeps a
                                                                    slower ringing (at f: sin(pi f P)/(pi f P))

:func:`largest_residual` is ``max |r_P1..Pm|``: how far the window's largest value can stand from the largest
value of its repeating part (docs/explanation/staggered-scheme.md has what it gives on settled and on ringing
windows; tests/master/test_synchronous.py holds the kernel on synthetic signals).
"""
from __future__ import annotations

import numpy as np


def residual(t: np.ndarray, y: np.ndarray, cycles: float) -> tuple[np.ndarray, np.ndarray]:
    """The residual ``r`` of the time-synchronous average of ``y(t)`` over the last ``floor(cycles)`` whole cycles
    of a window of ``cycles`` cycles (sampled at ``t``, increasing), on a uniform grid ``s`` of as many samples per
    cycle as the window has (``y`` read there by linear interpolation). Returns ``(s, r)``."""
    n = int(np.floor(cycles + 1e-9))
    if n < 1 or len(t) < 2 or not t[-1] > t[0]:
        raise ValueError(f"a time-synchronous average needs a window of a whole cycle at least, sampled in time; got "
                         f"{cycles:g} cycles over {len(t)} samples")
    period = (t[-1] - t[0]) / cycles
    m = max(2, int(round((len(t) - 1) / cycles)))
    s = t[-1] - n * period + np.arange(n * m) * (period / m)
    ys = np.interp(s, t, y).reshape(n, m)
    return s, (ys - ys.mean(axis=0)).ravel()


def moving_mean(s: np.ndarray, r: np.ndarray, period: float) -> tuple[np.ndarray, np.ndarray]:
    """``r_P`` over the samples a whole ``period`` after the first, exact for a period that is no whole number of
    samples: the running integral (trapezoidal) read ``period`` back by interpolation."""
    c = np.concatenate(([0.0], np.cumsum(0.5 * (r[1:] + r[:-1]) * np.diff(s))))
    keep = s >= s[0] + period
    return s[keep], (c[keep] - np.interp(s[keep] - period, s, c)) / period


def largest_residual(t: np.ndarray, y: np.ndarray, cycles: float, periods=()) -> float:
    """``max |r_P1..Pm|``: the largest deviation of ``y`` from its time-synchronous average over the window's whole
    cycles, after a moving mean over each of ``periods`` [s] (a period shorter than two samples, which the
    sampling cannot resolve, or not shorter than half the window is left out)."""
    s, r = residual(t, y, cycles)
    step = s[1] - s[0]
    for p in periods:
        if 2.0 * step <= p < 0.5 * (s[-1] - s[0]):
            s, r = moving_mean(s, r, p)
    return float(np.max(np.abs(r)))
