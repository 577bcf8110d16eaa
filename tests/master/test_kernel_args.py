"""Packed kernel containers (master/compiled/kernel_args.py): what the fixed compiled loop hands each kernel.

The loop's own equality with the generic path is tests/master/test_compiled.py; here the packing itself."""
from __future__ import annotations

from collections import namedtuple

import numpy as np
import pytest
from numba import njit, types
from numba.core.errors import TypingError

from rotorcosim.components import numba_internals
from rotorcosim.master.compiled import kernel_args
from rotorcosim.master.compiled import loop_ops

P = namedtuple("P", "a b scale flag n m")


@njit(cache=False)
def _kernel(s, p, u, y, t, h):
    # writes through every container: the arrays are the caller's (borrowed, not copies)
    y[0][0] = p.scale * (p.a[0] + p.b[1]) + u[0][0] + t + h
    y[0][1] = p.n + p.m[1, 0] if p.flag else -1.0
    s[0][0] += 1.0
    return np.int64(7)


@njit(cache=False)
def _call(taddr, ptr, kaddr, t, h):
    return loop_ops.call_trampoline(taddr, ptr, kaddr, t, h)


def _containers():
    # a bool and an int between the floats and arrays (alignment padding), a 2-d Fortran-ordered array (strides)
    m = np.asfortranarray(np.array([[1.0, 2.0], [30.0, 4.0]]))
    return ((np.zeros(1),), P(np.array([1.0, 2.0]), np.array([3.0, 4.0]), 2.0, True, 7, m), (np.array([5.0]),),
            (np.zeros(2),))


def test_a_kernel_called_through_the_trampoline_works_on_the_callers_arrays():
    ka = _containers()
    packed = kernel_args.Packed()
    assert packed.update(ka)
    from rotorcosim.master.compiled.runner import kernel_address
    kaddr = kernel_address(_kernel, ka)
    taddr = kernel_args.trampoline_address(kernel_args.container_type(ka))
    for _ in range(2):
        assert _call(taddr, packed.address, kaddr, 0.25, 0.5) == 7
    assert ka[3][0][0] == 2.0 * (1.0 + 4.0) + 5.0 + 0.75
    assert ka[3][0][1] == 37.0
    assert ka[0][0][0] == 2.0


def test_containers_are_repacked_only_when_one_of_them_is_another_object():
    ka = _containers()
    packed = kernel_args.Packed()
    assert packed.update(ka)
    # new tuples over the same arrays (kernel_args() builds its port tuples anew at every chunk): nothing to do
    assert not packed.update(((ka[0][0],), ka[1], (ka[2][0],), (ka[3][0],)))
    assert packed.update((ka[0], ka[1], (np.array([6.0]),), ka[3]))
    assert packed.update((ka[0], ka[1]._replace(scale=3.0), ka[2], ka[3]))


def test_a_partial_repack_writes_what_a_whole_one_does():
    """Only the containers that are other objects are written again: the buffer then holds what packing all of
    them into a new buffer gives, byte for byte."""
    ka = _containers()
    packed = kernel_args.Packed()
    assert packed.update(ka)
    steps = [(ka[0], ka[1], (np.array([6.0]),), ka[3]),                       # one port array replaced
             ((np.ones(1),), ka[1]._replace(scale=3.0), ka[2], (np.ones(2),)),  # state, a float, outputs
             ((np.ones(1),), ka[1]._replace(flag=False, n=-3), ka[2], ka[3])]
    for new in steps:
        assert packed.update(new)
        whole = kernel_args.Packed()
        assert whole.update(new)
        size = numba_internals.layout(kernel_args.container_type(new))[0]
        assert packed.buf.view(np.uint8)[:size].tobytes() == whole.buf.view(np.uint8)[:size].tobytes()


def test_a_container_the_loop_cannot_pass_is_refused_by_name():
    with pytest.raises(TypingError, match="kernel container holds"):
        kernel_args.trampoline_address(types.Tuple((types.Tuple(()), types.unicode_type, types.Tuple(()),
                                                     types.Tuple(()))))
