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
def test_produce_is_the_same_in_both_paths(kind):
    rng = np.random.default_rng(10 + kind)
    y = rng.standard_normal(N + 1)
    m, v = _state(rng)
    got = []
    for produce in (links.produce, loop_ops.produce):
        mm, vv = m.copy(), v.copy()
        produce(kind, y, 1, vv, 0, N, mm, 0.05, 0.25)
        got.append((mm.tobytes(), vv.tobytes()))
    assert got[0] == got[1]
