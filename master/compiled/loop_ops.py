"""The fixed compiled operations of the thermo-mechanical loop (master/compiled/runner.py), the same for every system.

The loop's glue is data, not generated code: all components' ports are views of one flat float64 array ``X``
(the kernels keep their named tuples: the tuple fields are those views), the links are rows of index tables, and
the functions here loop over table rows at run time. They are compiled once per package version (numba's disk
cache) whatever the system; only the loop that calls each component's kernel is generated (a few lines per
component), and it calls the kernels through their addresses (numba_internals.call_kernel), so that neither the glue nor
the kernels are re-optimised inside it. Measured before this design: one generated
function per system with every link and port spelled out inline took 95-140 s CPU to compile on a fresh machine,
most of it LLVM's scalar replacement of aggregates over that one large function.

Arithmetic and order are those of algorithm._Link / Engine._fire, operation for operation (the generic path and
this one agree to round-off 0: tests/master/test_compiled.py).

Tables (built by compiled.Tables):
* ``LI[j]`` (int64) a link's layout and kinds, columns ``L_*`` below;
* ``M[j]`` (float64, 17) a link's bookkeeping, fields ``HAS_ACC`` ... ``RLEN`` below;
* ``V`` (float64) per link four rows of its size at ``LI[j, L_VOFF]``: acc (or acc2), prev, last, the restart
  offset's delta;
* ``G`` the hand-off windows' rings (rows of the link's size), ``C`` their rotor-cycle means (rows of
  1 + the producer's window inputs);
* ``CT[i]`` (int64) a component's ranges in ``IDX``: its input links, its outgoing links, its watched outputs
  (pairs offset, size);
* ``IDX`` (int64) those lists, and the window ports (pairs offset, size) of each windowed link.
"""
from __future__ import annotations

import math

from numba import types

from rotorcosim.components.numba_internals import call_trampoline, kernel_jit

# the fields of a link's bookkeeping row M[j] (algorithm._Link's, then the hand-off window's (hold.HandOff):
# ring position, count, has t_last, t_last, cycle sum, cycle count, last sample, samples per cycle, cycles written
# in this chunk, then a hand-back's restart offset (hold.Restart): its start and length, 0 for none); V's rows per
# link: acc (or acc2), prev, last, the restart offset's delta
HAS_ACC, WEIGHT, HAS_PREV, PREV_T, HAS_CUR, CUR_T, RPOS, RCOUNT, HAS_RT, RT, CSUM, CN, WLAST, NCYC, NOUT, R0, \
    RLEN = range(17)

# columns of LI
(L_SRC, L_DST, L_N, L_TAKE, L_PROD, L_HB, L_WIN, L_VOFF, L_GOFF, L_GNR, L_COFF, L_CW, L_WP0, L_WP1) = range(14)
NL = 14
# what the consumer takes (algorithm._Link.value): a copy, the window's mean or RMS (fast -> slow), linear
# extrapolation to the middle (``linear``, slow -> fast) or to the end (``linear-end``) of its step
TAKE_COPY, TAKE_MEAN, TAKE_RMS, TAKE_MID, TAKE_END = range(5)
# the bookkeeping after the producer's step (algorithm._Link.produced): none, the weight only (fast -> slow
# ``last``), the weight and the mean's or the mean square's integral, the last two outputs (extrapolation)
PROD_NONE, PROD_WEIGHT, PROD_MEAN, PROD_RMS, PROD_HIST = range(5)
# columns of CT
C_IN0, C_IN1, C_OUT0, C_OUT1, C_W0, C_W1 = range(6)
NC = 6


