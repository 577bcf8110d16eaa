"""Every part of numba below its public API that rotorcosim relies on, in this one module.

Elsewhere the code uses numba's public API only (``njit``, ``typeof``, ``types``, ``extending.intrinsic``, a
dispatcher's ``compile``). What lives here, and why it is needed:

* :func:`kernel_jit`: ``njit(cache=True, no_cfunc_wrapper=True)``. ``no_cfunc_wrapper`` skips numba's C-callable
  wrapper of a function, which nothing here uses (compiled code calls compiled code in numba's own calling
  convention) and which cost ~0.3-0.7 s of CPU per function on a fresh machine.
* :func:`loop_jit`: the same without numba's reference counting (``_nrt=False``), for the compiled loop.
* :func:`native_address`: the address of a dispatcher's compiled code for one signature,
  ``overloads[sig].library.get_pointer_to_function(overloads[sig].fndesc.llvm_func_name)``, so that compiled code
  can call it without linking it into its own module (numba re-optimises every function linked into a module).
* :func:`call_native` (the code generation of a call through such an address, ``context.call_conv``, errors
  propagated) and the intrinsics built on it: :func:`call_at` (a kernel calling an inner function by address),
  :func:`call_kernel` and :func:`call_trampoline` (the compiled loop calling a kernel).
* :func:`layout`, :func:`pack` and :func:`load_packed`: a kernel's containers (tuples of arrays and numbers)
  written into one memory block in numba's in-memory representation (its data model; an array is the struct
  meminfo, parent, nitems, itemsize, data, shape[n], strides[n]) and read back in compiled code.
* :func:`in_disk_cache`: whether a dispatcher's on-disk cache holds a signature, read from the cache's private
  index (a helper process on a fresh machine builds only what is missing).

Tested with numba 0.68.1 (llvmlite 0.50.0); pyproject.toml pins the range (``TESTED``). A numba outside it may
move any of these: tests/components/test_numba_internals.py exercises each one and names the installed version
when one fails (:func:`check`).

numba is imported by this module: import it only where the compiled path is used.
"""
from __future__ import annotations

import struct

import numba
from numba import njit, types
from numba.core import cgutils
from numba.core.errors import TypingError
from numba.extending import intrinsic

#: the numba versions this module was tested with (pyproject.toml's range: >= the first, < the next minor)
TESTED = ("0.68.1",)


def version_note() -> str:
    """The installed numba against the tested versions, for error messages."""
    return (f"numba {numba.__version__} is installed; rotorcosim's use of numba's internals "
            f"(components/numba_internals.py) was tested with {', '.join(TESTED)}")


# -- compiling -------------------------------------------------------------------------------------------------
def kernel_jit(fn=None, **options):
    """``njit(cache=True, no_cfunc_wrapper=True, **options)``: how every compiled function of the package is
    compiled (on-disk cache; no C-callable wrapper). Used bare (``@kernel_jit``) or with options
    (``@kernel_jit(inline="always")``)."""
    deco = njit(**{"cache": True, "no_cfunc_wrapper": True, **options})
    return deco if fn is None else deco(fn)


def loop_jit(fn=None, **options):
    """:func:`kernel_jit` without numba's reference counting (``_nrt=False``), for a loop that allocates nothing
    and works on arrays its caller keeps alive: with it, each array handed to an inlined helper (a row view, an
    argument) costs atomic increments and decrements, ~25 % of the compiled loop's time."""
    return kernel_jit(fn, **{"_nrt": False, **options})


def compile_key(fn, sig) -> str:
    """The name of dispatcher ``fn`` compiled for the argument types ``sig`` (a helper process's claim,
    master/compiled/ahead.py, and components/cache.await_ahead)."""
    return f"numba/{fn.py_func.__module__}.{fn.py_func.__qualname__}{tuple(sig)}"


