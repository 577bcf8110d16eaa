"""What an input sees of the output it is connected to: the link semantics of both execution paths, in one place.

A link carries a producer's output ``y`` (n values) to a consumer's input ``u``. Between the two it may average
(fast producer -> slow consumer), extrapolate (slow -> fast, or ``linear-end``) and add a hand-back's restart offset
(master/manipulator/restart.py); a hand-off window's recording is the hold's own record (master/core/window.py),
not part of the link's state. Its state is two sequences of floats with the layout below, the same for the generic
loop (algorithm._Link keeps them as lists: ``link.state``, ``link.vectors``) and the compiled loop
(master/compiled/loop_ops: a row of a float64 table and a slice of another per link, copied from and back to the
link's lists around each chunk).

The operations are plain functions over arrays with offsets, written with element loops and no calls, so that the
compiled loop compiles these very functions (numba) and the generic loop calls them in Python: one source, the
same arithmetic operation for operation (tests/master/test_compiled.py holds the two paths equal). The copy
(``u = y``), the common case, the generic loop does with numpy.

State row ``m`` (:data:`NM` floats):

* the link's own: ``HAS_ACC`` (the integral A below holds a value), ``WEIGHT`` (W), ``HAS_PREV``, ``PREV_T``
  (t_prev), ``HAS_CUR``, ``CUR_T`` (t_cur);
* a hand-back's restart offset (restart.Restart, copied there by the compiled loop): ``R0`` (t0), ``RLEN`` (its
  length, 0 for none).

Vectors ``v`` (:data:`NV` rows of n floats, flat): ``V_ACC`` (A: the integral of y, or of y^2 for ``rms``, over
the consumer's window so far), ``V_PREV`` (y_prev), ``V_LAST`` (y_cur: the output at t_cur), ``V_DELTA`` (a
restart's delta).
"""
from __future__ import annotations

import math

HAS_ACC, WEIGHT, HAS_PREV, PREV_T, HAS_CUR, CUR_T = range(6)
R0, RLEN = 6, 7
#: fields of a link's state row
NM = 8
#: the link's own fields (reset at each interval)
OWN = CUR_T + 1
V_ACC, V_PREV, V_LAST, V_DELTA = range(4)
#: rows of a link's vectors
NV = 4

#: the producer's rate against the consumer's
SAME, FAST_TO_SLOW, SLOW_TO_FAST = 0, 1, 2
#: what the consumer takes (:func:`take`)
TAKE_COPY, TAKE_MEAN, TAKE_RMS, TAKE_MID, TAKE_END = range(5)
#: the bookkeeping after the producer's step (:func:`produce`)
PROD_NONE, PROD_WEIGHT, PROD_MEAN, PROD_RMS, PROD_HIST = range(5)


def kinds(mode: int, average: str, extrapolation: str) -> tuple[int, int]:
    """(take, produce) of a link of rate ``mode`` and the connection's ``average`` ("mean", "rms", "last") and
    ``extrapolation`` ("hold", "linear", "linear-end")."""
    if mode == FAST_TO_SLOW:
        take = {"mean": TAKE_MEAN, "rms": TAKE_RMS}.get(average, TAKE_COPY)
        return take, {"mean": PROD_MEAN, "rms": PROD_RMS}.get(average, PROD_WEIGHT)
    if extrapolation == "linear" and mode == SLOW_TO_FAST:
        take = TAKE_MID
    elif extrapolation == "linear-end":
        take = TAKE_END
    else:
        take = TAKE_COPY
    hist = mode == SLOW_TO_FAST or extrapolation == "linear-end"
    return take, (PROD_HIST if hist else PROD_NONE)


