"""A component's kernel containers packed into one memory block, and the trampoline that calls its kernel on them.

The compiled loop (loop_ops.run_chunk) is one function for every system: it calls each component's kernel through
a trampoline on that component's packed containers, all three given by address (int64 arrays), so its arguments
are plain arrays and numbers. Before this, the loop took the 36 containers of the blade-loss system (~200 arrays)
as arguments: one compiled version per system, whose CPython wrapper (unboxing them) and scalar replacement
(SROA) over ~1 400 argument values took 13-16 s of CPU on a fresh machine's first run.

* :class:`Packed` writes the containers (s, p, u, y) into a buffer in numba's in-memory layout (read from its data
  model, :func:`_layout`), in Python: nothing to compile. Every array goes in as a *borrowed* view: its meminfo
  and parent are null, so the compiled code neither keeps nor frees it (numba's reference counting skips a null
  meminfo); the arrays stay owned by Python: :class:`Packed` holds the containers, and repacks whenever one of
  them is another object.
* ``trampoline`` (compiled once per container type, like the kernel itself: :func:`functions`) loads them back
  and calls the kernel by its address (loop_ops.call_kernel), so a kernel's code is linked into neither.
"""
from __future__ import annotations

import functools
import hashlib
import importlib.util
import os
import struct
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

from rotorcosim.master.compiled import loop_ops
from rotorcosim.master.compiled.loop_ops import TRAMPOLINE_ARGS


def _check(ty) -> None:
    if isinstance(ty, (types.Array, types.Integer, types.Float, types.Boolean)):
        return
    if isinstance(ty, types.BaseTuple):
        for t in ty:
            _check(t)
        return
    raise TypingError(f"a kernel container holds {ty}: the compiled loop passes arrays, integers, floats, booleans and tuples of them")


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
from rotorcosim.master.compiled.kernel_args import _load
from rotorcosim.master.compiled.loop_ops import call_kernel


@njit(cache=True, no_cfunc_wrapper=True)
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
    _check(ctype)
    tramp = functions(ctype)
    sig = TRAMPOLINE_ARGS[:4] + (types.TypeRef(ctype),)
    tramp.compile(sig)
    cres = tramp.overloads[sig]
    return int(cres.library.get_pointer_to_function(cres.fndesc.llvm_func_name))


def _offsets(ctx, llty) -> list[int]:
    """Byte offsets of the members of an LLVM struct or array type (the target's ABI alignment)."""
    members = list(llty.elements) if hasattr(llty, "elements") else [llty.element] * llty.count
    out, off = [], 0
    for m in members:
        a = ctx.get_abi_alignment(m)
        off = (off + a - 1) // a * a
        out.append(off)
        off += ctx.get_abi_sizeof(m)
    return out


def _leaves(ctx, ty, llty, base, path, out) -> None:
    """(offset, struct format, path, ndim) of every array and number in a value of numba type ``ty`` whose
    in-memory (data model) type is ``llty``, at byte offset ``base``."""
    if isinstance(ty, types.Array):
        n = ty.ndim
        # numba's array struct: meminfo, parent, nitems, itemsize, data, shape[n], strides[n], all 8 bytes
        if ctx.get_abi_sizeof(llty) != 8 * (5 + 2 * n):
            raise TypingError(f"numba's array layout changed ({ty}): master/compiled/kernel_args.py cannot pack it")
        out.append((base, f"<5q{2 * n}q", path, n))
    elif isinstance(ty, types.BaseTuple):
        for i, (t, off) in enumerate(zip(ty, _offsets(ctx, llty))):
            sub = llty.elements[i] if hasattr(llty, "elements") else llty.element
            _leaves(ctx, t, sub, base + off, path + (i,), out)
    elif isinstance(ty, types.Boolean):
        out.append((base, "<B", path, -1))
    elif isinstance(ty, types.Float):
        out.append((base, "<" + {32: "f", 64: "d"}[ty.bitwidth], path, -1))
    elif isinstance(ty, types.Integer):
        code = {8: "b", 16: "h", 32: "i", 64: "q"}[ty.bitwidth]
        out.append((base, "<" + (code if ty.signed else code.upper()), path, -1))
    else:
        _check(ty)


_LAYOUTS: dict = {}


def _layout(ctype):
    """(size in bytes, leaves) of containers of numba type ``ctype`` in numba's in-memory representation."""
    lay = _LAYOUTS.get(ctype)
    if lay is None:
        from numba.core.registry import cpu_target

        _check(ctype)
        ctx = cpu_target.target_context
        llty = ctx.data_model_manager[ctype].get_data_type()
        leaves = []
        _leaves(ctx, ctype, llty, 0, (), leaves)
        lay = _LAYOUTS[ctype] = (ctx.get_abi_sizeof(llty), leaves)
    return lay


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
        written again (after a thermal-only interval the bearings' state and ports are new arrays, their constants
        the same: ~0.2 ms a bearing saved), unless the type or the buffer changed. The packed arrays are borrowed:
        ``self.kargs`` keeps them alive."""
        old = self.kargs
        fresh = [True] * len(kargs)
        if old is not None:
            fresh = [not (a is b or (type(a) is type(b) and isinstance(a, tuple) and len(a) == len(b)
                                     and all(x is z for x, z in zip(a, b)))) for a, b in zip(old, kargs)]
            if not any(fresh):
                return False
        ctype = container_type(kargs) if ctype is None else ctype
        size, leaves = _layout(ctype)
        if self.buf.nbytes < size or ctype != self.ctype or len(old or ()) != len(kargs):
            if self.buf.nbytes < size:
                self.buf = np.zeros(size // 8 + 1, dtype=np.int64)
            fresh = [True] * len(kargs)
        mem = self.buf.view(np.uint8)
        for off, fmt, path, ndim in leaves:
            if not fresh[path[0]]:
                continue
            v = kargs
            for i in path:
                v = v[i]
            if ndim >= 0:
                struct.pack_into(fmt, mem, off, 0, 0, v.size, v.itemsize, v.ctypes.data, *v.shape, *v.strides)
            else:
                struct.pack_into(fmt, mem, off, v)
        self.kargs = kargs
        self.ctype = ctype
        return True
