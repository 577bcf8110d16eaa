"""compiled._type_key, the cheap key of the kernel-address cache: two containers with the same key must have the
same numba type (else the loop would call a kernel compiled for other types), checked on variants of every
property numba's array type holds."""
from collections import namedtuple

import numba
import numpy as np

from rotorcosim.master.compiled.runner import _type_key

P = namedtuple("P", "a b c")
Q = namedtuple("Q", "a b c")


def _variants():
    base = np.zeros((4, 3))
    ro = base.copy()
    ro.flags.writeable = False
    raw = np.zeros(4 * 8 + 1, dtype=np.uint8)[1:].view(np.float64)  # misaligned float64 view
    arrays = [np.zeros(3), np.zeros(3, dtype=np.int64), np.zeros(3, dtype=np.float32), base, base.T, base[:, 1],
              ro, raw, np.zeros((2, 2, 2))]
    scalars = [1.5, np.float64(1.5), 3, True, np.int64(3)]
    out = []
    for a in arrays:
        for s in scalars:
            out += [P(a, s, np.zeros(2)), Q(a, s, np.zeros(2)), P(a, s, (np.zeros(2), 1.0))]
    return out


def test_equal_keys_mean_equal_numba_types():
    vs = _variants()
    seen = {}
    for v in vs:
        seen.setdefault(_type_key(v), set()).add(numba.typeof(v))
    assert all(len(types) == 1 for types in seen.values())
    # finer than numba's types is allowed (one more look-up), never coarser; and containers rebuilt from new arrays
    # of the same kinds (every chunk of an interval) hit the cache
    assert len(seen) >= len({numba.typeof(v) for v in vs})
    assert _type_key(P(np.ones(3), 2.0, np.ones(2))) == _type_key(P(np.zeros(3), 1.5, np.zeros(2)))
