"""Any FMI 1.0, 2.0 or 3.0 co-simulation FMU as a rotorcosim component (through fmpy).

``load_fmu_component(path, name, params)`` is what the master calls for a scenario component given as
``fmu = "file.fmu"``. Its model description is read and its ports made by description.py, a saved state is
fmu_state.py's, the FMU's C functions come from fmpy through fmpy_internals.py. The FMU is checked and extracted (safezip.py: nothing can be written outside the folder;
the folder is kept between runs by extraction_cache.py, so an FMU is unpacked and compiled once), its shared library is loaded and instantiated at once (so a binary that does not load is
reported when the system is built, not in the middle of a run), and its scalar variables are regrouped into the
contract's vector ports (``X[1]..X[n]`` -> port ``X`` of size n, flatten.py) with their units and descriptions.

Mapping onto the contract (components/contract.py):

* parameters are set right away (before initialisation, as FMI requires); unknown names, wrong sizes or
  non-parameters are clear errors naming the FMU;
* ``setup(t0)``: (setupExperiment, the parameters and start values set again, as fmpy and libcosim set them
  after it,) enterInitializationMode, inputs, exitInitializationMode, outputs read; FMI 1.0, which has no
  initialisation mode: inputs, ``fmiInitializeSlave(t0, stopTimeDefined = false)``, outputs read;
* ``do_step(t, h)``: all inputs set, DoStep, all outputs read into ``self.y`` (the master reads ``y``);
* ``get_state``/``set_state``: Get/SetFMUstate when the FMU declares
  ``canGetAndSetFMUstate``; otherwise, and for every FMI 1.0 FMU (FMI 1.0 has no FMU state), a clear error
  (rollback is impossible with that FMU);
* ``phases`` and ``preferred_step``: from rotorcosim's vendor annotation when the FMU is one of ours, else
  ``{"TM"}`` and the DefaultExperiment stepSize (model_description.py documents the annotation);
* ``do_step``: a stop request of the FMU (FMI 2: ``fmi2Discard`` with ``fmi2Terminated`` true, at
  ``fmi2LastSuccessfulTime``; FMI 3: ``terminateSimulation``, at ``lastSuccessfulTime`` after an early return)
  reads the outputs where the FMU stopped and raises the contract's StopRequested: the master ends the run there;
  FMI 1.0 cannot ask to stop: its ``fmiDiscard`` is a failed step;
* ``start_values``: start values of states and other ``initial = "exact"/"approx"`` variables (FMI 1.0, which
  has no ``initial``: variables that declare a start value), checked against their type and range and set before
  initialisation (fmpy's ``start_values``).

Types: every FMI 1.0 / 2.0 / 3.0 co-simulation type becomes a port (components/value_types.py): Real/Float64/Float32,
Integer/Enumeration and every FMI 3.0 integer width, Boolean, String; FMI 3.0 arrays are vector ports of
prod(shape) values (row-major); Binary and Clock ports are declared but not carried (they may stay unconnected).
Ranges (min/max, enumeration items) and unit definitions (BaseUnit exponents, factor, offset) are kept on the
contract variables, for the checks of values and the unit conversions of connections (master/core/conversions.py).
FMI 1.0 (fmi1.py): fmpy reads its description in FMI 2.0's terms (variability ``parameter`` is a parameter,
causality ``internal`` a local); a declared alias may share an input's value reference, and a negated alias's
values are negated both ways in the transfer buffers.

The hot path calls the FMU's C functions directly with preallocated ctypes buffers, one Get/Set call per FMI type
(fmpy's convenience wrappers build new arrays on every call): the FMU boundary should cost what FMI costs, not
what the glue costs. The FMI 1.0 functions are bound again with their C signatures (fmi1.py: fmpy's declare
some return types wrongly).
"""
from __future__ import annotations

import ctypes
import os
import sys
import weakref
from collections import deque
from pathlib import Path
from typing import Any, Mapping

import numpy as np

from rotorcosim.components.contract import Component, ContractError, StopRequested, Variable
from rotorcosim.components.value_types import KIND_OF, check_value, dtype_of

from rotorcosim.fmus import extraction_cache, fmi1
from rotorcosim.fmus import model_description as mdx
from rotorcosim.fmus.description import FMUError, declared_attribute, describe, parse_number, ports_of
from rotorcosim.fmus.fmpy_internals import c_function
from rotorcosim.fmus.fmu_state import STATE_FUNCTIONS, FMUState
from rotorcosim.fmus.flatten import FlattenError, regroup
from rotorcosim.fmus.safezip import ArchiveError

