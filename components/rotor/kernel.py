"""The hot loop of the rotor component: one Newmark step of the reduced model and its port outputs.

s_new = T s + B f (newmark.step_operator, f = the 20 port/unbalance forces), xv = O s_new (displacements and
velocities at the port DOFs). Compiled with numba (found by profiling: numpy's call overheads for three small
matrix-vector products, the input gathering and the finiteness checks were ~50 us per step; this is a few us).
The products are written column by column (axpy) so the inner loop vectorises without reassociating sums, and
the result is bit-for-bit the same on every run.
"""
from __future__ import annotations

import numpy as np
from numba import njit


@njit(cache=True)
def _put(f, k, a, n):
    for i in range(n):
        f[k + i] = a[i]
    return k + n


@njit(cache=True)
def gather(f, fb0, fb5, fs0, fr0, fs5, fr5, fq0, fq5, fux, fuy):
    """Fill the force vector in the order of component._INPUTS, then the unbalance; returns the sum of squares
    (non-finite if any input is)."""
    k = _put(f, 0, fb0, 3)
    k = _put(f, k, fb5, 3)
    k = _put(f, k, fs0, 2)
    k = _put(f, k, fr0, 2)
    k = _put(f, k, fs5, 2)
    k = _put(f, k, fr5, 2)
    k = _put(f, k, fq0, 2)
    k = _put(f, k, fq5, 2)
    f[k] = fux
    f[k + 1] = fuy
    acc = 0.0
    for i in range(k + 2):
        acc += f[i] * f[i]
    return acc


@njit(cache=True)
def step(TB, O, s, f, s_out, xv):
    """s_out = TB [s; f] (TB = [T B], Fortran order), xv = O s_out; returns s_out . s_out."""
    n3 = s.shape[0]
    nf = f.shape[0]
    for i in range(n3):
        s_out[i] = 0.0
    for j in range(n3):
        c = s[j]
        for i in range(n3):
            s_out[i] += TB[i, j] * c
    for j in range(nf):
        c = f[j]
        for i in range(n3):
            s_out[i] += TB[i, n3 + j] * c
    no = xv.shape[0]
    for i in range(no):
        xv[i] = 0.0
    for j in range(n3):
        c = s_out[j]
        for i in range(no):
            xv[i] += O[i, j] * c
    acc = 0.0
    for i in range(n3):
        acc += s_out[i] * s_out[i]
    return acc


def pack(T: np.ndarray, B: np.ndarray) -> np.ndarray:
    return np.asfortranarray(np.hstack([T, B]))
