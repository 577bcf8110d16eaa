"""Any FMI 2.0 (or 3.0) co-simulation FMU as a rotorcosim component (through fmpy).

``load_fmu_component(path, name, params)`` is what the master calls for a scenario component given as
``fmu = "file.fmu"``. The FMU is checked and extracted into a fresh temporary folder (safezip.py: nothing can be
written outside it), its shared library is loaded and instantiated at once (so a binary that does not load is
reported when the system is built, not in the middle of a run), and its scalar variables are regrouped into the
contract's vector ports (``X[1]..X[n]`` -> port ``X`` of size n, flatten.py) with their units and descriptions.

Mapping onto the contract (components/contract.py):

* parameters are set right away (before initialisation, as FMI requires); unknown names, wrong sizes or
  non-parameters are clear errors naming the FMU;
* ``setup(t0)``: (setupExperiment,) enterInitializationMode, inputs, exitInitializationMode, outputs read;
* ``do_step(t, h)``: all inputs set, DoStep, all outputs read into ``self.y`` (the master reads ``y``);
* ``get_state``/``set_state``: Get/SetFMUstate when the FMU declares
  ``canGetAndSetFMUstate``; otherwise a clear error (rollback is impossible with that FMU);
* ``phases`` and ``preferred_step``: from rotorcosim's vendor annotation when the FMU is one of ours, else
  ``{"TM"}`` and the DefaultExperiment stepSize (model_description.py documents the annotation).

The hot path calls the FMU's C functions directly with preallocated ctypes buffers (fmpy's convenience
wrappers build new arrays on every call): the FMU boundary should cost what FMI costs, not what the glue costs.
FMI 3.0 co-simulation FMUs are read the same way for scalar variables of types Float64 (Real), Int32
(Integer), Boolean and String; FMI 3.0 array variables and other integer widths are refused with a clear error.
"""
from __future__ import annotations

import ctypes
import io
import os
import shutil
import sys
import weakref
from collections import deque
from pathlib import Path
from typing import Any, Mapping

import numpy as np

from rotorcosim.components.contract import Component, ContractError, Variable

from . import model_description as mdx
from .flatten import FlattenError, regroup
from .safezip import ArchiveError, check_entries, open_zip, safe_extract

_OK_STATUS = 1  # OK = 0, Warning = 1 (FMI 2.0 and 3.0): anything above is a failure
_TYPE_OF = {"Real": "Real", "Integer": "Integer", "Enumeration": "Integer", "Boolean": "Boolean", "String": "String",
            "Float64": "Real", "Int32": "Integer"}
#: per FMI version: contract type -> (ctypes value type, set function, get function); the state functions
_API = {
    "2": {"Real": (ctypes.c_double, "fmi2SetReal", "fmi2GetReal"),
          "Integer": (ctypes.c_int, "fmi2SetInteger", "fmi2GetInteger"),
          "Boolean": (ctypes.c_int, "fmi2SetBoolean", "fmi2GetBoolean"),
          "state": ("fmi2GetFMUstate", "fmi2SetFMUstate", "fmi2FreeFMUstate"),
          "setters": {"Real": "setReal", "Integer": "setInteger", "Boolean": "setBoolean", "String": "setString"}},
    "3": {"Real": (ctypes.c_double, "fmi3SetFloat64", "fmi3GetFloat64"),
          "Integer": (ctypes.c_int32, "fmi3SetInt32", "fmi3GetInt32"),
          "Boolean": (ctypes.c_bool, "fmi3SetBoolean", "fmi3GetBoolean"),
          "state": ("fmi3GetFMUState", "fmi3SetFMUState", "fmi3FreeFMUState"),
          "setters": {"Real": "setFloat64", "Integer": "setInt32", "Boolean": "setBoolean", "String": "setString"}},
}


#: logger callbacks handed to FMUs (see _instantiate2)
_CALLBACKS: list = []


class FMUError(ContractError):
    """An FMU that cannot be used as a component; the message names the file and the problem."""


def _convert_start(typ: str, text: str | None) -> Any:
    if text is None:
        return "" if typ == "String" else 0.0
    if typ == "Real":
        return float(text)
    if typ == "Integer":
        return int(text)
    if typ == "Boolean":
        return text.strip().lower() in ("true", "1")
    return text