_OK_STATUS = 1  # OK = 0, Warning = 1 (FMI 1.0, 2.0 and 3.0): anything above is a failure
_DISCARD = 2
_FMI2_TERMINATED, _FMI2_LAST_SUCCESSFUL_TIME = 3, 2   # fmi2StatusKind values

#: per FMI version and FMI type: (ctypes value type, the suffix of its Get/Set functions)
_CTYPES = {
    "1": {"Real": (ctypes.c_double, "Real"), "Integer": (ctypes.c_int, "Integer"),
          "Enumeration": (ctypes.c_int, "Integer"), "Boolean": (ctypes.c_uint8, "Boolean"),
          "String": (ctypes.c_char_p, "String")},
    "2": {"Real": (ctypes.c_double, "Real"), "Integer": (ctypes.c_int, "Integer"),
          "Enumeration": (ctypes.c_int, "Integer"), "Boolean": (ctypes.c_int, "Boolean"),
          "String": (ctypes.c_char_p, "String")},
    "3": {"Float64": (ctypes.c_double, "Float64"), "Float32": (ctypes.c_float, "Float32"),
          "Int8": (ctypes.c_int8, "Int8"), "UInt8": (ctypes.c_uint8, "UInt8"), "Int16": (ctypes.c_int16, "Int16"),
          "UInt16": (ctypes.c_uint16, "UInt16"), "Int32": (ctypes.c_int32, "Int32"),
          "UInt32": (ctypes.c_uint32, "UInt32"), "Int64": (ctypes.c_int64, "Int64"),
          "UInt64": (ctypes.c_uint64, "UInt64"), "Enumeration": (ctypes.c_int64, "Int64"),
          "Boolean": (ctypes.c_bool, "Boolean"), "String": (ctypes.c_char_p, "String")},
}


#: the function freeing an instance, per FMI version (fmpy's names)
_FREE = {"1": "fmi1FreeSlaveInstance", "2": "fmi2FreeInstance", "3": "fmi3FreeInstance"}

#: logger callbacks handed to FMUs (see _instantiate2)
_CALLBACKS: list = []


class _Handle:
    """What must be released when the component goes away: kept apart from the component for weakref.finalize."""

    def __init__(self, folder: Path, annotation: mdx.Annotation, version: str, cached: bool = False):
        self.folder = folder
        self.cached = cached  # an extraction kept in the cache between runs (extraction_cache.py)
        self.failed = False   # an FMU that could not be set up leaves nothing behind, in the cache neither
        self.version = version
        self.annotation = annotation
        self.fmu = None
        self.instantiated = False
        self.initialised = False
        self.log: deque = deque(maxlen=40)

    def release(self) -> None:
        fmu, self.fmu = self.fmu, None
        if fmu is not None:
            try:
                if self.instantiated:
                    getattr(fmu, _FREE[self.version])(fmu.component)
                fmu.freeLibrary()
            except Exception:  # best effort while tearing down
                pass
        self.instantiated = False
        _forget_python_modules(self.folder, self.annotation)
        extraction_cache.release(self.folder, self.cached and not self.failed)


def _forget_python_modules(folder: Path, ann: mdx.Annotation) -> None:
    """pythonfmu puts the FMU's resources folder first on sys.path and imports the slave there: undo that for
    a freed FMU of ours, so that the process does not keep stale modules pointing at a deleted folder."""
    root = str(folder) + os.sep
    sys.path[:] = [p for p in sys.path if not (str(p) + os.sep).startswith(root)]
    for key in list(sys.modules):
        f = getattr(sys.modules.get(key), "__file__", None) or ""
        if f.startswith(root):
            del sys.modules[key]


def _purge_cached(ann: mdx.Annotation) -> None:
    """Drop an earlier instance's copy of this FMU's Python modules, so this instance imports its own."""
    for key in list(sys.modules):
        top = key.split(".")[0]
        if (ann.package and top == ann.package) or (ann.slave_module and top == ann.slave_module):
            del sys.modules[key]


