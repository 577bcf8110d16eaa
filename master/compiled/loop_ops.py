"""The fixed compiled operations of the thermo-mechanical loop (master/compiled/runner.py), the same for every system.

The loop's glue is data, not generated code: all components' ports are views of one flat float64 array ``X``
(the kernels keep their named tuples: the tuple fields are those views), the links are rows of index tables, and
:func:`run_chunk` loops over table rows at run time; it calls every kernel through a trampoline by address
(numba_internals.call_trampoline), so that neither the glue nor the kernels are re-optimised inside it. One
function compiled once (numba's disk cache) for every system: a generated function per system with every link and
port spelled out inline took 95-140 s of CPU to compile on a fresh machine, most of it LLVM's scalar replacement
of aggregates over that one large function.

What a link does is master/core/links.py's, whose functions are compiled here as they are (the generic loop calls
the same functions in Python): the two paths agree to round-off 0 (tests/master/test_compiled.py).

The loop's arguments are named records (:class:`Chunk`, :class:`Tables`, :class:`LinkState`, :class:`Kernels`,
:class:`Results`) plus the port array ``X``:

* ``Tables.links[j]`` (int64) link j's layout and kinds, columns ``L_*`` below; ``Tables.comps[i]`` (int64)
  component i's ranges in ``Tables.index``: its input links, its outgoing links, its watched outputs (pairs
  offset, size); ``Tables.index`` (int64) those lists, and the window ports (pairs offset, size) of each windowed
  link; ``Tables.mult`` each component's base steps per step;
* ``LinkState.rows[j]`` link j's state row and ``LinkState.vectors`` its vectors at ``links[j, L_VOFF]``
  (links.py's layout, copied from and back to the link's own arrays), ``LinkState.windows[j]`` the recording
  state of link j's hand-off window (a record of master/core/window.py's DTYPE, read by field; copied from and
  back to the hold's Window), ``LinkState.rings`` the hand-off windows' rings (rows of the link's size),
  ``LinkState.cycles`` their rotor-cycle means (rows: the mean, then the producer's window inputs at the cycle's
  end);
* ``Kernels``: per component the addresses of its trampoline, its packed containers and its kernel.
"""
from __future__ import annotations

import hashlib
import math
from pathlib import Path
from typing import NamedTuple

import numba
import numpy as np

from rotorcosim.components import numba_internals
from rotorcosim.components.numba_internals import call_trampoline, kernel_jit, loop_jit

from rotorcosim.master.core import links, window
from rotorcosim.master.core.links import R0, RLEN

# columns of Tables.links
(L_SRC, L_DST, L_N, L_TAKE, L_PROD, L_HB, L_WIN, L_VOFF, L_GOFF, L_GNR, L_COFF, L_CW, L_WP0, L_WP1,
 L_ANG) = range(15)
NL = 15
# columns of Tables.comps
C_IN0, C_IN1, C_OUT0, C_OUT1, C_W0, C_W1 = range(6)
NC = 6


class Chunk(NamedTuple):
    """Base steps k0 .. k1 - 1 of an interval that starts at t0, base step h; resume_after >= 0: base step k0
    resumes after that component (it stepped in Python); the finiteness of all outputs every check_every base
    steps; the observers' row is X[:width]."""
    k0: int
    k1: int
    resume_after: int
    t0: float
    h: float
    check_every: int
    width: int


class Tables(NamedTuple):
    """The plan's index tables (module docstring)."""
    links: np.ndarray
    comps: np.ndarray
    index: np.ndarray
    mult: np.ndarray


class LinkState(NamedTuple):
    """The links' state (module docstring)."""
    rows: np.ndarray
    vectors: np.ndarray
    windows: np.ndarray
    rings: np.ndarray
    cycles: np.ndarray


class Kernels(NamedTuple):
    """Per component: the addresses of its trampoline (kernel_args), its packed containers and its kernel."""
    trampolines: np.ndarray
    packed: np.ndarray
    kernels: np.ndarray


class Results(NamedTuple):
    """What the loop hands back: each component's steps, the observers' rows (one per base step) and the status
    (code, base step, component): code 0 done, a kernel's non-zero status, -1 a non-finite watched output, -2 a
    non-finite output."""
    count: np.ndarray
    rows: np.ndarray
    status: np.ndarray


# link semantics (links.py) compiled as they are, inlined into the loop (numba's IR), which runs without reference
# counting (numba_internals.loop_jit)
take = kernel_jit(links.take, inline="always")
add_restart = kernel_jit(links.add_restart, inline="always")
produce = kernel_jit(links.produce, inline="always")
record = kernel_jit(window.record, inline="always")


# The helpers below are inlined into run_chunk and have no disk cache of their own: numba's disk cache keys a
# function by its own file, so run_chunk's key carries the sources it is made of (_sources, in its closure), and
# helpers cached on their own would bring back their old code into a new run_chunk.
@loop_jit(cache=False, inline="always")
def gather(i, t, hc, X, tab, st):
    """The inputs of component i from its links, just before it fires over [t, t + hc] (links.take, then
    links.add_restart on a hand-back)."""
    LI = tab.links
    for r in range(tab.comps[i, C_IN0], tab.comps[i, C_IN1]):
        j = tab.index[r]
        dst = LI[j, L_DST]
        n = LI[j, L_N]
        vo = LI[j, L_VOFF]
        m = st.rows[j]
        take(LI[j, L_TAKE], X, dst, X, LI[j, L_SRC], st.vectors, vo, n, m, t + 0.5 * hc, t + hc)
        if LI[j, L_HB] != 0 and m[RLEN] > 0.0:
            add_restart(X, dst, st.vectors, vo + 3 * n, n, t + hc, m[R0], m[RLEN])


