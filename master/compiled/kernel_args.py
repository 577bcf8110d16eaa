"""A component's kernel containers packed into one memory block, and the trampoline that calls its kernel on them.

The compiled loop (loop_ops.run_chunk) is one function for every system: it calls each component's kernel through
a trampoline on that component's packed containers, all three given by address (int64 arrays), so its arguments
are plain arrays and numbers. The containers themselves as arguments (~200 arrays for a system of nine kernels)
would make one compiled loop per system, whose CPython wrapper (unboxing them) and scalar replacement (SROA) over
~1 400 argument values cost 13-16 s of CPU on a fresh machine's first run.

* :class:`Packed` writes the containers (s, p, u, y) into a buffer in numba's in-memory layout
  (components/numba_internals.layout and pack), in Python: nothing to compile. Every array goes in as a
  *borrowed* view; the arrays stay owned by Python: :class:`Packed` holds the containers, and repacks whenever
  one of them is another object.
* ``trampoline`` (compiled once per container type, like the kernel itself: :func:`functions`) loads them back
  (numba_internals.load_packed) and calls the kernel by its address (numba_internals.call_kernel), so a kernel's
  code is linked into neither.
"""
from __future__ import annotations

import functools
import hashlib
import importlib.util
import os
import sys
import tempfile
from pathlib import Path

import numba
import numpy as np
from numba import types

from rotorcosim.components import numba_internals
from rotorcosim.components.cache import cache_dir
from rotorcosim.components.numba_internals import TRAMPOLINE_ARGS, check_packable, layout, native_address, pack

from rotorcosim.master.compiled import loop_ops


_SOURCE = """\
# containers: {ctype}
# sources: {sources}
from rotorcosim.components.numba_internals import call_kernel, kernel_jit, load_packed


@kernel_jit
def trampoline(ptr, kaddr, t, h, proto):
    s, p, u, y = load_packed(ptr, proto)
    return call_kernel(kaddr, s, p, u, y, t, h)
"""


@functools.cache
def _sources_hash() -> str:
    # numba's disk cache checks the generated file only: the code it runs (numba_internals' intrinsics) is hashed
    # into the file, so that an edit gives another file, never stale code
    h = hashlib.sha256()
    for f in (Path(__file__).resolve(), Path(loop_ops.__file__).resolve(), Path(numba_internals.__file__).resolve()):
        h.update(f.read_bytes())
    return h.hexdigest()[:16]


_MODULES: dict = {}


def functions(ctype):
    """The trampoline of containers of type ``ctype``: ``trampoline(ptr, kaddr, t, h, proto)`` loads them from
    ptr (packed by :class:`Packed`) and returns kernel(s, p, u, y, t, h) of the kernel at address kaddr.

    One small generated module per container type (in the cache folder, components/cache.py), compiled with
    numba's disk cache: a cache index holds the types it was compiled for, and unpickling one names every
    component class's port tuples (components/kernels.port_tuple, made when a component first builds them), so an
    index shared by all types could not be read by a process whose system lacks one of those components."""
    mod = _MODULES.get(ctype)
    if mod is None:
        source = _SOURCE.format(ctype=str(ctype).replace("\n", " "), sources=_sources_hash())
        key = hashlib.sha256(source.encode()).hexdigest()[:20]
        folder = cache_dir("compiled")
        if folder is not None:
            try:
                folder.mkdir(parents=True, exist_ok=True)
            except OSError:
                folder = None
        if folder is None:  # caching off or not writable: a temporary folder (each run compiles)
            folder = Path(tempfile.mkdtemp(prefix="rotorcosim-compiled-"))
        path = folder / f"kernel_args_{key}.py"
        if not path.exists() or path.read_text() != source:
            tmp = path.with_name(f"{path.name}.{os.getpid()}.part")
            tmp.write_text(source)
            tmp.replace(path)
        name = f"rotorcosim_kernel_args_{key}"
        spec = importlib.util.spec_from_file_location(name, path)
        mod = importlib.util.module_from_spec(spec)
        sys.modules[name] = mod
        spec.loader.exec_module(mod)
        _MODULES[ctype] = mod
    return mod.trampoline


def container_type(kargs) -> types.Type:
    """numba's type of a component's containers (s, p, u, y)."""
    return types.Tuple(tuple(numba.typeof(a) for a in kargs))


def trampoline_address(ctype) -> int:
    """The address of the trampoline compiled for containers of type ``ctype`` (compiled or loaded from its disk
    cache if not yet)."""
    check_packable(ctype)
    return native_address(functions(ctype), TRAMPOLINE_ARGS[:4] + (types.TypeRef(ctype),))


class Packed:
    """One component's containers packed for the loop; :meth:`update` repacks when a container changed."""

    def __init__(self):
        self.buf = np.zeros(8, dtype=np.int64)
        self.kargs = None
        self.ctype = None  # the numba type of the packed kargs

    @property
    def address(self) -> int:
        """The packed buffer's address in memory (what a compiled kernel is given)."""
        return int(self.buf.ctypes.data)

    def update(self, kargs, ctype=None) -> bool:
        """Pack ``kargs`` (of type ``ctype``, typed here if None) unless they are the packed ones (the same objects,
        or tuples of the same objects); True when packed anew. Only the containers that are other objects are
        written again (after a thermal-only interval a component's state and ports may be new arrays, its
        constants the same: ~0.2 ms a component saved), unless the type or the buffer changed. The packed arrays are borrowed:
        ``self.kargs`` keeps them alive."""
        old = self.kargs
        fresh = [True] * len(kargs)
        if old is not None:
            fresh = [not (a is b or (type(a) is type(b) and isinstance(a, tuple) and len(a) == len(b)
                                     and all(x is z for x, z in zip(a, b)))) for a, b in zip(old, kargs)]
            if not any(fresh):
                return False
        ctype = container_type(kargs) if ctype is None else ctype
        size, leaves = layout(ctype)
        if self.buf.nbytes < size or ctype != self.ctype or len(old or ()) != len(kargs):
            if self.buf.nbytes < size:
                self.buf = np.zeros(size // 8 + 1, dtype=np.int64)
            fresh = [True] * len(kargs)
        mem = self.buf.view(np.uint8)
        for leaf in leaves:
            path = leaf[2]
            if not fresh[path[0]]:
                continue
            v = kargs
            for i in path:
                v = v[i]
            pack(mem, leaf, v)
        self.kargs = kargs
        self.ctype = ctype
        return True