@kernel_jit
def gather(i, t, hc, X, LI, M, V, CT, IDX):
    """The inputs of component i from its links, just before it fires over [t, t + hc] (algorithm._Link.value,
    then hold.Restart's offset on a hand-back)."""
    for r in range(CT[i, C_IN0], CT[i, C_IN1]):
        j = IDX[r]
        src = LI[j, L_SRC]
        dst = LI[j, L_DST]
        n = LI[j, L_N]
        vo = LI[j, L_VOFF]
        take = LI[j, L_TAKE]
        if take == TAKE_MEAN or take == TAKE_RMS:
            if M[j, WEIGHT] > 0.0:
                if take == TAKE_MEAN:
                    for q in range(n):
                        X[dst + q] = V[vo + q] / M[j, WEIGHT]
                else:
                    for q in range(n):
                        X[dst + q] = math.sqrt(V[vo + q] / M[j, WEIGHT])
                M[j, HAS_ACC] = 0.0
                M[j, WEIGHT] = 0.0
            else:
                for q in range(n):
                    X[dst + q] = X[src + q]
        elif take == TAKE_MID or take == TAKE_END:
            if M[j, HAS_PREV] != 0.0 and M[j, CUR_T] > M[j, PREV_T]:
                if take == TAKE_MID:
                    when = t + 0.5 * hc
                else:
                    when = t + hc
                c = (when - M[j, CUR_T]) / (M[j, CUR_T] - M[j, PREV_T])
                for q in range(n):
                    X[dst + q] = X[src + q] + (X[src + q] - V[vo + n + q]) * c
            else:
                for q in range(n):
                    X[dst + q] = X[src + q]
        else:
            for q in range(n):
                X[dst + q] = X[src + q]
        if LI[j, L_HB] != 0 and M[j, RLEN] > 0.0:
            # hold.Restart.offset at the consumer's step end (the generic loop passes t_end = t + hc)
            rs = ((t + hc) - M[j, R0]) / M[j, RLEN]
            if rs < 1.0:
                if rs <= 0.0:
                    rf = 1.0
                else:
                    rf = 0.5 + 0.5 * math.cos(math.pi * rs)
                for q in range(n):
                    X[dst + q] = X[dst + q] + V[vo + 3 * n + q] * rf


@kernel_jit
def finite(X, CT, IDX, i):
    """Are component i's watched outputs (those other components read) finite (Engine._fire)?"""
    tot = 0.0
    for r in range(CT[i, C_W0], CT[i, C_W1], 2):
        o = IDX[r]
        for q in range(IDX[r + 1]):
            tot += X[o + q]
    return math.isfinite(tot)


@kernel_jit
def produced(i, t, hc, X, LI, M, V, G, C, CT, IDX):
    """The bookkeeping of component i's outgoing links after it fired over [t, t + hc] (algorithm._Link.produced;
    hold.HandOff.record for a hand-off window)."""
    te = t + hc
    for r in range(CT[i, C_OUT0], CT[i, C_OUT1]):
        j = IDX[r]
        y = LI[j, L_SRC]
        n = LI[j, L_N]
        vo = LI[j, L_VOFF]
        prod = LI[j, L_PROD]
        if prod == PROD_MEAN or prod == PROD_RMS or prod == PROD_WEIGHT:
            if prod == PROD_MEAN:
                if M[j, HAS_ACC] == 0.0:
                    for q in range(n):
                        V[vo + q] = X[y + q] * hc
                    M[j, HAS_ACC] = 1.0
                else:
                    for q in range(n):
                        V[vo + q] = V[vo + q] + X[y + q] * hc
            elif prod == PROD_RMS:
                if M[j, HAS_ACC] == 0.0:
                    for q in range(n):
                        V[vo + q] = X[y + q] * X[y + q] * hc
                    M[j, HAS_ACC] = 1.0
                else:
                    for q in range(n):
                        V[vo + q] = V[vo + q] + X[y + q] * X[y + q] * hc
            M[j, WEIGHT] += hc
        elif prod == PROD_HIST:
            if M[j, HAS_CUR] != 0.0:
                for q in range(n):
                    V[vo + n + q] = V[vo + 2 * n + q]
                M[j, HAS_PREV] = 1.0
            else:
                M[j, HAS_PREV] = 0.0
            M[j, PREV_T] = M[j, CUR_T]
            for q in range(n):
                V[vo + 2 * n + q] = X[y + q]
            M[j, CUR_T] = te
            M[j, HAS_CUR] = 1.0
        if LI[j, L_WIN] != 0:
            # hold.HandOff.record (a sample per producer step; no repeated steps here): the window ring and the
            # rotor-cycle means with the producer's thermal inputs at each cycle's end (rows of C: mean, inputs)
            nr = LI[j, L_GNR]
            go = LI[j, L_GOFF]
            M[j, HAS_RT] = 1.0
            M[j, RT] = te
            pos = int(M[j, RPOS])
            for q in range(n):
                G[go + pos * n + q] = X[y + q]
            M[j, RPOS] = (pos + 1) % nr
            M[j, RCOUNT] = min(M[j, RCOUNT] + 1, nr)
            ys = X[y]
            M[j, WLAST] = ys
            M[j, CSUM] += ys
            M[j, CN] += 1.0
            if M[j, CN] == M[j, NCYC]:
                cw = LI[j, L_CW]
                c0 = LI[j, L_COFF] + int(M[j, NOUT]) * cw
                C[c0] = M[j, CSUM] / M[j, CN]
                col = 1
                for w in range(LI[j, L_WP0], LI[j, L_WP1], 2):
                    o = IDX[w]
                    for q in range(IDX[w + 1]):
                        C[c0 + col + q] = X[o + q]
                    col += IDX[w + 1]
                M[j, NOUT] += 1.0
                M[j, CSUM] = 0.0
                M[j, CN] = 0.0


