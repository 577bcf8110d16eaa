"""A hand-off window's recording state: the named record the thermal-only hold keeps per hand-off.

The hold (master/manipulator/handoff.py, HandOff) owns one :class:`Window` per hand-off: where its ring of the last
samples stands and the rotor cycle being recorded. Both loops record a sample with :func:`record`, the one
source of that arithmetic: the generic loop on the hold's :class:`Window` (an object with one attribute per
field), the compiled loop (master/compiled/loop_ops) on a row of a numpy structured array of :data:`DTYPE`
(the same fields; numba reads a record by field), copied from and back to the hold's object around each chunk
(:meth:`Window.to_record`, :meth:`Window.from_record`). It lives beside the links (master/core) because both
loops read it; only the hold writes it outside :func:`record`.

Fields (:data:`FIELDS`):

* ``pos`` the next ring row, ``count`` the rows filled, ``has_t`` / ``t_last`` the time of the last sample;
* ``csum`` / ``cn`` the sum and count of the cycle being recorded, ``last`` the last sample's first value;
* ``n_cycle`` the samples per cycle; 0: a window counted in revolutions, whose cycle ends at the sample where the
  cycle's angle passes ``next_turn`` (the next whole turn from the interval's start), turning in ``direction``
  (+1 or -1);
* ``cmean`` the mean of the last completed cycle and ``last_cn`` its count;
* ``nout`` the cycles the compiled loop has written in its chunk (its own bookkeeping).
"""
from __future__ import annotations

import math

import numpy as np

#: the record's fields and their types
FIELDS = (("pos", np.int64), ("count", np.int64), ("has_t", np.bool_), ("t_last", np.float64),
          ("csum", np.float64), ("cn", np.int64), ("last", np.float64), ("n_cycle", np.int64),
          ("cmean", np.float64), ("last_cn", np.int64), ("next_turn", np.float64), ("direction", np.float64),
          ("nout", np.int64))
#: the compiled loop's record of a window (a row of a structured array)
DTYPE = np.dtype(list(FIELDS))
_PY = {np.int64: int, np.float64: float, np.bool_: bool}


class Window:
    """A hand-off window's recording state (module docstring), one attribute per field of :data:`FIELDS`."""

    __slots__ = tuple(name for name, _ in FIELDS)

    def __init__(self):
        for name, kind in FIELDS:
            setattr(self, name, _PY[kind](0))

    def to_record(self, r) -> None:
        """Copy into ``r``, a record of :data:`DTYPE`."""
        for name, _ in FIELDS:
            r[name] = getattr(self, name)

    def from_record(self, r) -> None:
        """Copy from ``r``, a record of :data:`DTYPE` (as Python numbers: the generic loop's arithmetic)."""
        for name, kind in FIELDS:
            setattr(self, name, _PY[kind](r[name]))

    def __getstate__(self):
        return {name: getattr(self, name) for name, _ in FIELDS}

    def __setstate__(self, state):
        for name, value in state.items():
            setattr(self, name, value)


def record(y, yo, n, w, ring, ro, nr, t_end, theta):
    """One sample of a hand-off window ``w`` (:class:`Window` or a record of :data:`DTYPE`): y[yo:yo+n] at
    ``t_end`` into row ``pos`` of the ring (nr rows of n at ring[ro:]), and its first value into the rotor cycle
    being recorded. True when the sample completes a cycle: ``n_cycle`` samples, or (``n_cycle`` = 0) the cycle's
    angle ``theta`` [rad] at ``t_end`` has passed the next whole turn ``next_turn`` (which then moves on by whole
    turns past it); the cycle's mean, csum / cn, is then in ``cmean``, its count in ``last_cn``, and the next
    cycle starts. Written with element loops and no calls: the compiled loop compiles this very function."""
    w.has_t = True
    w.t_last = t_end
    pos = w.pos
    for q in range(n):
        ring[ro + pos * n + q] = y[yo + q]
    w.pos = (pos + 1) % nr
    w.count = min(w.count + 1, nr)
    ys = y[yo]
    w.last = ys
    csum = w.csum + ys
    cn = w.cn + 1
    if w.n_cycle > 0:
        done = cn == w.n_cycle
    else:
        done = (theta - w.next_turn) * w.direction >= 0.0
        if done:
            turn = 2.0 * math.pi * w.direction
            w.next_turn = w.next_turn + turn
            while (theta - w.next_turn) * w.direction >= 0.0:
                w.next_turn = w.next_turn + turn
    if done:
        w.cmean = csum / cn
        w.last_cn = cn
        w.csum = 0.0
        w.cn = 0
        return True
    w.csum = csum
    w.cn = cn
    return False