def compile_for(fn, sig) -> None:
    """Compile dispatcher ``fn`` for the argument types ``sig`` (or load it from its disk cache), after waiting
    for a helper process that builds it (components/cache.await_ahead): the explicit step every compilation a
    helper may share goes through."""
    from .cache import await_ahead

    sig = tuple(sig)
    if sig not in fn.overloads:
        await_ahead(compile_key(fn, sig))
        fn.compile(sig)


def native_address(fn, sig, returns=None) -> int:
    """The address of dispatcher ``fn``'s native code for the argument types ``sig`` (:func:`compile_for` first);
    ``returns``: the return type it must have (a TypeError otherwise)."""
    sig = tuple(sig)
    compile_for(fn, sig)
    cres = fn.overloads[sig]
    if returns is not None and cres.signature.return_type != returns:
        raise TypeError(f"{fn.py_func.__module__}.{fn.py_func.__name__} returns {cres.signature.return_type}, "
                        f"not {returns}")
    return int(cres.library.get_pointer_to_function(cres.fndesc.llvm_func_name))


def in_disk_cache(fn, sig) -> bool:
    """Is ``fn`` compiled for ``sig`` here or in its disk cache (True when it has no disk cache: nothing to
    share)? Reads the cache's index only; False when numba's cache moved (the caller then builds it)."""
    if tuple(sig) in fn.overloads:
        return True
    try:
        return _index_has(fn, sig)
    except Exception:
        return False


def _index_has(fn, sig) -> bool:
    cache = getattr(fn, "_cache", None)
    if cache is None or type(cache).__name__ == "NullCache":
        return True
    return cache._index_key(tuple(sig), fn.targetctx.codegen()) in cache._cache_file._load_index()


# -- calls by address ------------------------------------------------------------------------------------------
def call_native(context, builder, addr, restype, argtys, args):
    """Code of ``restype = f(*args)`` for the function at the integer address ``addr`` compiled for ``argtys``, in
    numba's calling convention; an exception raised by ``f`` is propagated to the caller's caller."""
    fnty = context.call_conv.get_function_type(restype, argtys)
    fn = builder.inttoptr(addr, fnty.as_pointer())
    status, res = context.call_conv.call_function(builder, fn, restype, argtys, args)
    with cgutils.if_unlikely(builder, status.is_error):
        context.call_conv.return_status_propagate(builder, status)
    return res


#: inner functions callable by address (:func:`call_at`): the Python function -> its declared argument types
_BY_ADDRESS: dict = {}


def by_address(fn, sig):
    """Declare the numba dispatcher ``fn`` callable by address (:func:`call_at`) for exactly the argument types
    ``sig``; returns ``fn``."""
    _BY_ADDRESS[fn.py_func] = tuple(sig)
    return fn


def address_of(fn) -> int:
    """The address of ``fn``'s native code for its declared signature (:func:`by_address`): the value a kernel
    passes to :func:`call_at`, kept in its constants."""
    return native_address(fn, _BY_ADDRESS[fn.py_func])


@intrinsic
def call_at(typingctx, addr, fn, args):
    """``fn(*args)`` through ``addr`` = :func:`address_of(fn) <address_of>`. The arguments must have the declared
    types (:func:`by_address`): a TypingError says otherwise. The caller's compiled code holds no address (it is
    an argument), so its disk cache stays valid across processes."""
    disp = getattr(fn, "dispatcher", None)
    declared = _BY_ADDRESS.get(getattr(disp, "py_func", None))
    argtys = tuple(args) if isinstance(args, types.BaseTuple) else None
    if declared is None or argtys != declared:
        name = getattr(getattr(disp, "py_func", None), "__qualname__", fn)
        raise TypingError(f"call_at: {name} is called by address with {argtys}, declared for {declared} "
                          f"(components/numba_internals.by_address)")
    restype = fn.get_call_type(typingctx, argtys, {}).return_type

    def codegen(context, builder, signature, llargs):
        vals = [builder.extract_value(llargs[2], i) for i in range(len(argtys))]
        return call_native(context, builder, llargs[0], restype, argtys, vals)

    return restype(addr, fn, args), codegen


