"""The hot loop of the rotor component: one Newmark step of the reduced model and its port outputs.

s_new = T s + B f (newmark.step_operator, f = the port forces of the attached bearings, dampers and rub rings (20 for the
paper's engine), then the unbalance), xv = O s_new (displacements and
velocities at the port DOFs). Compiled with numba (found by profiling: numpy's call overheads for three small
matrix-vector products, the input gathering and the finiteness checks were ~50 us per step; this is a few us).
The products are written column by column (axpy) so the inner loop vectorises without reassociating sums, and
the result is bit-for-bit the same on every run.
"""
from __future__ import annotations

import math
from collections import namedtuple

import numpy as np

from ..numba_internals import kernel_jit


@kernel_jit(inline="always")
def gather(f, u, in_off, fux, fuy):
    """Fill the force vector: input port j (the j-th array of the tuple ``u``) at offset ``in_off[j]`` (-1: not a
    force, e.g. a speed input), in the order of attach.input_ports, then the unbalance (fux, fuy) last; returns the
    sum of squares over the vector in its order (non-finite if any input is)."""
    for j in range(len(u)):         # a homogeneous tuple of contiguous arrays (component.Rotor.kernel_io)
        k = in_off[j]
        if k >= 0:
            a = u[j]
            for i in range(a.shape[0]):
                f[k + i] = a[i]
    n = f.shape[0]
    f[n - 2] = fux
    f[n - 1] = fuy
    acc = 0.0
    for i in range(n):
        acc += f[i] * f[i]
    return acc


@kernel_jit(inline="always")
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


#: the rotor's kernel containers (components/kernels.py): state s = (x_v_a: the Newmark state (x, v, a), tau: the
#: mechanical time); constants p = (TB, O: the step map and output rows, f, s_new, xv: scratch, the unbalance data)
RotorState = namedtuple("RotorState", "s tau")
#: in_off / out_off: the offset table of the ports (component.Rotor._offsets): input field j of u enters the force
#: vector at in_off[j] (-1: not a force); output field j of y is xv[out_off[j]:] (-1: the unbalance force F_u)
RotorParams = namedtuple("RotorParams", "TB O f s_new xv W F_residual F_unbalance unbalance_phase t_blade_loss "
                                        "in_off out_off")


@kernel_jit(inline="always")
def unbalance(p, t, tau):
    """The rotating unbalance force at time t, at the rotor's own angle W tau (component._unbalance)."""
    a = p.W * tau
    fx = p.F_residual * math.cos(a)
    fy = p.F_residual * math.sin(a)
    if t >= p.t_blade_loss:
        ph = a + p.unbalance_phase
        fx += p.F_unbalance * math.cos(ph)
        fy += p.F_unbalance * math.sin(ph)
    return fx, fy


@kernel_jit
def tm_step(s, p, u, y, t, h):
    """One Newmark step from t to t + h (components/kernels.py contract); status 2: a non-finite input force,
    3: a non-finite response."""
    tau = s.tau[0] + h
    fux, fuy = unbalance(p, t + h, tau)
    return advance(s, p, u, y, fux, fuy, tau)


@kernel_jit(inline="always")
def advance(s, p, u, y, fux, fuy, tau):
    """The Newmark step under the port inputs and the unbalance force (fux, fuy); the mechanical time becomes tau."""
    if not math.isfinite(gather(p.f, u, p.in_off, fux, fuy)):
        return 2
    if not math.isfinite(step(p.TB, p.O, s.s, p.f, p.s_new, p.xv)):
        return 3
    # an element loop, not s.s[:] = p.s_new: numba's slice assignment compiles its shape-mismatch error message
    # (string formatting: ~10 s of CPU on a fresh machine, measured with numba's compile events)
    sn = p.s_new
    st = s.s
    for i in range(sn.shape[0]):
        st[i] = sn[i]
    s.tau[0] = tau
    xv = p.xv
    for j in range(len(y)):
        k = p.out_off[j]
        a = y[j]
        if k >= 0:
            for i in range(a.shape[0]):
                a[i] = xv[k + i]
        else:
            a[0] = fux
            a[1] = fuy
    return 0
