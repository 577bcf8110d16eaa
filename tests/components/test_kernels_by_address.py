"""An inner function called by address from a kernel (components/numba_internals.by_address / address_of / call_at): the
same result as the call by name, the declared types enforced, the callee's errors raised in the caller."""
from __future__ import annotations

import numpy as np
import pytest
from numba import njit, types
from numba.core.errors import TypingError

from rotorcosim.components.kernels import address_of, by_address, call_at


@njit(no_cfunc_wrapper=True)
def _axpy(a, x, y):
    if a < 0.0:
        raise ValueError("negative a")
    s = 0.0
    for i in range(x.shape[0]):
        y[i] += a * x[i]
        s += y[i]
    return s, x.shape[0]


by_address(_axpy, (types.float64, types.float64[::1], types.float64[::1]))


@njit
def _by_address(addr, a, x, y):
    return call_at(addr, _axpy, (a, x, y))


@njit
def _by_name(a, x, y):
    return _axpy(a, x, y)


def test_call_at_gives_the_call_by_name():
    x = np.linspace(0.1, 2.0, 7)
    y1, y2 = np.cos(x), np.cos(x)
    r1 = _by_address(address_of(_axpy), 1.7, x, y1)
    r2 = _by_name(1.7, x, y2)
    assert r1 == r2 and r1[1] == 7
    assert np.array_equal(y1, y2)   # written in place through the pointer


def test_the_callee_error_is_raised_in_the_caller():
    x = np.ones(3)
    with pytest.raises(ValueError, match="negative a"):
        _by_address(address_of(_axpy), -1.0, x, x.copy())


def test_other_argument_types_than_the_declared_are_a_typing_error():
    x = np.ones((3, 2))[:, 0]   # not contiguous: another array type than the declared float64[::1]
    with pytest.raises(TypingError, match="_axpy is called by address"):
        _by_address(address_of(_axpy), 1.0, x, np.ones(3))