@intrinsic
def call_kernel(typingctx, addr, s, p, u, y, t, h):
    """status = kernel(s, p, u, y, t, h) through the address of a kernel compiled for exactly these argument types
    and returning int64 (master/compiled/runner.kernel_address checks both)."""
    sig = types.int64(addr, s, p, u, y, t, h)

    def codegen(context, builder, signature, args):
        return call_native(context, builder, args[0], types.int64, signature.args[1:], args[1:])

    return sig, codegen


#: a trampoline's argument types (master/compiled/kernel_args): the packed containers' address, the kernel's
#: address, t, h, and the containers' type (a TypeRef, passed as a null pointer: it only types the compilation)
TRAMPOLINE_ARGS = (types.int64, types.int64, types.float64, types.float64, types.TypeRef(types.int64))


@intrinsic
def call_trampoline(typingctx, taddr, ptr, kaddr, t, h):
    """status = trampoline(ptr, kaddr, t, h) through the trampoline's address: every kernel is called the same
    way, so a loop over kernels is one function for every system."""
    sig = types.int64(taddr, ptr, kaddr, t, h)

    def codegen(context, builder, signature, args):
        proto = cgutils.get_null_value(context.get_value_type(TRAMPOLINE_ARGS[4]))
        return call_native(context, builder, args[0], types.int64, TRAMPOLINE_ARGS, list(args[1:]) + [proto])

    return sig, codegen


# -- containers packed in numba's in-memory layout ---------------------------------------------------------------
def check_packable(ty) -> None:
    """A TypingError unless ``ty`` is made of arrays, integers, floats, booleans and tuples of them."""
    if isinstance(ty, (types.Array, types.Integer, types.Float, types.Boolean)):
        return
    if isinstance(ty, types.BaseTuple):
        for t in ty:
            check_packable(t)
        return
    raise TypingError(f"a kernel container holds {ty}: the compiled loop passes arrays, integers, floats, booleans "
                      "and tuples of them")


@intrinsic
def load_packed(typingctx, ptr, proto):
    """The value packed at address ``ptr`` (:func:`pack`), of the type ``proto`` refers to."""
    ty = proto.instance_type
    check_packable(ty)

    def codegen(context, builder, sig, llargs):
        dm = context.data_model_manager[ty]
        p = builder.inttoptr(llargs[0], dm.get_data_type().as_pointer())
        return dm.from_data(builder, builder.load(p))

    return ty(ptr, proto), codegen


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
            raise TypingError(f"numba's array layout changed ({ty}): {version_note()}")
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
        check_packable(ty)


_LAYOUTS: dict = {}


def layout(ty):
    """(size in bytes, leaves) of a value of numba type ``ty`` in numba's in-memory representation; a leaf is
    (byte offset, struct format, path of tuple indices, ndim of an array or -1 for a number)."""
    lay = _LAYOUTS.get(ty)
    if lay is None:
        from numba.core.registry import cpu_target

        check_packable(ty)
        ctx = cpu_target.target_context
        llty = ctx.data_model_manager[ty].get_data_type()
        leaves = []
        _leaves(ctx, ty, llty, 0, (), leaves)
        lay = _LAYOUTS[ty] = (ctx.get_abi_sizeof(llty), leaves)
    return lay


def pack(mem, leaf, v) -> None:
    """Write ``v`` (the value at one leaf of :func:`layout`) into the byte buffer ``mem``. An array goes in as a
    *borrowed* view: its meminfo and parent are null, so compiled code neither keeps nor frees it (numba's
    reference counting skips a null meminfo); the caller keeps the array alive."""
    off, fmt, _, ndim = leaf
    if ndim >= 0:
        struct.pack_into(fmt, mem, off, 0, 0, v.size, v.itemsize, v.ctypes.data, *v.shape, *v.strides)
    else:
        struct.pack_into(fmt, mem, off, v)