def describe(path: str | Path):
    """Check ``path`` as an FMU and return ``(model description xml bytes, fmpy ModelDescription)``.

    Raises FMUError for: a file that is not a zip, unsafe entries, no modelDescription.xml, an unreadable model
    description, a version other than FMI 2.0 / 3.0, an FMU without co-simulation (model exchange only)."""
    from fmpy import read_model_description

    path = Path(path)
    try:
        with open_zip(path, "FMU") as zf:
            check_entries(zf, str(path))
            if "modelDescription.xml" not in zf.namelist():
                raise FMUError(f"{path}: no modelDescription.xml at the top of the archive: not an FMU")
            xml = zf.read("modelDescription.xml")
    except ArchiveError as exc:
        raise FMUError(str(exc)) from None
    try:
        md = read_model_description(io.BytesIO(_zip_of({"modelDescription.xml": xml})), validate=False)
    except Exception as exc:  # lxml / fmpy parse errors: an unreadable description
        raise FMUError(f"{path}: modelDescription.xml cannot be read: {exc}") from None
    if md.fmiVersion != "2.0" and not md.fmiVersion.startswith("3."):
        raise FMUError(f"{path}: FMI {md.fmiVersion} FMU: rotorcosim imports FMI 2.0 and 3.0 co-simulation FMUs")
    if md.coSimulation is None:
        raise FMUError(f"{path}: the FMU offers model exchange only, no co-simulation interface: rotorcosim "
                       "needs a co-simulation FMU (one that integrates itself in DoStep)")
    return xml, md


def _zip_of(entries: Mapping[str, bytes]) -> bytes:
    """A zip in memory (fmpy reads a model description from a zip or a folder, not from bare bytes)."""
    import zipfile

    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w") as zf:
        for k, v in entries.items():
            zf.writestr(k, v)
    return buf.getvalue()


def ports_of(md, where: str, hidden=frozenset()) -> tuple[list[Variable], dict[str, list]]:
    """Contract variables regrouped from the FMU's scalars, and ``{port: [fmpy variables by index]}``.

    ``hidden``: variables that are not ports (our FMUs' schedule phase variables)."""
    by_name = {v.name: v for v in md.modelVariables
               if v.causality in ("parameter", "input", "output") and v.name not in hidden}
    try:
        groups = regroup(by_name, where)
    except FlattenError as exc:
        raise FMUError(str(exc)) from None
    variables, scalars = [], {}
    for port, names in groups.items():
        elems = [by_name[n] for n in names]
        first = elems[0]
        for attr in ("causality", "type"):
            values = {getattr(e, attr) for e in elems}
            if len(values) > 1:
                raise FMUError(f"{where}: the elements of {port!r} differ in {attr} ({sorted(values)}): "
                               "they cannot form one port")
        units = {e.unit or (e.declaredType.unit if e.declaredType is not None else None) or "1" for e in elems}
        if len(units) > 1:
            raise FMUError(f"{where}: the elements of {port!r} have different units {sorted(units)}")
        typ = _TYPE_OF.get(first.type)
        if md.fmiVersion.startswith("3.") and first.type == "Enumeration":
            typ = None
        if getattr(first, "dimensions", None):
            raise FMUError(f"{where}: variable {first.name!r} is an FMI 3.0 array: not supported (use scalars "
                           "named X[1]..X[n])")
        if typ is None:
            raise FMUError(f"{where}: variable {first.name!r} has type {first.type}, which rotorcosim cannot map")
        if first.causality != "parameter" and typ == "String":
            raise FMUError(f"{where}: {first.causality} {port!r} is a String: only parameters may be strings")
        starts = [_convert_start(typ, e.start) for e in elems]
        start = starts[0] if len(starts) == 1 else starts
        try:
            variables.append(Variable(port, first.causality, len(elems), units.pop(), first.description or "",
                                      start, typ))
        except ContractError as exc:
            raise FMUError(f"{where}: {exc}") from None
        scalars[port] = elems
    return variables, scalars


class _Handle:
    """What must be released when the component goes away: kept apart from the component for weakref.finalize."""

    def __init__(self, folder: Path, annotation: mdx.Annotation, version: str):
        self.folder = folder
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
                    getattr(fmu, f"fmi{self.version}FreeInstance")(fmu.component)
                fmu.freeLibrary()
            except Exception:  # best effort while tearing down
                pass
        self.instantiated = False
        _forget_python_modules(self.folder, self.annotation)
        shutil.rmtree(self.folder, ignore_errors=True)


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


class _FMUState:
    """An FMU state pointer, freed with the FMU when it is no longer referenced."""

    def __init__(self, comp: "FMUComponent", state):
        self.state = state
        self._finalizer = weakref.finalize(self, _free_state, comp._handle, state)


