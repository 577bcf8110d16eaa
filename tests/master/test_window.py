"""A hand-off window's record (master/core/window.py) is one source for both execution paths: the generic loop
records into the hold's Window object, the compiled loop (master/compiled/loop_ops) into a record of the same
fields in a numpy structured array; both give the same bits. (tests/master/test_compiled.py compares whole runs.)"""
from __future__ import annotations

import pickle

import numpy as np
import pytest

from rotorcosim.master.compiled import loop_ops
from rotorcosim.master.core import window

N = 3


def _window(n_cycle=2, next_turn=0.0, direction=0.0):
    w = window.Window()
    w.pos, w.count, w.n_cycle, w.cn, w.csum = 1, 1, n_cycle, 1, 0.7
    w.next_turn, w.direction = next_turn, direction
    return w


def _both(w, y, theta):
    """record() of the generic path on a copy of the Window and of the compiled path on a record of it."""
    py = pickle.loads(pickle.dumps(w))
    ring_py = np.zeros(2 * N)
    done_py = window.record(y, 1, N, py, ring_py, 0, 2, 0.25, theta)
    rec = np.zeros(1, window.DTYPE)
    w.to_record(rec[0])
    ring_c = np.zeros(2 * N)
    done_c = _compiled(y, rec, ring_c, theta)
    back = window.Window()
    back.from_record(rec[0])
    return (bool(done_py), py, ring_py), (bool(done_c), back, ring_c)


def _compiled(y, rec, ring, theta):
    return loop_ops.record(y, 1, N, rec[0], ring, 0, 2, 0.25, theta)


def _fields(w):
    return [(name, getattr(w, name)) for name, _ in window.FIELDS]


def test_record_is_the_same_in_both_paths():
    rng = np.random.default_rng(11)
    y = rng.standard_normal(N + 1)
    (dp, wp, rp), (dc, wc, rc) = _both(_window(), y, 0.0)
    assert dp and dc  # the sample completed a cycle (cn reached n_cycle)
    assert _fields(wp) == _fields(wc) and rp.tobytes() == rc.tobytes()
    assert wp.cmean == (0.7 + y[1]) / 2 and wp.last_cn == 2 and wp.cn == 0 and wp.pos == 0 and wp.count == 2
    assert wp.has_t and wp.t_last == 0.25


@pytest.mark.parametrize("theta, completes", [(7.0, True), (6.0, False), (20.0, True)])
def test_a_cycle_counted_in_revolutions_ends_where_the_angle_passes_a_turn(theta, completes):
    """n_cycle = 0: the cycle ends at the sample whose angle has passed next_turn (here 2 pi, turning forwards);
    next_turn then moves on by whole turns past the angle (one cycle even where a sample spans several turns).
    Both paths alike."""
    rng = np.random.default_rng(3)
    y = rng.standard_normal(N + 1)
    (dp, wp, _), (dc, wc, _) = _both(_window(0, 2.0 * np.pi, 1.0), y, theta)
    assert dp == dc == completes
    assert _fields(wp) == _fields(wc)
    if completes:
        assert wp.cmean == pytest.approx((0.7 + y[1]) / 2.0) and wp.last_cn == 2
        assert theta < wp.next_turn <= theta + 2.0 * np.pi
        assert (wp.next_turn / (2.0 * np.pi)) % 1.0 == pytest.approx(0.0, abs=1e-12)
    else:
        assert wp.cn == 2 and wp.next_turn == 2.0 * np.pi


def test_the_record_and_the_object_have_the_same_fields_and_types():
    w = window.Window()
    assert tuple(window.DTYPE.names) == w.__slots__
    rec = np.zeros(1, window.DTYPE)
    w.to_record(rec[0])
    back = window.Window()
    back.from_record(rec[0])
    assert [type(getattr(back, n)) for n in back.__slots__] == [
        {np.int64: int, np.float64: float, np.bool_: bool}[k] for _, k in window.FIELDS]