@loop_jit(cache=False, inline="always")
def finite(X, tab, i):
    """Are component i's watched outputs (those other components read) finite (Engine._fire)?"""
    tot = 0.0
    IDX = tab.index
    for r in range(tab.comps[i, C_W0], tab.comps[i, C_W1], 2):
        o = IDX[r]
        for q in range(IDX[r + 1]):
            tot += X[o + q]
    return math.isfinite(tot)


@loop_jit(cache=False, inline="always")
def produced(i, t, hc, X, tab, st):
    """The bookkeeping of component i's outgoing links after it fired over [t, t + hc] (links.produce;
    window.record for a hand-off window, whose completed cycles go to the rows of LinkState.cycles with the
    producer's window inputs)."""
    te = t + hc
    LI, IDX, C = tab.links, tab.index, st.cycles
    for r in range(tab.comps[i, C_OUT0], tab.comps[i, C_OUT1]):
        j = IDX[r]
        y = LI[j, L_SRC]
        n = LI[j, L_N]
        m = st.rows[j]
        produce(LI[j, L_PROD], X, y, st.vectors, LI[j, L_VOFF], n, m, hc, te)
        # a window counted in revolutions reads the cycle's angle (its offset in X; -1: counted in samples)
        theta = X[LI[j, L_ANG]] if LI[j, L_ANG] >= 0 else 0.0
        if LI[j, L_WIN] != 0 and record(X, y, n, st.windows[j], st.rings, LI[j, L_GOFF], LI[j, L_GNR], te, theta):
            rec = st.windows[j]
            cw = LI[j, L_CW]
            c0 = LI[j, L_COFF] + rec.nout * cw
            C[c0] = rec.cmean
            col = 1
            for w in range(LI[j, L_WP0], LI[j, L_WP1], 2):
                o = IDX[w]
                for q in range(IDX[w + 1]):
                    C[c0 + col + q] = X[o + q]
                col += IDX[w + 1]
            rec.nout += 1


@loop_jit(cache=False, inline="always")
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


def _sources() -> str:
    """The sources compiled into run_chunk besides this file: the link semantics, the window record and numba's
    internals."""
    h = hashlib.sha256()
    for mod in (links, window, numba_internals):
        h.update(Path(mod.__file__).read_bytes())
    return h.hexdigest()[:16]


def _loop(sources: str):
    def run_chunk(chunk, X, tab, st, kern, res):
        """Base steps chunk.k0 .. chunk.k1 - 1 of an interval (master/compiled/runner.py): per step the components
        in order, each that fires gathering its inputs, stepping (its kernel called by its trampoline on its packed
        containers, ``kern``), checked and producing; then the observers' row. res.status = (code, base step,
        component), :class:`Results`."""
        sources  # noqa: B018  (in the closure: numba's cache key)
        nc = tab.mult.shape[0]
        mult = tab.mult
        k0, rstart, t0, h = chunk.k0, chunk.resume_after, chunk.t0, chunk.h
        status, count = res.status, res.count
        for k in range(k0, chunk.k1):
            t_end = t0 + (k + 1) * h
            resume = k == k0 and rstart >= 0
            for i in range(nc):
                if (k + 1) % mult[i] != 0:
                    continue
                hc = mult[i] * h
                t = t_end - hc
                if not (resume and i <= rstart):
                    gather(i, t, hc, X, tab, st)
                    code = call_trampoline(kern.trampolines[i], kern.packed[i], kern.kernels[i], t, hc)
                    if code != 0:
                        status[0] = code
                        status[1] = k
                        status[2] = i
                        return
                if not (resume and i < rstart):
                    count[i] += 1
                    if not finite(X, tab, i):
                        status[0] = -1
                        status[1] = k
                        status[2] = i
                        return
                    produced(i, t, hc, X, tab, st)
            if not end_of_step(k, k0, chunk.check_every, X, chunk.width, res.rows):
                status[0] = -2
                status[1] = k
                status[2] = -1
                return
        status[0] = 0
        status[1] = chunk.k1
        status[2] = -1

    run_chunk.__qualname__ = "run_chunk"
    return loop_jit(run_chunk)


#: the loop of every system (module docstring); its key in numba's disk cache carries the sources it is made of
run_chunk = _loop(_sources())

_I1, _I2, _F1, _F2 = np.zeros(1, np.int64), np.zeros((1, 1), np.int64), np.zeros(1), np.zeros((1, 1))
_W1 = np.zeros(1, window.DTYPE)
#: run_chunk's argument types (every system's: compiled.Runner.run); a helper process compiles it ahead on a fresh
#: machine (master/compiled/ahead.py; tests/master/test_ahead.py checks them against the runner's call)
RUN_CHUNK_SIG = tuple(numba.typeof(a) for a in (
    Chunk(0, 0, 0, 0.0, 0.0, 0, 0), _F1, Tables(_I2, _I2, _I1, _I1), LinkState(_F2, _F1, _W1, _F1, _F1),
    Kernels(_I1, _I1, _I1), Results(_I1, _F2, _I1)))