def _free_state(handle: _Handle, state) -> None:
    fmu = handle.fmu
    if fmu is not None and handle.instantiated:
        try:
            fmu._functions[_API[handle.version]["state"][2]](fmu.component, ctypes.byref(state))
        except Exception:
            pass


class _Transfer:
    """Preallocated value references and values of one FMI type, for a set of ports."""

    def __init__(self, typ: str, ports: list[tuple[str, list[int]]], ctype):
        self.typ = typ
        self.ports = []
        vrs = []
        for name, refs in ports:
            self.ports.append((name, len(vrs), len(vrs) + len(refs)))
            vrs.extend(refs)
        self.n = len(vrs)
        self.vr = (ctypes.c_uint * self.n)(*vrs)
        self.values = (ctype * self.n)()
        self.view = np.ctypeslib.as_array(self.values)


class FMUComponent(Component):
    """An FMI 2.0 / 3.0 co-simulation FMU following the component contract."""

    def __init__(self, path: str | Path, name: str = "component", parameters: Mapping[str, Any] | None = None):
        self.path = Path(path)
        self.name = name
        where = f"FMU {self.path} (component {name!r})"
        self._where = where
        xml, md = describe(self.path)
        self.model_description = md
        ann = mdx.read_annotation(xml)
        variables, self._scalars = ports_of(md, where, ann.hidden)
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
        self.can_get_set_state = bool(md.coSimulation.canGetAndSetFMUstate)
        self.p = {v.name: v.start for v in self.variables if v.causality == "parameter"}
        self.u = {v.name: v.start_array() for v in self.variables if v.causality == "input"}
        self.y = {v.name: v.start_array() for v in self.variables if v.causality == "output"}
        self.state = {}
        self.time = 0.0
        self._version = "3" if md.fmiVersion.startswith("3.") else "2"
        self._api = _API[self._version]
        self._in = self._transfers("input", where)
        self._out = self._transfers("output", where)
        try:
            folder = safe_extract(self.path, "FMU", prefix="rcs_fmu_")
        except ArchiveError as exc:
            raise FMUError(str(exc)) from None
        self._handle = _Handle(folder, ann, self._version)
        self._finalizer = weakref.finalize(self, self._handle.release)
        try:
            self._instantiate(md, where)
            for key, value in (parameters or {}).items():
                self.set_parameter(key, value)
        except BaseException:
            self._finalizer()
            raise

    # -- loading ---------------------------------------------------------------------------------------
    def _transfers(self, causality: str, where: str) -> list[_Transfer]:
        by_type: dict[str, list] = {}
        for v in self.variables:
            if v.causality == causality:
                by_type.setdefault(v.type, []).append((v.name, [e.valueReference for e in self._scalars[v.name]]))
        return [_Transfer(t, ports, self._api[t][0]) for t, ports in sorted(by_type.items())]

    def _instantiate(self, md, where: str) -> None:
        from fmpy.fmi2 import FMU2Slave
        from fmpy.fmi3 import FMU3Slave

        h = self._handle
        ident = md.coSimulation.modelIdentifier
        binary = h.folder / "binaries"
        cwd = os.getcwd()
        try:
            if self._version == "2":
                h.fmu = FMU2Slave(guid=md.guid, unzipDirectory=str(h.folder), modelIdentifier=ident,
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
            if self._version == "2":
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
        f = h.fmu._functions
        self._c = h.fmu.component
        self._set = {t: f[self._api[t][1]] for t in ("Real", "Integer", "Boolean")}
        self._get = {t: f[self._api[t][2]] for t in ("Real", "Integer", "Boolean")}
        self._do_step = f[f"fmi{self._version}DoStep"]
        if self._version == "3":
            self._flags = [ctypes.c_bool(), ctypes.c_bool(), ctypes.c_bool(), ctypes.c_double()]
            self._flag_refs = [ctypes.byref(x) for x in self._flags]

    def _instantiate2(self, log) -> None:
        from fmpy.fmi2 import (calloc, fmi2CallbackAllocateMemoryTYPE, fmi2CallbackFreeMemoryTYPE,
                               fmi2CallbackFunctions, fmi2CallbackLoggerTYPE, free)
        from fmpy.logging import addLoggerProxy

        def logger(env, instance, status, category, message):
            log.append((int(status), (category or b"").decode("utf-8", "replace"),
                        (message or b"").decode("utf-8", "replace")))

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

    # -- parameters ------------------------------------------------------------------------------------
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
        refs = [e.valueReference for e in self._scalars[name]]
        fmu = self._handle.fmu
        values = list(np.atleast_1d(coerced)) if v.type != "String" else [coerced]
        convert = {"Real": float, "Integer": int, "Boolean": bool, "String": str}[v.type]
        try:
            getattr(fmu, self._api["setters"][v.type])(refs, [convert(x) for x in values])
        except Exception as exc:
            raise FMUError(f"{self._where}: setting parameter {name!r} failed ({exc}){self._log_text()}") from None
        self.p[name] = coerced
        self.explicit.add(name)

    # -- the co-simulation calls -----------------------------------------------------------------------
    def _push_inputs(self) -> None:
        for tr in self._in:
            for name, a, b in tr.ports:
                tr.view[a:b] = self.u[name]
            args = (self._c, tr.vr, tr.n, tr.values) + ((tr.n,) if self._version == "3" else ())
            self._check(self._set[tr.typ](*args), self._api[tr.typ][1])

    def _pull_outputs(self) -> None:
        for tr in self._out:
            args = (self._c, tr.vr, tr.n, tr.values) + ((tr.n,) if self._version == "3" else ())
            self._check(self._get[tr.typ](*args), self._api[tr.typ][2])
            for name, a, b in tr.ports:
                self.y[name] = tr.view[a:b].astype(float)

    def setup(self, t0: float = 0.0) -> None:
        h = self._handle
        if h.fmu is None:
            raise FMUError(f"{self._where}: the FMU was terminated; build a new component")
        if h.initialised:
            raise FMUError(f"{self._where}: setup() called twice (an FMU is initialised once; build a new one)")
        self.time = float(t0)
        fmu = h.fmu
        try:
            if self._version == "2":
                fmu.setupExperiment(startTime=self.time)
                fmu.enterInitializationMode()
            else:
                fmu.enterInitializationMode(startTime=self.time)
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

    def _get_integer(self, vr: int) -> int:
        vrs, val = (ctypes.c_uint * 1)(vr), (self._api["Integer"][0] * 1)()
        args = (self._c, vrs, 1, val) + ((1,) if self._version == "3" else ())
        self._check(self._get["Integer"](*args), self._api["Integer"][2])
        return int(val[0])

    def enter_phase(self, phase: str) -> None:
        """Passed to one of our FMUs through its phase input (the component's own ``enter_phase``)."""
        self.phase = phase
        if self._phase_in is not None and self._handle.initialised and self._handle.fmu is not None:
            vrs, val = (ctypes.c_uint * 1)(self._phase_in), (self._api["Integer"][0] * 1)(int(phase == "TO"))
            args = (self._c, vrs, 1, val) + ((1,) if self._version == "3" else ())
            self._check(self._set["Integer"](*args), self._api["Integer"][1])

    def do_step(self, t: float, h: float) -> None:
        self._push_inputs()
        if self._version == "2":
            status = self._do_step(self._c, float(t), float(h), 1)
        else:
            status = self._do_step(self._c, float(t), float(h), True, *self._flag_refs)
            if status <= _OK_STATUS and (self._flags[1].value or self._flags[2].value):
                raise FMUError(f"{self._where}: fmi3DoStep(t = {t:.9g} s) returned early or asked to terminate "
                               f"(at t = {self._flags[3].value:.9g} s): not supported{self._log_text()}")
        self._check(status, f"DoStep(t = {t:.9g} s, h = {h:.3g} s)")
        self.time = t + h
        self._pull_outputs()

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
            raise FMUError(f"{self._where}: the FMU cannot get/set its state (canGetAndSetFMUstate is false): "
                           "rollback (iterative coupling) and state snapshots are impossible with it")

    def get_state(self) -> Any:
        self._require_state()
        state = ctypes.c_void_p()
        name = self._api["state"][0]
        self._check(self._handle.fmu._functions[name](self._c, ctypes.byref(state)), name)
        return (self.time, {k: v.copy() for k, v in self.u.items()}, {k: v.copy() for k, v in self.y.items()},
                _FMUState(self, state))

    def set_state(self, snapshot: Any) -> None:
        self._require_state()
        t, u, y, handle = snapshot
        name = self._api["state"][1]
        self._check(self._handle.fmu._functions[name](self._c, handle.state), name)
        self.time = t
        self.u = {k: v.copy() for k, v in u.items()}
        self.y = {k: v.copy() for k, v in y.items()}

    def __repr__(self) -> str:
        return f"<FMUComponent {self.name!r} from {self.path}>"


def load_fmu_component(path: str | Path, name: str, params: Mapping[str, Any] | None = None) -> FMUComponent:
    """The FMU at ``path`` as the component ``name`` with parameters ``params`` (called by master/scenario.py)."""
    return FMUComponent(path, name, params)
