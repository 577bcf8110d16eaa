"""A component's kernel containers packed into one memory block, and the trampoline that calls its kernel on them.

The compiled loop (loop_ops.run_chunk) is one function for every system: it calls each component's kernel through
a trampoline on that component's packed containers, all three given by address (int64 arrays), so its arguments
are plain arrays and numbers. Before this, the loop took the 36 containers of the blade-loss system (~200 arrays)
as arguments: one compiled version per system, whose CPython wrapper (unboxing them) and scalar replacement
(SROA) over ~1 400 argument values took 13-16 s of CPU on a fresh machine's first run (notes/h16.md).

* ``pack`` writes the containers (s, p, u, y) into a buffer in numba's in-memory layout, every array as a
  *borrowed* view: its meminfo and parent are null, so the compiled code neither keeps nor frees it (numba's
  reference counting skips a null meminfo). The arrays stay owned by Python: :class:`Packed` holds the
  containers, and repacks whenever one of them is another object.
* ``trampoline`` loads them back and calls the kernel by its address (loop_ops.call_kernel), so a kernel's code
  is linked into neither.

Both are compiled once per container type, like the kernel itself (:func:`functions`).
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
from numba.core import cgutils
from numba.core.errors import TypingError
from numba.extending import intrinsic

from rotorcosim.components.cache import cache_dir

from . import loop_ops
from .loop_ops import TRAMPOLINE_ARGS


def _check(ty) -> None:
    if isinstance(ty, (types.Array, types.Number, types.Boolean)):
        return
    if isinstance(ty, types.BaseTuple):
        for t in ty:
            _check(t)
        return
    raise TypingError(f"a kernel container holds {ty}: the compiled loop passes arrays, numbers and tuples of them")


def _borrowed(context, builder, ty, val):
    """val with the meminfo and parent of every array in it set to null (see the module docstring)."""
    if isinstance(ty, types.Array):
        ary = context.make_array(ty)(context, builder, value=val)
        ary.meminfo = cgutils.get_null_value(ary.meminfo.type)
        ary.parent = cgutils.get_null_value(ary.parent.type)
        return ary._getvalue()
    if isinstance(ty, types.BaseTuple):
        for i, t in enumerate(ty):
            val = builder.insert_value(val, _borrowed(context, builder, t, builder.extract_value(val, i)), i)
    return val


@intrinsic
def _store(typingctx, buf, args):
    """Write ``args`` into ``buf`` (an int64 array); returns the bytes written, or minus the bytes needed when
    ``buf`` is too small (nothing written)."""
    _check(args)

    def codegen(context, builder, sig, llargs):
        bty, aty = sig.args
        dm = context.data_model_manager[aty]
        size = context.get_abi_sizeof(dm.get_data_type())
        ary = context.make_array(bty)(context, builder, llargs[0])
        have = builder.mul(ary.nitems, ary.itemsize)
        need = context.get_constant(types.int64, size)
        ok = builder.icmp_signed(">=", have, need)
        with builder.if_then(ok):
            data = dm.as_data(builder, _borrowed(context, builder, aty, llargs[1]))
            builder.store(data, builder.bitcast(ary.data, data.type.as_pointer()))
        return builder.select(ok, need, builder.neg(need))

    return types.int64(buf, args), codegen


@intrinsic
def _load(typingctx, ptr, proto):
    """The containers packed at address ``ptr``, of the type ``proto`` refers to."""
    ty = proto.instance_type
    _check(ty)

    def codegen(context, builder, sig, llargs):
        dm = context.data_model_manager[ty]
        p = builder.inttoptr(llargs[0], dm.get_data_type().as_pointer())
        return dm.from_data(builder, builder.load(p))

    return ty(ptr, proto), codegen


_SOURCE = """\
# containers: {ctype}
# sources: {sources}
from numba import njit
from rotorcosim.master.kernel_args import _load, _store
from rotorcosim.master.loop_ops import call_kernel


@njit(cache=True)
def pack(s, p, u, y, buf):
    return _store(buf, (s, p, u, y))


@njit(cache=True)
def trampoline(ptr, kaddr, t, h, proto):
    s, p, u, y = _load(ptr, proto)
    return call_kernel(kaddr, s, p, u, y, t, h)
"""


@functools.cache
def _sources_hash() -> str:
    # numba's disk cache checks the generated file only: the code it runs (this module's intrinsics, loop_ops'
    # call_kernel) is hashed into the file, so that an edit gives another file, never stale code
    h = hashlib.sha256()
    for f in (Path(__file__).resolve(), Path(loop_ops.__file__).resolve()):
        h.update(f.read_bytes())
    return h.hexdigest()[:16]


_MODULES: dict = {}


def functions(ctype):
    """(pack, trampoline) for containers of type ``ctype``: ``pack(s, p, u, y, buf)`` writes them into buf (an
    int64 array) and returns the bytes written (< 0: buf too small, nothing written); ``trampoline(ptr, kaddr, t,
    h, proto)`` loads them from ptr and returns kernel(s, p, u, y, t, h) of the kernel at address kaddr.

    One small generated module per container type (in the cache folder, components/cache.py), each compiled with
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
    return mod.pack, mod.trampoline


def container_type(kargs) -> types.Type:
    """numba's type of a component's containers (s, p, u, y)."""
    return types.Tuple(tuple(numba.typeof(a) for a in kargs))


def trampoline_address(ctype) -> int:
    """The address of the trampoline compiled for containers of type ``ctype`` (compiled or loaded from its disk
    cache if not yet)."""
    _check(ctype)
    tramp = functions(ctype)[1]
    sig = TRAMPOLINE_ARGS[:4] + (types.TypeRef(ctype),)
    tramp.compile(sig)
    cres = tramp.overloads[sig]
    return int(cres.library.get_pointer_to_function(cres.fndesc.llvm_func_name))


class Packed:
    """One component's containers packed for the loop; :meth:`update` repacks when a container changed."""

    def __init__(self):
        self.buf = np.zeros(64, dtype=np.int64)
        self.kargs = None

    @property
    def address(self) -> int:
        return int(self.buf.ctypes.data)

    def update(self, kargs, ctype=None) -> bool:
        """Pack ``kargs`` (of type ``ctype``, typed here if None) unless they are the packed ones (the same objects,
        or tuples of the same objects); True when packed anew. The packed arrays are borrowed: ``self.kargs``
        keeps them alive."""
        old = self.kargs
        if old is not None and all(a is b or (type(a) is type(b) and isinstance(a, tuple) and len(a) == len(b)
                                             and all(x is z for x, z in zip(a, b))) for a, b in zip(old, kargs)):
            return False
        pack = _pack_entry(container_type(kargs) if ctype is None else ctype)
        n = pack(*kargs, self.buf)
        if n < 0:
            self.buf = np.zeros(-n // 8 + 1, dtype=np.int64)
            pack(*kargs, self.buf)
        self.kargs = kargs
        return True


_PACK: dict = {}


def _pack_entry(ctype):
    """pack's compiled entry point for containers of type ``ctype``: called without the dispatcher's typing of
    its arguments (the caller has their type; typing a system's containers again costs ~ms per interval)."""
    entry = _PACK.get(ctype)
    if entry is None:
        pack = functions(ctype)[0]
        sig = tuple(ctype) + (types.int64[::1],)
        pack.compile(sig)
        entry = _PACK[ctype] = pack.overloads[sig].entry_point
    return entry
