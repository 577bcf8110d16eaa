"""The link semantics (master/core/links.py) are one source for both execution paths: the functions the generic
loop calls in Python and the compiled loop's numba versions of them (master/compiled/loop_ops) give the same bits,
for every kind, on the same state layout. (tests/master/test_compiled.py compares whole runs.)"""
from __future__ import annotations

import numpy as np
import pytest

from rotorcosim.master.compiled import loop_ops
from rotorcosim.master.core import links

N = 3


def _state(rng):
    m = np.zeros(links.NM)
    m[links.HAS_ACC], m[links.WEIGHT] = 1.0, 0.3
    m[links.HAS_PREV], m[links.PREV_T], m[links.HAS_CUR], m[links.CUR_T] = 1.0, 0.1, 1.0, 0.2
    m[links.RPOS], m[links.RCOUNT], m[links.NCYC], m[links.CN], m[links.CSUM] = 1.0, 1.0, 2.0, 1.0, 0.7
    return m, rng.standard_normal(links.NV * N) + 2.0


@pytest.mark.parametrize("kind", [links.TAKE_COPY, links.TAKE_MEAN, links.TAKE_RMS, links.TAKE_MID, links.TAKE_END])
def test_take_and_restart_are_the_same_in_both_paths(kind):
    rng = np.random.default_rng(kind)
    y = rng.standard_normal(N + 2)
    m, v = _state(rng)
    outs = []
    for take, restart in ((links.take, links.add_restart), (loop_ops.take, loop_ops.add_restart)):
        mm, out = m.copy(), np.zeros(N + 1)
        take(kind, out, 1, y, 2, v, 0, N, mm, 0.25, 0.3)
        restart(out, 1, v, links.V_DELTA * N, N, 0.3, 0.2, 0.5)
        outs.append((out, mm))
    assert outs[0][0].tobytes() == outs[1][0].tobytes()
    assert outs[0][1].tobytes() == outs[1][1].tobytes()


@pytest.mark.parametrize("kind", [links.PROD_NONE, links.PROD_WEIGHT, links.PROD_MEAN, links.PROD_RMS,
                                  links.PROD_HIST])
def test_produce_and_record_are_the_same_in_both_paths(kind):
    rng = np.random.default_rng(10 + kind)
    y = rng.standard_normal(N + 1)
    m, v = _state(rng)
    got = []
    for produce, record in ((links.produce, links.record), (loop_ops.produce, loop_ops.record)):
        mm, vv, ring = m.copy(), v.copy(), np.zeros(2 * N)
        produce(kind, y, 1, vv, 0, N, mm, 0.05, 0.25)
        done = record(y, 1, N, mm, ring, 0, 2, 0.25, 0.0)
        got.append((bool(done), mm.tobytes(), vv.tobytes(), ring.tobytes()))
    assert got[0] == got[1]
    assert got[0][0]  # the sample completed a cycle (CN reached NCYC)


@pytest.mark.parametrize("theta, completes", [(7.0, True), (6.0, False), (20.0, True)])
def test_a_cycle_counted_in_revolutions_ends_where_the_angle_passes_a_turn(theta, completes):
    """NCYC = 0: the cycle ends at the sample whose angle has passed NEXT (here 2 pi, turning forwards); NEXT then
    moves on by whole turns past the angle (one cycle even where a sample spans several turns). Both paths alike."""
    rng = np.random.default_rng(3)
    y = rng.standard_normal(N + 1)
    m, _ = _state(rng)
    m[links.NCYC], m[links.NEXT], m[links.DIR] = 0.0, 2.0 * np.pi, 1.0
    got = []
    for record in (links.record, loop_ops.record):
        mm, ring = m.copy(), np.zeros(2 * N)
        done = record(y, 1, N, mm, ring, 0, 2, 0.25, theta)
        got.append((bool(done), mm.tobytes()))
        assert bool(done) == completes
        if completes:
            assert mm[links.CMEAN] == pytest.approx((0.7 + y[1]) / 2.0) and mm[links.LCN] == 2.0
            assert theta < mm[links.NEXT] <= theta + 2.0 * np.pi
            assert (mm[links.NEXT] / (2.0 * np.pi)) % 1.0 == pytest.approx(0.0, abs=1e-12)
        else:
            assert mm[links.CN] == 2.0 and mm[links.NEXT] == 2.0 * np.pi
    assert got[0] == got[1]