@kernel_jit
def end_of_step(k, k0, check_every, X, width, buf):
    """The observers' row of base step k (every Real output, the first ``width`` values of X) and, every
    ``check_every`` base steps, the finiteness of them all (Engine.check_finite): False when one is not."""
    row = k - k0
    for q in range(width):
        buf[row, q] = X[q]
    if (k + 1) % check_every == 0:
        tot = 0.0
        for q in range(width):
            tot += X[q] * 0.0
        return math.isfinite(tot)
    return True


_I1, _I2, _F1, _F2 = types.int64[::1], types.int64[:, ::1], types.float64[::1], types.float64[:, ::1]
#: run_chunk's argument types (every system's: compiled.Runner.run); a helper process compiles it ahead on a fresh
#: machine (master/compiled/ahead.py; tests/master/test_ahead.py checks them against the runner's call)
RUN_CHUNK_SIG = (types.int64, types.int64, types.int64, types.float64, types.float64, types.int64, _I1, _F2, _I1,
                 _I1, types.int64, _F1, _I2, _F2, _F1, _F1, _F1, _I2, _I1, _I1, _I1, _I1)


@kernel_jit
def run_chunk(k0, k1, rstart, t0, h, check_every, count, buf, status, mult, width, X, LI, M, V, G, C, CT, IDX,
              TA, PA, KA):
    """Base steps k0 .. k1 - 1 of an interval (master/compiled/runner.py): per step the components in order, each that
    fires gathering its inputs, stepping (its kernel at KA[i] called by the trampoline at TA[i] on its packed
    containers at PA[i]), checked and producing; then the observers' row. status = (code, base step, component):
    code 0 done, a kernel's non-zero status, -1 a non-finite watched output, -2 a non-finite output; rstart >= 0
    resumes base step k0 after component rstart (which stepped in Python)."""
    nc = mult.shape[0]
    for k in range(k0, k1):
        t_end = t0 + (k + 1) * h
        resume = k == k0 and rstart >= 0
        for i in range(nc):
            if (k + 1) % mult[i] != 0:
                continue
            hc = mult[i] * h
            t = t_end - hc
            if not (resume and i <= rstart):
                gather(i, t, hc, X, LI, M, V, CT, IDX)
                st = call_trampoline(TA[i], PA[i], KA[i], t, hc)
                if st != 0:
                    status[0] = st
                    status[1] = k
                    status[2] = i
                    return
            if not (resume and i < rstart):
                count[i] += 1
                if not finite(X, CT, IDX, i):
                    status[0] = -1
                    status[1] = k
                    status[2] = i
                    return
                produced(i, t, hc, X, LI, M, V, G, C, CT, IDX)
        if not end_of_step(k, k0, check_every, X, width, buf):
            status[0] = -2
            status[1] = k
            status[2] = -1
            return
    status[0] = 0
    status[1] = k1
    status[2] = -1
