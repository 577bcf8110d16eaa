"""The fatigue content of a load series: rainflow counting, load spectra, damage-equivalent loads, Miner damage.

* **Rainflow counting** (ASTM E1049-85, the four-point method, as fatpack implements it: ``find_reversals``,
  ``find_rainflow_cycles``): the series' turning points, found on ``K`` load classes of width ``(max - min) / K``
  (``LOAD_CLASSES``: a wiggle smaller than 1/4096 of the series' span is no turning point) and taken at the
  series' own values there, give closed cycles of range ``S_i`` and a residue; the residue is counted as half cycles (ASTM E1049-85, 5.4.4: each range of the
  residue counts one half). A series given as counted cycles (``Counts``: ranges ``S_i`` with weights ``n_i``)
  adds its cycles to those of the series (:func:`combine`): the cycles of held intervals, where nothing was
  simulated (held_cycles.py).
* **Load spectrum**: the range histogram ``n(S)`` (bins of equal width from 0 to the largest range) and the
  cumulative exceedance ``N(S) = sum_{S_i >= S} n_i``, the number of cycles whose range reaches S.
* **Damage-equivalent load** (DEL) for a Woehler exponent ``m`` and a reference cycle count ``N_ref``: the range
  that, applied ``N_ref`` times, does the same damage under a Basquin S-N curve ``N(S) = N_c (S / S_c)^-m``
  (whatever ``S_c``, ``N_c``):

      DEL = (sum_i n_i S_i^m / N_ref)^(1/m)

* **Miner damage** (Palmgren-Miner linear rule) for the S-N curve through ``(S_c, N_c)`` with slope ``m``
  (fatpack's ``LinearEnduranceCurve``):

      D = sum_i n_i / N(S_i) = sum_i n_i (S_i / S_c)^m / N_c

  D = 1 is the life used up. With ``N_ref = N_c``, ``D = (DEL / S_c)^m``.

A constant-amplitude sine of amplitude ``a`` over ``n`` periods: ``n`` cycles of range ``2 a``, DEL
``2 a (n / N_ref)^(1/m)``, ``D = n (2 a / S_c)^m / N_c`` (tests/master/test_fatigue.py holds this).

Example::

    >>> import numpy as np
    >>> y = 3.0 * np.cos(np.linspace(0.0, 2 * np.pi * 100, 10001))    # 100 periods, peak to peak
    >>> c = rainflow(y)
    >>> round(float(c.n.sum()), 6), round(float(c.S.max()), 6)
    (100.0, 6.0)
    >>> round(del_load(c, m=4.0, n_ref=100.0), 6)
    6.0
"""
from __future__ import annotations

from collections import namedtuple

import numpy as np

#: load classes of the rainflow count: the range resolution is the series' span over this
LOAD_CLASSES = 4096
Counts = namedtuple("Counts", "S n")
Counts.__doc__ = "Cycle ranges ``S`` with their counts ``n`` (1 a full cycle, 0.5 a half)."
Spectrum = namedtuple("Spectrum", "bin_S bin_n exceed_S exceed_n")
Spectrum.__doc__ = ("A load spectrum: the range histogram's bin centres ``bin_S`` and counts ``bin_n``; the ranges "
                    "``exceed_S`` and the cycles ``exceed_n`` reaching them (cumulative exceedance).")
EMPTY = Counts(np.zeros(0), np.zeros(0))


def library():
    """fatpack, imported at the first count: it imports numpy.f2py (~0.15 s), which a run without fatigue content
    would pay at start-up."""
    import fatpack

    return fatpack


def rainflow(y, k: int = LOAD_CLASSES) -> Counts:
    """The rainflow cycles of series ``y``: closed cycles count 1, the residue's ranges 1/2 each."""
    y = np.asarray(y, dtype=float).ravel()
    if y.size < 3 or not np.ptp(y) > 0.0:
        return EMPTY
    try:
        _, at = library().find_reversals(y, k=k)
    except IndexError:
        # a series monotone at the load classes' resolution (a temperature rising, a load over a short coupled
        # interval): fatpack indexes a second reversal it has not found. Its one reversal pair is its ends: one
        # half cycle, from its first value to its last
        return Counts(np.array([abs(y[-1] - y[0])]), np.array([0.5]))
    if at.size < 2:
        return EMPTY
    # the classes find the turning points; their ranges are the series' own values there, not the classes' centres
    cycles, residue = library().find_rainflow_cycles(y[at])
    full = np.abs(cycles[:, 1] - cycles[:, 0]) if cycles.size else np.zeros(0)
    half = np.abs(np.diff(residue))
    return Counts(np.concatenate([full, half]), np.concatenate([np.ones(full.size), np.full(half.size, 0.5)]))


def combine(*counts: Counts) -> Counts:
    """The cycles of several counts together."""
    return Counts(np.concatenate([c.S for c in counts]), np.concatenate([c.n for c in counts]))


def scaled(c: Counts, factor: float) -> Counts:
    """The cycles of ``c``, each counted ``factor`` times (a window's cycles over a longer span)."""
    return Counts(c.S, c.n * float(factor))


def del_load(c: Counts, m: float, n_ref: float) -> float:
    """DEL = (sum n_i S_i^m / N_ref)^(1/m) (module docstring); 0 without cycles."""
    if not c.n.size:
        return 0.0
    return float((np.sum(c.n * c.S ** m) / n_ref) ** (1.0 / m))


def miner_damage(c: Counts, m: float, s_c: float, n_c: float) -> float:
    """D = sum n_i / N(S_i) on the S-N curve through (s_c, n_c) of slope m (fatpack's LinearEnduranceCurve)."""
    keep = c.S > 0.0            # a cycle of no range does no damage (and its endurance is infinite)
    if not keep.any():
        return 0.0
    curve = library().LinearEnduranceCurve(s_c)
    curve.m, curve.Nc = m, n_c
    return float(curve.find_miner_sum(np.column_stack([c.S[keep], c.n[keep]])))


def spectrum(c: Counts, bins: int = 50) -> Spectrum:
    """The range histogram over ``bins`` equal bins from 0 to the largest range, and the cumulative exceedance
    (each distinct range, descending, with the cycles reaching it)."""
    if not c.n.size:
        return Spectrum(np.zeros(0), np.zeros(0), np.zeros(0), np.zeros(0))
    edges = np.linspace(0.0, float(c.S.max()), bins + 1)
    hist, _ = np.histogram(c.S, bins=edges, weights=c.n)
    order = np.argsort(c.S)[::-1]
    return Spectrum(0.5 * (edges[1:] + edges[:-1]), hist, c.S[order], np.cumsum(c.n[order]))