def take(kind, out, oo, y, yo, v, vo, n, m, t_mid, t_end):
    """out[oo:oo+n] = what a consumer stepping to ``t_end`` (its step's middle ``t_mid``) sees of y[yo:yo+n]:

    * ``TAKE_COPY``: u = y;
    * ``TAKE_MEAN``: u = A / W, the mean of y over the consumer's window weighted by the producer's steps (so a
      power, itself a step mean, delivers its exact energy), then A and W start again; u = y while W = 0;
    * ``TAKE_RMS``: u = sqrt(A / W), A the integral of y^2; likewise;
    * ``TAKE_MID``: u = y + (y - y_prev) (t_mid - t_cur) / (t_cur - t_prev), linear extrapolation to the middle of
      the consumer's step; u = y without two earlier outputs (t_cur > t_prev);
    * ``TAKE_END``: the same to ``t_end`` (a consumer enforcing equilibrium at its step's end: the Gauss-Seidel
      lag becomes second order)."""
    if kind == TAKE_MEAN or kind == TAKE_RMS:
        if m[WEIGHT] > 0.0:
            if kind == TAKE_MEAN:
                for q in range(n):
                    out[oo + q] = v[vo + q] / m[WEIGHT]
            else:
                for q in range(n):
                    out[oo + q] = math.sqrt(v[vo + q] / m[WEIGHT])
            m[HAS_ACC] = 0.0
            m[WEIGHT] = 0.0
            return
    elif kind == TAKE_MID or kind == TAKE_END:
        if m[HAS_PREV] != 0.0 and m[CUR_T] > m[PREV_T]:
            when = t_mid if kind == TAKE_MID else t_end
            c = (when - m[CUR_T]) / (m[CUR_T] - m[PREV_T])
            p = vo + n  # V_PREV
            for q in range(n):
                out[oo + q] = y[yo + q] + (y[yo + q] - v[p + q]) * c
            return
    for q in range(n):
        out[oo + q] = y[yo + q]


def add_restart(out, oo, v, vo, n, t, t0, length):
    """out[oo:oo+n] += delta f(s), s = (t - t0) / length, delta = v[vo:vo+n]: a hand-back's restart offset
    (restart.Restart), f = 1 for s <= 0, (1 + cos(pi s)) / 2 for 0 < s < 1, nothing added for s >= 1."""
    s = (t - t0) / length
    if s < 1.0:
        if s <= 0.0:
            f = 1.0
        else:
            f = 0.5 + 0.5 * math.cos(math.pi * s)
        for q in range(n):
            out[oo + q] = out[oo + q] + v[vo + q] * f


def produce(kind, y, yo, v, vo, n, m, hc, t_end):
    """The link's bookkeeping after its producer stepped over [t_end - hc, t_end] to y[yo:yo+n]:

    * ``PROD_MEAN``: A += y hc (A = y hc at a window's start), W += hc;
    * ``PROD_RMS``: A += y^2 hc, W += hc;
    * ``PROD_WEIGHT``: W += hc (``average = "last"``);
    * ``PROD_HIST``: (y_prev, t_prev) = (y_cur, t_cur) (none before a first output), (y_cur, t_cur) = (y, t_end)."""
    if kind == PROD_MEAN or kind == PROD_RMS or kind == PROD_WEIGHT:
        if kind == PROD_MEAN:
            if m[HAS_ACC] == 0.0:
                for q in range(n):
                    v[vo + q] = y[yo + q] * hc
                m[HAS_ACC] = 1.0
            else:
                for q in range(n):
                    v[vo + q] = v[vo + q] + y[yo + q] * hc
        elif kind == PROD_RMS:
            if m[HAS_ACC] == 0.0:
                for q in range(n):
                    v[vo + q] = y[yo + q] * y[yo + q] * hc
                m[HAS_ACC] = 1.0
            else:
                for q in range(n):
                    v[vo + q] = v[vo + q] + y[yo + q] * y[yo + q] * hc
        m[WEIGHT] += hc
    elif kind == PROD_HIST:
        p, c = vo + n, vo + 2 * n  # V_PREV, V_LAST
        if m[HAS_CUR] != 0.0:
            for q in range(n):
                v[p + q] = v[c + q]
            m[HAS_PREV] = 1.0
        else:
            m[HAS_PREV] = 0.0
        m[PREV_T] = m[CUR_T]
        for q in range(n):
            v[c + q] = y[yo + q]
        m[CUR_T] = t_end
        m[HAS_CUR] = 1.0


def restart_history(y, yo, v, vo, n, m, t):
    """The extrapolation history after the producer's output jumped at a discrete event at ``t`` [s] (a fuse's
    break, master/core/events.py): y[yo:yo+n] is its output from ``t`` on, the history starts there, (y_cur, t_cur)
    = (y, t) and no y_prev, so that the consumer's next step holds y and the slope restarts from the outputs after
    the jump (a slope through the jump would carry it into that step)."""
    c = vo + 2 * n  # V_LAST
    for q in range(n):
        v[c + q] = y[yo + q]
    m[CUR_T] = t
    m[HAS_CUR] = 1.0
    m[HAS_PREV] = 0.0
