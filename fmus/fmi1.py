"""What FMI 1.0 co-simulation needs beyond FMI 2.0's in the importer (fmus/importer.py).

* The C functions called directly, bound here with their C signatures (:func:`function`): fmpy 0.3.32 declares
  the return type of ``fmiDoStep`` and ``fmiInitializeSlave`` as a string (fmpy_internals.library_function says
  why that is fatal), and an ``fmiBoolean`` is a ``char``, carried here as an unsigned byte so that numpy can
  view the buffer.
* The slave instantiated with a logger kept for the life of the process (:func:`instantiate`).
* Aliases (:func:`aliases`): FMI 1.0 declares them with an ``alias`` attribute (``"alias"`` or
  ``"negatedAlias"``) on a variable sharing another's value reference, which fmpy does not read. An alias may
  share its value reference with an input (libcosim's identity FMU: each output an alias of its input), and a
  negated alias holds the opposite of the value behind its reference (the importer negates it both ways).
"""
from __future__ import annotations

import ctypes
from ctypes import POINTER, c_char_p, c_double, c_int, c_size_t, c_uint, c_uint8, c_void_p
from typing import Any, Callable
from xml.etree import ElementTree

from rotorcosim.fmus.fmpy_internals import library_function

_VR = POINTER(c_uint)
#: FMI 1.0 type -> ctypes type of a value, as the Get/Set functions take it (``fmiBoolean`` is a char)
CTYPES = {"Real": c_double, "Integer": c_int, "Boolean": c_uint8, "String": c_char_p}
#: the functions called directly: name -> (restype, argtypes); every status is an ``fmiStatus`` (an int)
SIGNATURES = {
    **{f"fmi{op}{t}": (c_int, [c_void_p, _VR, c_size_t, POINTER(ct)]) for op in ("Get", "Set")
       for t, ct in CTYPES.items()},
    "fmiInitializeSlave": (c_int, [c_void_p, c_double, c_uint8, c_double]),
    "fmiDoStep": (c_int, [c_void_p, c_double, c_double, c_uint8]),
    "fmiGetRealStatus": (c_int, [c_void_p, c_int, POINTER(c_double)]),
}
LAST_SUCCESSFUL_TIME = 2   # fmiStatusKind fmiLastSuccessfulTime


def function(fmu: Any, name: str) -> Callable:
    """The FMI 1.0 function ``name`` (``"fmiDoStep"``) of the loaded slave ``fmu``, with its C signature. A
    KeyError for a function not in SIGNATURES, an AttributeError when the binary does not export it."""
    restype, argtypes = SIGNATURES[name]
    f = library_function(fmu, f"{fmu.modelIdentifier}_{name}")
    f.restype, f.argtypes = restype, argtypes
    return f


def logger_to(log: list):
    """The FMU logger callback (FMI 1.0 and 2.0 take the same five arguments) that appends ``(status,
    category, message)`` to ``log``, the bytes decoded."""

    def logger(component, instance, status, category, message):
        log.append((int(status), (category or b"").decode("utf-8", "replace"),
                    (message or b"").decode("utf-8", "replace")))

    return logger


def instantiate(fmu: Any, log, keep: list) -> None:
    """fmiInstantiateSlave with a logger appending ``(status, category, message)`` to ``log``; the callbacks
    are appended to ``keep`` (the importer keeps them for the life of the process, as for FMI 2.0). A
    RuntimeError when the FMU gives no instance."""
    from fmpy.fmi1 import (calloc, fmi1CallbackAllocateMemoryTYPE, fmi1CallbackFreeMemoryTYPE,
                           fmi1CallbackFunctions, fmi1CallbackLoggerTYPE, free)
    from fmpy.logging import addLoggerProxy

    logger = logger_to(log)
    cb = fmi1CallbackFunctions()
    cb.logger = fmi1CallbackLoggerTYPE(logger)
    cb.allocateMemory = fmi1CallbackAllocateMemoryTYPE(calloc)
    cb.freeMemory = fmi1CallbackFreeMemoryTYPE(free)
    cb.stepFinished = None
    # the FMI 1.0 logger is variadic: fmpy's native proxy formats the message before calling ours
    addLoggerProxy(ctypes.byref(cb))
    keep.append((cb, logger))
    fmu.instantiate(functions=cb, loggingOn=False)
    if not fmu.component:
        raise RuntimeError("fmiInstantiateSlave returned no instance")


def aliases(xml: bytes) -> dict[str, str]:
    """``{variable name: "alias" | "negatedAlias"}`` for the FMI 1.0 variables that declare an alias."""
    root = ElementTree.fromstring(xml)
    vars_ = root.find("ModelVariables")
    if vars_ is None:
        return {}
    return {v.get("name"): v.get("alias") for v in vars_.iter("ScalarVariable")
            if v.get("alias") in ("alias", "negatedAlias") and v.get("name") is not None}