# -- the smoke test ----------------------------------------------------------------------------------------------
def check() -> None:
    """Exercise every internal above on small functions (compiled without a disk cache); a RuntimeError naming
    the failing one and the numba version when one does not work."""
    import numpy as np

    steps = []

    def step(name, fn):
        try:
            fn()
        except Exception as exc:
            raise RuntimeError(f"numba internal {name!r} failed ({type(exc).__name__}: {exc}); {version_note()}") from exc
        steps.append(name)

    global _SMOKE_INNER
    inner = _SMOKE_INNER = njit(no_cfunc_wrapper=True)(_smoke_inner)
    by_address(inner, (types.float64, types.float64[::1]))
    outer = njit(_smoke_outer)
    kern = njit(no_cfunc_wrapper=True)(_smoke_kernel)
    x = np.array([1.0, 2.0, 3.0])

    step("no_cfunc_wrapper", lambda: kernel_jit(_smoke_inner, cache=False))
    step("_nrt=False", lambda: _expect(loop_jit(_smoke_views, cache=False)(np.arange(6.0).reshape(2, 3)), 12.0))
    step("overloads[sig].library.get_pointer_to_function",
         lambda: native_address(inner, (types.float64, types.float64[::1]), returns=types.float64))
    step("call_conv (call_at)", lambda: _expect(outer(address_of(inner), 2.0, x), 12.0))
    kargs = ((np.zeros(1),), (np.array([4.0, 5.0]), 3, True), (np.array([0.5]),), (np.zeros(2),))
    ctype = types.Tuple(tuple(numba.typeof(a) for a in kargs))

    def packed_call():
        size, leaves = layout(ctype)
        buf = np.zeros(size // 8 + 1, dtype=np.int64)
        mem = buf.view(np.uint8)
        for leaf in leaves:
            v = kargs
            for i in leaf[2]:
                v = v[i]
            pack(mem, leaf, v)
        tramp = njit(no_cfunc_wrapper=True)(_smoke_trampoline)
        sig = TRAMPOLINE_ARGS[:4] + (types.TypeRef(ctype),)
        taddr = native_address(tramp, sig)
        kaddr = native_address(kern, tuple(ctype) + (types.float64, types.float64), returns=types.int64)
        call = njit(_smoke_call)
        _expect(call(taddr, int(buf.ctypes.data), kaddr, 0.25, 0.5), 3)
        _expect(kargs[3][0][0], 4.0 + 5.0 + 0.5 + 0.75)

    step("data model layout, call_kernel, call_trampoline", packed_call)
    step("disk cache index", lambda: _expect(type(_index_has(kernel_jit(_smoke_inner), (types.float64, types.float64[::1]))), bool))


_SMOKE_INNER = None


def _expect(got, want) -> None:
    if got != want:
        raise AssertionError(f"got {got!r}, expected {want!r}")


def _smoke_inner(a, x):
    return a * x.sum()


def _smoke_outer(addr, a, x):
    return call_at(addr, _SMOKE_INNER, (a, x))


def _smoke_views(a):
    tot = 0.0
    for i in range(a.shape[0]):
        row = a[i]
        tot += row[1] + row[2]
    return tot


def _smoke_kernel(s, p, u, y, t, h):
    y[0][0] = p[0][0] + p[0][1] + u[0][0] + t + h
    return p[1] if p[2] else -1


def _smoke_trampoline(ptr, kaddr, t, h, proto):
    s, p, u, y = load_packed(ptr, proto)
    return call_kernel(kaddr, s, p, u, y, t, h)


def _smoke_call(taddr, ptr, kaddr, t, h):
    return call_trampoline(taddr, ptr, kaddr, t, h)