class _Transfer:
    """Preallocated value references and values of one FMI type, for a set of ports (one Get/Set call)."""

    def __init__(self, version: str, fmi_type: str, ports: list[tuple[Variable, list[int]]], fmu,
                 negated: list[int] = ()):
        ctype, suffix = _CTYPES[version][fmi_type]
        self.fmi3 = version == "3"
        self.string = fmi_type == "String"
        if version == "1":
            # bound with their C signatures (fmi1.py): fmpy's names and types do not fit a direct call
            self.get_name, self.set_name = f"fmiGet{suffix}", f"fmiSet{suffix}"
            self.get, self.set = fmi1.function(fmu, self.get_name), fmi1.function(fmu, self.set_name)
        else:
            self.get_name, self.set_name = f"fmi{version}Get{suffix}", f"fmi{version}Set{suffix}"
            self.get, self.set = c_function(fmu, self.get_name), c_function(fmu, self.set_name)
        # FMI 1.0 negated aliases: the positions whose value is the opposite of the one behind the reference
        self.negated = np.asarray(negated, dtype=np.intp) if len(negated) else None
        self.boolean = fmi_type == "Boolean"
        self.ports = []
        vrs: list[int] = []
        n = 0
        for var, refs in ports:
            # an FMI 3.0 array is one value reference for var.size values; scalars one reference each
            self.ports.append((var.name, n, n + var.size, dtype_of(var.type, var.fmi_type)))
            vrs.extend(refs)
            n += var.size
        self.nvr, self.n = len(vrs), n
        self.vr = (ctypes.c_uint * self.nvr)(*vrs)
        self.values = (ctype * n)()
        self.view = None if self.string else np.ctypeslib.as_array(self.values)
        self.args = (self.vr, self.nvr, self.values) + ((n,) if self.fmi3 else ())

    def negate(self) -> None:
        """The negated aliases' values in the buffer turned into their base's (or back: it is its own inverse)."""
        v = self.view[self.negated]
        self.view[self.negated] = (v == 0) if self.boolean else -v


