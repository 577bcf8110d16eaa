"""Every part of fmpy below its public API that rotorcosim relies on, in this one module.

Elsewhere the FMI boundary uses fmpy's public API only (``read_model_description``, ``FMU2Slave``/``FMU3Slave``
and their methods, ``fmpy.fmi2``'s callback types, ``fmpy.logging.addLoggerProxy``). What lives here, and why:

* :func:`c_function`: one of the FMI C functions of a loaded binary, as fmpy bound it (a ctypes function with
  its ``argtypes`` and ``restype`` set), read from the slave's private ``_functions`` table. The hot path calls
  these directly with preallocated ctypes buffers (fmus/importer.py): fmpy's public wrappers build new arrays
  and check each status in Python on every call, which cost more than the FMU's step itself for our small
  components. The FMU state functions (Get/Set/FreeFMUstate) are called the same way, so that a state pointer
  can be freed after the instance's wrapper objects are gone.
* :func:`library_function`: a fresh ctypes function from the shared library fmpy loaded (the slave's ``dll``),
  for FMI 1.0. fmpy 0.3.32 declares the C return type of ``fmiDoStep``, ``fmiInitializeSlave`` and the
  ``fmiGet*Status`` functions as a string where FMI 1.0 returns an ``fmiStatus``: any status but OK would be
  read as a pointer (a crash). fmus/fmi1.py binds the FMI 1.0 functions it calls with their C signatures.

Tested with fmpy 0.3.32; pyproject.toml allows only the tested releases (``TESTED``). A new fmpy may rename
or restructure the table: tests/fmus/test_fmpy_internals.py loads an FMU with the installed fmpy, checks each use
here (:func:`check`) and names the installed version when one fails.
"""
from __future__ import annotations

from typing import Any

#: the fmpy versions this module was tested with (pyproject.toml's range holds these and no other)
TESTED = ("0.3.32",)


def version_note() -> str:
    """The installed fmpy against the tested versions, for error messages."""
    import fmpy

    return (f"fmpy {fmpy.__version__} is installed; rotorcosim's use of fmpy's internals "
            f"(fmus/fmpy_internals.py) was tested with {', '.join(TESTED)}")


def c_function(fmu: Any, name: str):
    """The FMI C function ``name`` (e.g. ``"fmi2DoStep"``) of the binary that the fmpy slave ``fmu``
    (``FMU2Slave``/``FMU3Slave``, loaded) bound, called as ``f(fmu.component, ...)``. A KeyError when the binary
    does not export it."""
    return fmu._functions[name]


def library_function(fmu: Any, symbol: str):
    """A new ctypes function for the exported ``symbol`` of the library the fmpy slave ``fmu`` loaded, its
    ``restype``/``argtypes`` unset (fmpy's own binding of the same symbol is left as it is). An AttributeError
    when the binary does not export it."""
    # CDLL[...] builds a new function object on each call; CDLL.<name> would return fmpy's cached one
    return fmu.dll[symbol]


def check(fmu: Any, version: str) -> None:
    """A RuntimeError naming what moved and the fmpy version unless :func:`c_function` gives, for the loaded and
    instantiated slave ``fmu`` of FMI ``version`` ("2" or "3"), bound ctypes functions of the FMI C API; for
    ``"1"``, unless :func:`library_function` gives the library's ``fmiDoStep``."""
    if version == "1":
        try:
            library_function(fmu, f"{fmu.modelIdentifier}_fmiDoStep")
        except (AttributeError, TypeError) as exc:
            raise RuntimeError(f"fmpy's FMI 1.0 slave does not give its shared library as .dll ({type(exc).__name__}: "
                               f"{exc}); {version_note()}") from exc
        return
    names = {"2": ("fmi2DoStep", "fmi2GetReal", "fmi2SetReal", "fmi2GetInteger"),
             "3": ("fmi3DoStep", "fmi3GetFloat64", "fmi3SetFloat64", "fmi3GetInt32")}[version]
    for name in names:
        try:
            f = c_function(fmu, name)
        except (AttributeError, KeyError, TypeError) as exc:
            raise RuntimeError(f"fmpy's table of FMI functions does not give {name} ({type(exc).__name__}: {exc}); "
                               f"{version_note()}") from exc
        if not callable(f) or f.restype is None or not getattr(f, "argtypes", None):
            raise RuntimeError(f"fmpy's table gives {name} as {f!r}, not a ctypes function with its argtypes and "
                               f"restype bound; {version_note()}")
        if getattr(f, "__name__", name) != name:
            raise RuntimeError(f"fmpy's table gives {f.__name__} for {name}; {version_note()}")