class FMUComponent(Component):
    """An FMI 1.0 / 2.0 / 3.0 co-simulation FMU following the component contract."""

    def __init__(self, path: str | Path, name: str = "component", parameters: Mapping[str, Any] | None = None,
                 start_values: Mapping[str, Any] | None = None, label: str | None = None):
        self.path = Path(path)
        self.name = name
        # label: how messages name the file when ``path`` is a temporary one (an SSP archive's entry)
        where = f"FMU {label or self.path} (component {name!r})"
        self._where = where
        xml, md = describe(self.path)
        self.model_description = md
        ann = mdx.read_annotation(xml, where)
        variables, self._scalars = ports_of(md, where, ann.hidden,
                                            ann.default_inputs if ann.implementation is not None else None)
        refs = {v.name: v.valueReference for v in md.modelVariables}
        self._phase_in = refs.get(ann.phase_input) if ann.phase_input else None
        self._phases_out = refs.get(ann.phases_output) if ann.phases_output else None
        self._error_vr = refs.get(ann.error_variable) if ann.error_variable else None
        self.variables = tuple(variables)
        self._by_name = {v.name: v for v in self.variables}
        self.phases = ann.phases or frozenset({"TM"})
        self.holds_state_in_TO = False
        self.phase = None
        self.explicit: set[str] = set()
        step = ann.preferred_step or (md.defaultExperiment.stepSize if md.defaultExperiment else None)
        self.preferred_step = float(step) if step else Component.preferred_step
        self.description = md.description or ""
        self.implementation = ann.implementation
        self._version = {"1.0": "1", "2.0": "2"}.get(md.fmiVersion, "3")
        # FMI 1.0 has no FMU state functions (fmpy leaves the flag false for it)
        self.can_get_set_state = bool(md.coSimulation.canGetAndSetFMUstate) and self._version != "1"
        self._negated = frozenset(n for n, kind in (fmi1.aliases(xml).items() if self._version == "1" else ())
                                  if kind == "negatedAlias")
        self.p = {v.name: v.start for v in self.variables if v.causality == "parameter"}
        self.u = {v.name: v.start_array() for v in self.variables if v.causality == "input" and v.carried}
        self.y = {v.name: v.start_array() for v in self.variables if v.causality == "output" and v.carried}
        self.state = {}
        self.time = 0.0
        self.start_values: dict[str, Any] = {}
        # the parameters and start values written before initialisation, written again after setupExperiment
        # (setup): an FMU may reset its variables there (a 20-sim FMU of libcosim's demo lost its mt0_init), and
        # fmpy and libcosim write them after it
        self._before_init: dict[str, tuple] = {}
        try:
            folder, cached = extraction_cache.acquire(self.path, md.instantiationToken if self._version == "3"
                                                      else md.guid)
        except ArchiveError as exc:
            raise FMUError(str(exc)) from None
        self._handle = _Handle(folder, ann, self._version, cached)
        self._finalizer = weakref.finalize(self, self._handle.release)
        try:
            self._instantiate(md, where)
            self._in = self._transfers("input")
            self._out = self._transfers("output")
            for key, value in (parameters or {}).items():
                self.set_parameter(key, value)
            self._set_start_values(start_values or {})
        except BaseException:
            self._handle.failed = True
            self._finalizer()
            raise

    # -- loading ---------------------------------------------------------------------------------------
    def _transfers(self, causality: str) -> list[_Transfer]:
        by_type: dict[str, list] = {}
        for v in self.variables:
            if v.causality == causality and v.carried:
                refs = list(dict.fromkeys(e.valueReference for e in self._scalars[v.name]))
                by_type.setdefault(v.fmi_type, []).append((v, refs))
        return [_Transfer(self._version, t, ports, self._handle.fmu, self._negated_positions(ports))
                for t, ports in sorted(by_type.items())]

    def _negated_positions(self, ports: list[tuple[Variable, list[int]]]) -> list[int]:
        """The positions, in one transfer's buffer, of FMI 1.0 negated aliases (none for FMI 2.0 / 3.0)."""
        if not self._negated:
            return []
        names = [e.name for var, _ in ports for e in self._scalars[var.name]]
        return [i for i, n in enumerate(names) if n in self._negated]

    def _instantiate(self, md, where: str) -> None:
        from fmpy.fmi1 import FMU1Slave
        from fmpy.fmi2 import FMU2Slave
        from fmpy.fmi3 import FMU3Slave

        h = self._handle
        ident = md.coSimulation.modelIdentifier
        binary = h.folder / "binaries"
        cwd = os.getcwd()
        try:
            if self._version in ("1", "2"):
                cls = FMU1Slave if self._version == "1" else FMU2Slave
                h.fmu = cls(guid=md.guid, unzipDirectory=str(h.folder), modelIdentifier=ident,
                            instanceName=self.name)
            else:
                h.fmu = FMU3Slave(guid=md.instantiationToken, unzipDirectory=str(h.folder),
                                  modelIdentifier=ident, instanceName=self.name)
        except Exception as exc:
            os.chdir(cwd)   # fmpy changes into the binaries folder and stays there when loading fails
            found = sorted(str(p.relative_to(h.folder)) for p in binary.rglob("*") if p.is_file()) \
                if binary.is_dir() else []
            raise FMUError(f"{where}: its binary (model identifier {ident!r}) does not load on this platform: "
                           f"{exc} (binaries in the FMU: {', '.join(found) or 'none'})") from None
        log = h.log
        _purge_cached(h.annotation)
        try:
            if self._version == "1":
                fmi1.instantiate(h.fmu, log, _CALLBACKS)
                h.instantiated = True
                self._bind1()
            elif self._version == "2":
                self._instantiate2(log)
            else:
                def logger(env, status, category, message):
                    log.append((int(status), (category or b"").decode("utf-8", "replace"),
                                (message or b"").decode("utf-8", "replace")))

                h.fmu.instantiate(loggingOn=False, logMessage=logger)
                _CALLBACKS.append((h.fmu.logMessage, logger))
        except Exception as exc:
            raise FMUError(f"{where}: instantiation failed ({exc}){self._log_text()}") from None
        h.instantiated = True
        self._c = h.fmu.component
        if self._version == "1":
            return
        suffix = "eger" if self._version == "2" else "32"
        self._int_get = c_function(h.fmu, f"fmi{self._version}GetInt{suffix}")
        self._int_set = c_function(h.fmu, f"fmi{self._version}SetInt{suffix}")
        self._do_step = c_function(h.fmu, f"fmi{self._version}DoStep")
        if self._version == "3":
            self._flags = [ctypes.c_bool(), ctypes.c_bool(), ctypes.c_bool(), ctypes.c_double()]
            self._flag_refs = [ctypes.byref(x) for x in self._flags]

    def _bind1(self) -> None:
        """The FMI 1.0 functions called directly, with their C signatures (a binary without one of them is
        reported here, at instantiation)."""
        fmu = self._handle.fmu
        self._int_get = fmi1.function(fmu, "fmiGetInteger")
        self._int_set = fmi1.function(fmu, "fmiSetInteger")
        self._do_step = fmi1.function(fmu, "fmiDoStep")
        self._initialize1 = fmi1.function(fmu, "fmiInitializeSlave")

    def _instantiate2(self, log) -> None:
        from fmpy.fmi2 import (calloc, fmi2CallbackAllocateMemoryTYPE, fmi2CallbackFreeMemoryTYPE,
                               fmi2CallbackFunctions, fmi2CallbackLoggerTYPE, free)
        from fmpy.logging import addLoggerProxy

        logger = fmi1.logger_to(log)
        cb = fmi2CallbackFunctions()
        cb.logger = fmi2CallbackLoggerTYPE(logger)
        cb.allocateMemory = fmi2CallbackAllocateMemoryTYPE(calloc)
        cb.freeMemory = fmi2CallbackFreeMemoryTYPE(free)
        addLoggerProxy(ctypes.byref(cb))
        # kept alive for the life of the process, not of the instance: an FMU that failed fatally may still
        # log while the interpreter shuts down, and a freed callback there is a crash
        _CALLBACKS.append((cb, logger))
        # logging off: pythonfmu 0.7 reports a Python exception to the logger only with logging on, and that
        # path corrupts the interpreter (a crash at exit); our FMUs keep the message in a variable instead
        self._handle.fmu.instantiate(callbacks=cb, loggingOn=False)

    def _error_text(self) -> str:
        """Our FMUs' own error variable (the component's last error message), or ""."""
        fmu = self._handle.fmu
        if self._error_vr is None or fmu is None or not self._handle.instantiated:
            return ""
        try:
            text = fmu.getString([self._error_vr])[0]
        except Exception:
            return ""
        return text.decode("utf-8", "replace") if isinstance(text, bytes) else (text or "")

    def _log_text(self) -> str:
        """What the FMU said about a failure: our FMUs' error variable, else its last log messages."""
        msgs = [m for _, _, m in self._handle.log if m.strip()]
        own = self._error_text()
        if own:
            msgs.append(own)
        return (": " + " | ".join(msgs[-5:])) if msgs else ""

    def _check(self, status: int, what: str) -> None:
        if status > _OK_STATUS:
            label = {2: "discard", 3: "error", 4: "fatal", 5: "pending"}.get(status, str(status))
            raise FMUError(f"{self._where}: {what} failed (status {label}){self._log_text()}")

    # -- parameters and start values ---------------------------------------------------------------------
    def _write(self, var: Variable, refs: list[int], values: np.ndarray, what: str,
               names: list[str] = ()) -> None:
        """Set ``values`` (already checked against ``var``) through fmpy's typed setters; ``names``, the
        variables written (one per reference), tells FMI 1.0 negated aliases, whose base gets the opposite."""
        if self._negated and any(n in self._negated for n in names):
            values = np.array([(not x if var.type == "Boolean" else -x) if n in self._negated else x
                               for n, x in zip(names, values)], dtype=object)
        fmu = self._handle.fmu
        suffix = _CTYPES[self._version][var.fmi_type][1]
        setter = getattr(fmu, "set" + suffix)
        if var.type == "String":
            data = [str(x) for x in values]
        elif var.type == "Boolean":
            data = [bool(x) for x in values]
        elif var.type == "Integer":
            data = [int(x) for x in values]
        else:
            data = [float(x) for x in values]
        try:
            setter(refs, data)
        except Exception as exc:
            raise FMUError(f"{self._where}: setting {what} failed ({exc}){self._log_text()}") from None

    def set_parameter(self, name: str, value: Any) -> None:
        v = self._by_name.get(name)
        if v is None or v.causality != "parameter":
            known = ", ".join(x.name for x in self.variables if x.causality == "parameter") or "none"
            what = "no parameter" if v is None else f"{v.causality} (not a parameter)"
            raise FMUError(f"{self._where}: {what} {name!r}; its parameters: {known}")
        try:
            coerced = self._coerce_parameter(v, value)
        except ContractError as exc:
            raise FMUError(f"{self._where}: {exc}") from None
        if self._handle.initialised:
            raise FMUError(f"{self._where}: parameter {name!r} can only be set before setup()")
        first = {}
        for e in self._scalars[name]:
            first.setdefault(e.valueReference, e.name)   # one write per reference (FMI 2.0 aliases in a port)
        refs = list(first)
        values = np.atleast_1d(np.asarray(coerced, dtype=object))
        self._write(v, refs, values, f"parameter {name!r}", list(first.values()))
        self._before_init[f"parameter {name!r}"] = (v, refs, values)
        self.p[name] = coerced
        self.explicit.add(name)

    def _set_start_values(self, values: Mapping[str, Any]) -> None:
        """Start values of states and other variables with ``initial = "exact"`` (or ``"approx"``), set before
        initialisation as fmpy's ``start_values`` does; ``name`` is a variable of the FMU or a port ``X`` that
        stands for ``X[1]..X[n]``. Each value is checked against the variable's type and range."""
        if not values:
            return
        md = self.model_description
        by_name = {v.name: v for v in md.modelVariables}
        try:
            groups = regroup([v.name for v in md.modelVariables if not getattr(v, "dimensions", None)], self._where)
        except FlattenError:
            groups = {}
        problems = []
        for name, value in values.items():
            elems = [by_name[name]] if name in by_name else [by_name[n] for n in groups.get(name, [])]
            if not elems:
                problems.append(f"{name!r}: no such variable")
                continue
            first = elems[0]
            if first.causality == "parameter":
                problems.append(f"{name!r} is a parameter: set it under parameters")
                continue
            if first.causality == "input":
                problems.append(f"{name!r} is an input: connect it or give it a constant under [inputs]")
                continue
            refusal = self._no_start_value(first)
            if refusal:
                problems.append(f"{name!r} {refusal}")
                continue
            kind = KIND_OF.get(first.type)
            size = int(np.prod(first.shape)) if getattr(first, "dimensions", None) and first.shape else len(elems)
            integer = kind == "Integer"
            choices = tuple(sorted(int(i.value) for i in first.declaredType.items)) \
                if first.type == "Enumeration" and first.declaredType is not None and first.declaredType.items \
                else None
            var = Variable(name, "parameter", size, type=kind or "Real", fmi_type=first.type,
                           min=parse_number(declared_attribute(first, "min"), integer) if kind in ("Real", "Integer") else None,
                           max=parse_number(declared_attribute(first, "max"), integer) if kind in ("Real", "Integer") else None,
                           choices=choices)
            try:
                arr = check_value(var, value, f"{self._where}: start value of {name!r}")
            except ContractError as exc:
                problems.append(str(exc).replace(f"{self._where}: ", ""))
                continue
            self._write(var, [e.valueReference for e in elems], arr, f"the start value of {name!r}",
                        [e.name for e in elems])
            self._before_init[f"the start value of {name!r}"] = (var, [e.valueReference for e in elems], arr)
            self.start_values[name] = arr
        if problems:
            raise FMUError(f"{self._where}: start values: " + "; ".join(problems))

    def _no_start_value(self, var) -> str:
        """Why the FMU variable ``var`` takes no start value, or "" when it does."""
        if self._version == "1":
            # FMI 1.0 has no 'initial': a variable with a declared start value takes one before
            # fmiInitializeSlave (fmpy's rule for FMI 1.0 too)
            if var.variability == "constant" or var.start is None:
                return (f"(causality {var.causality}, variability {var.variability}) has no start value to set: "
                        "only FMI 1.0 variables that declare a start value do")
            return ""
        if var.variability == "constant" or var.initial not in ("exact", "approx"):
            return (f"(causality {var.causality}, variability {var.variability}, initial {var.initial}) has no "
                    "start value to set: only variables with initial = \"exact\" or \"approx\" do (states, for "
                    "instance)")
        return ""

    # -- the co-simulation calls -----------------------------------------------------------------------
    def _push_inputs(self) -> None:
        for tr in self._in:
            if tr.string:
                keep = []
                for name, a, b, _ in tr.ports:
                    for i, x in enumerate(self.u[name]):
                        keep.append(str(x).encode("utf-8"))
                        tr.values[a + i] = keep[-1]
            else:
                for name, a, b, _ in tr.ports:
                    tr.view[a:b] = self.u[name]
                if tr.negated is not None:
                    tr.negate()
            self._check(tr.set(self._c, *tr.args), tr.set_name)

    def _pull_outputs(self) -> None:
        for tr in self._out:
            self._check(tr.get(self._c, *tr.args), tr.get_name)
            if tr.string:
                for name, a, b, _ in tr.ports:
                    self.y[name] = np.array([(tr.values[i] or b"").decode("utf-8", "replace")
                                             for i in range(a, b)], dtype=object)
            else:
                if tr.negated is not None:
                    tr.negate()
                for name, a, b, dtype in tr.ports:
                    self.y[name] = tr.view[a:b].astype(dtype)

    def setup(self, t0: float = 0.0) -> None:
        h = self._handle
        if h.fmu is None:
            raise FMUError(f"{self._where}: the FMU was terminated; build a new component")
        if h.initialised:
            raise FMUError(f"{self._where}: setup() called twice (an FMU is initialised once; build a new one)")
        self.time = float(t0)
        fmu = h.fmu
        try:
            if self._version == "1":
                self._initialize_slave()
            elif self._version == "2":
                fmu.setupExperiment(startTime=self.time)
                for what, (var, refs, values) in self._before_init.items():
                    self._write(var, refs, values, what)
                fmu.enterInitializationMode()
            else:
                fmu.enterInitializationMode(startTime=self.time)
            if self._version != "1":
                self._push_inputs()
                fmu.exitInitializationMode()
        except FMUError:
            raise
        except Exception as exc:
            raise FMUError(f"{self._where}: initialisation failed ({exc}){self._log_text()}") from None
        if self._error_text():
            # one of our FMUs whose component failed to set up (it reports through its error variable)
            raise FMUError(f"{self._where}: initialisation failed{self._log_text()}")
        h.initialised = True
        self._pull_outputs()
        if self._phases_out is not None:
            # the phases the component decided on in its set-up (they may follow its parameters)
            bits = self._get_integer(self._phases_out)
            self.phases = frozenset(p for p, b in (("TM", 1), ("TO", 2)) if bits & b)
            self.holds_state_in_TO = bool(bits & 4)

    def _initialize_slave(self) -> None:
        """FMI 1.0: the inputs, then fmiInitializeSlave with no stop time (the master's run may end anywhere).
        There is no initialisation mode: parameters and start values were set after instantiation, and inputs
        are set before it, as FMI 1.0 allows."""
        self._push_inputs()
        self._check(self._initialize1(self._c, self.time, 0, 0.0), f"fmiInitializeSlave(tStart = {self.time:.9g} s)")

    def _get_integer(self, vr: int) -> int:
        vrs, val = (ctypes.c_uint * 1)(vr), (ctypes.c_int32 * 1)()
        args = (self._c, vrs, 1, val) + ((1,) if self._version == "3" else ())
        self._check(self._int_get(*args), "GetInteger")
        return int(val[0])

    def enter_phase(self, phase: str) -> None:
        """Passed to one of our FMUs through its phase input (the component's own ``enter_phase``)."""
        self.phase = phase
        if self._phase_in is not None and self._handle.initialised and self._handle.fmu is not None:
            vrs, val = (ctypes.c_uint * 1)(self._phase_in), (ctypes.c_int32 * 1)(int(phase == "TO"))
            args = (self._c, vrs, 1, val) + ((1,) if self._version == "3" else ())
            self._check(self._int_set(*args), "SetInteger")

    def do_step(self, t: float, h: float) -> None:
        """One DoStep. A stop request (FMI 2: ``fmi2Discard`` and the ``fmi2Terminated`` status true; FMI 3:
        ``terminateSimulation``, at the last successful time when it also returned early) reads the outputs
        where the FMU stopped and raises StopRequested; the master ends the run there."""
        self._push_inputs()
        if self._version == "1":
            status = self._do_step(self._c, float(t), float(h), 1)
            if status == _DISCARD:
                self._discard1(t, h)
        elif self._version == "2":
            status = self._do_step(self._c, float(t), float(h), 1)
            if status == _DISCARD and not self._error_text():   # (our FMUs report their failures by text)
                self._stop2(t, h)
        else:
            status = self._do_step(self._c, float(t), float(h), True, *self._flag_refs)
            if status <= _DISCARD and (self._flags[1].value or self._flags[2].value):
                self._stop3(t, h, status)
        self._check(status, f"DoStep(t = {t:.9g} s, h = {h:.3g} s)")
        self.time = t + h
        self._pull_outputs()

    def _discard1(self, t: float, h: float) -> None:
        """FMI 1.0's fmiDiscard: the slave computed part of the step only, and FMI 1.0 has no way to ask to
        terminate (FMI 2.0's fmi2Terminated): the step failed, at the time the slave reached when it tells it."""
        last = ctypes.c_double(t)
        try:
            told = fmi1.function(self._handle.fmu, "fmiGetRealStatus")(
                self._c, fmi1.LAST_SUCCESSFUL_TIME, ctypes.byref(last)) <= _OK_STATUS
        except Exception:
            told = False
        reached = f"it reached t = {last.value:.9g} s" if told else "fmiLastSuccessfulTime not available"
        raise FMUError(f"{self._where}: fmiDoStep(t = {t:.9g} s, h = {h:.3g} s) returned fmiDiscard ({reached}): "
                       f"the step was not completed{self._log_text()}")

    def _stop2(self, t: float, h: float) -> None:
        fmu = self._handle.fmu
        flag = ctypes.c_int(0)
        try:
            ok = c_function(fmu, "fmi2GetBooleanStatus")(self._c, _FMI2_TERMINATED, ctypes.byref(flag)) <= _OK_STATUS
        except Exception:
            ok = False
        if not (ok and flag.value):
            raise FMUError(f"{self._where}: DoStep(t = {t:.9g} s, h = {h:.3g} s) returned fmi2Discard without "
                           "asking to terminate (fmi2Terminated "
                           + ("false" if ok else "not available") + "): the step was not completed"
                           + self._log_text())
        last = ctypes.c_double(t)
        try:
            if c_function(fmu, "fmi2GetRealStatus")(self._c, _FMI2_LAST_SUCCESSFUL_TIME, ctypes.byref(last)) > _OK_STATUS:
                last.value = t
        except Exception:
            last.value = t
        self.time = min(max(float(last.value), t), t + h)
        self._pull_outputs()
        raise StopRequested(self.name, self.time, "fmi2Discard with fmi2Terminated")

    def _stop3(self, t: float, h: float, status: int) -> None:
        terminate, early, last = self._flags[1].value, self._flags[2].value, self._flags[3].value
        if not terminate:
            raise FMUError(f"{self._where}: fmi3DoStep(t = {t:.9g} s) returned early (at t = {last:.9g} s) "
                           "without asking to terminate, although early return was not allowed"
                           + self._log_text())
        self.time = min(max(float(last), t), t + h) if (early or status == _DISCARD) else t + h
        self._pull_outputs()
        raise StopRequested(self.name, self.time, "terminateSimulation" + (" (early return)" if early else ""))

    def terminate(self) -> None:
        h = self._handle
        if h.fmu is not None and h.initialised:
            try:
                h.fmu.terminate()
            except Exception:
                pass
        self._finalizer()

    # -- state -----------------------------------------------------------------------------------------
    def _require_state(self) -> None:
        if not self.can_get_set_state:
            why = "FMI 1.0 has no FMU state functions" if self._version == "1" else "canGetAndSetFMUstate is false"
            raise FMUError(f"{self._where}: the FMU cannot get/set its state ({why}): "
                           "rollback (iterative coupling) and state snapshots are impossible with it")

    def get_state(self) -> Any:
        self._require_state()
        state = ctypes.c_void_p()
        name = STATE_FUNCTIONS[self._version][0]
        self._check(c_function(self._handle.fmu, name)(self._c, ctypes.byref(state)), name)
        return (self.time, {k: v.copy() for k, v in self.u.items()}, {k: v.copy() for k, v in self.y.items()},
                FMUState(self, state))

    def set_state(self, snapshot: Any) -> None:
        self._require_state()
        t, u, y, handle = snapshot
        name = STATE_FUNCTIONS[self._version][1]
        self._check(c_function(self._handle.fmu, name)(self._c, handle.state), name)
        self.time = t
        self.u = {k: v.copy() for k, v in u.items()}
        self.y = {k: v.copy() for k, v in y.items()}

    def __repr__(self) -> str:
        return f"<FMUComponent {self.name!r} from {self.path}>"


def load_fmu_component(path: str | Path, name: str, params: Mapping[str, Any] | None = None,
                       start_values: Mapping[str, Any] | None = None, label: str | None = None) -> FMUComponent:
    """The FMU at ``path`` as the component ``name`` with parameters ``params`` and the start values of its
    states / ``initial = "exact"`` variables ``start_values`` (called by master/scenario/build.py); ``label`` names
    the file in messages instead of ``path``."""
    return FMUComponent(path, name, params, start_values, label)
