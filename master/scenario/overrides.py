"""Changing a loaded scenario: parameter values (``--set comp.param=value``, :meth:`Scenario.set`) and
implementations (``--swap comp=IMPL|FILE.fmu``, :meth:`Scenario.swap`). Both return a new scenario.

:func:`parse_set` is the one parser of ``comp.param=value`` texts; ``values=True`` reads a comma-separated list
of values (a sweep's ``comp.param=v1,v2,...``).
"""
from __future__ import annotations

import copy
import math
import sys
from pathlib import Path
from typing import Any, Mapping

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

from rotorcosim.components import registry
from rotorcosim.components import toml_text
from rotorcosim.components.contract import ContractError
from rotorcosim.components.value_types import check_value

from rotorcosim.master.scenario.compose import ScenarioError, real_path
from rotorcosim.master.scenario.engine import drop_undeclared, set_bound

#: where a change made by the API or the command line is said to come from, in error messages
API_ORIGIN = "Scenario.set/swap"


def _literal(text: str, what: str) -> Any:
    """A value written as in TOML (``42``, ``1e-5``, ``true``, ``"a"``, ``[1, 2]``); a bare word is a string."""
    text = text.strip()
    if not text:
        raise ValueError(f"{what}: an empty value")
    try:
        parsed = toml_text.loads(f"v = {text}")
    except tomllib.TOMLDecodeError as exc:
        if toml_text.BEYOND_64_BITS in str(exc):  # a number, not a bare word
            raise ValueError(f"{what}: {exc}") from None
        if any(c in text for c in "[]{}\"'=,"):
            raise ValueError(f"{what}: {text!r} is not a value (a number, true/false, a string or [a, list])") \
                from None
        return text
    if len(parsed) != 1:  # "10\nR = 5" read as TOML sets a second key, which would be dropped without a word
        raise ValueError(f"{what}: {text!r} is not one value (a number, true/false, a string or [a, list])")
    value = parsed["v"]
    try:
        _check_value(what, value)
    except ValueError:
        raise ValueError(f"{what}: {text!r} is not a finite number") from None
    return value


def parse_set(text: str, values: bool = False) -> tuple[str, Any]:
    """``"comp.param=value"`` -> (``"comp.param"``, value). With ``values=True`` the right-hand side is a
    comma-separated list (``"osc.F0=10,20"`` -> (``"osc.F0"``, [10, 20])), a
    bracketed ``[...]`` staying one value."""
    key, eq, rhs = str(text).partition("=")
    key = key.strip()
    what = f"--set {text!r}"
    comp, dot, param = key.partition(".")
    if not eq or not dot or not comp or not param:
        raise ValueError(f"{what}: expected COMP.PARAM=" + ("V1,V2,..." if values else "VALUE"))
    if not values:
        return key, _literal(rhs, what)
    items, depth, cur = [], 0, ""
    for ch in rhs:  # split on the commas outside brackets
        depth += ch == "["
        depth -= ch == "]"
        if ch == "," and depth == 0:
            items.append(cur)
            cur = ""
        else:
            cur += ch
    items.append(cur)
    return key, [_literal(v, what) for v in items]


def parse_swap(text: str) -> tuple[str, str]:
    """``"comp=IMPL"`` or ``"comp=FILE.fmu"`` -> (component, implementation)."""
    comp, eq, impl = str(text).partition("=")
    if not eq or not comp.strip() or not impl.strip():
        raise ValueError(f"--swap {text!r}: write it component=implementation (a registry name, module:Class "
                         f"or a .fmu file)")
    return comp.strip(), impl.strip()


def _check_value(ref: str, value: Any) -> None:
    if isinstance(value, (bool, str)):
        return
    if isinstance(value, (int, float)):
        try:
            finite = math.isfinite(value)
        except OverflowError:  # an int beyond any float (the API takes Python ints as they come)
            finite = False
        if not finite:
            raise ValueError(f"{ref}: value {value!r} is not finite")
        return
    if isinstance(value, (list, tuple)):
        for v in value:
            _check_value(ref, v)
        return
    try:  # numpy scalars and arrays
        import numpy as np

        arr = np.asarray(value, dtype=float)
        if not np.all(np.isfinite(arr)):
            raise ValueError(f"{ref}: value {value!r} is not finite")
        return
    except (TypeError, ValueError):
        raise ValueError(f"{ref}: unsupported value {value!r}") from None


def _component(sc, name: str):
    if name not in sc.components:
        raise ScenarioError(f"scenario {sc.name!r}: no component {name!r} (components: {', '.join(sc.components)})")
    return sc.components[name]


def declared_parameters(spec) -> dict | None:
    """The parameters the component's implementation declares, name -> Variable (None when not known before it
    is built: FMUs)."""
    if spec.implementation is None:
        return None
    cls = registry.lookup(spec.implementation, spec.folder)
    return {v.name: v for v in getattr(cls, "variables", ()) if v.causality == "parameter"}


def _plain(value: Any) -> Any:
    if hasattr(value, "tolist"):
        return value.tolist()
    if isinstance(value, tuple):
        return list(value)
    return value


def resolve_file_parameters(impl: str, params: dict, folder_of, lookup_folder: str | None, names=None) -> None:
    """The implementation's file parameters (``Component.file_parameters``) in ``params`` made absolute paths,
    a relative one read from ``folder_of(param)``: the folder of the scenario file that wrote it, or the working
    folder for a value given on the command line or to :meth:`Scenario.set` (a sweep's case may run elsewhere)."""
    try:
        cls = registry.lookup(impl, lookup_folder)
    except (ContractError, ImportError, AttributeError):  # the schema or the build names it
        return
    for p in getattr(cls, "file_parameters", ()):
        value = params.get(p)
        if isinstance(value, str) and value and (names is None or p in names):
            path = Path(value).expanduser()
            params[p] = str(real_path(path if path.is_absolute() else Path(folder_of(p)) / path))


def apply_set(sc, values: Mapping[str, Any], origin: str = API_ORIGIN):
    """A copy of ``sc`` with ``{"comp.param": value}`` applied (see :meth:`Scenario.set`)."""
    if not isinstance(values, Mapping):
        raise TypeError(f"set() takes a dict {{'component.parameter': value}}, got {type(values).__name__}")
    out = copy.deepcopy(sc)
    for ref, value in values.items():
        comp, dot, param = str(ref).partition(".")
        if not dot or not comp or not param:
            raise ValueError(f"set: {ref!r} must be written 'component.parameter'")
        spec = _component(out, comp)
        _check_value(ref, value)
        try:
            known = declared_parameters(spec)
        except ContractError as exc:
            raise ScenarioError(f"set {ref}: {exc}") from None
        if known is not None and param not in known:
            raise ScenarioError(f"set {ref}: {spec.implementation} ({comp}) has no parameter {param!r} "
                                f"(its parameters: {', '.join(known)})")
        if known is not None:  # the value's kind and size now, not when the run (or a sweep's case) builds it
            try:
                check_value(known[param], value, f"set {ref}")
            except ContractError as exc:
                raise ScenarioError(str(exc)) from None
        if getattr(out, "engine", None) is not None and ref in out.engine.targets:
            if spec.implementation is not None and isinstance(value, str) and value:
                tmp = {param: value}   # a file parameter (the engine file itself) from the working folder
                resolve_file_parameters(spec.implementation, tmp, lambda p: Path.cwd(), spec.folder, (param,))
                value = tmp[param]
            set_bound(out, ref, value, origin)
            spec.parameters[param] = _plain(value)     # the value as given (a speed's rev/min round trip aside)
            out.edits.append({"set": ref, "value": _plain(value), "origin": origin,
                              "engine_quantity": out.engine.targets[ref]})
            continue
        spec.parameters[param] = _plain(value)
        spec.param_origins[param] = origin
        out.edits.append({"set": f"{comp}.{param}", "value": spec.parameters[param], "origin": origin})
        if spec.implementation is not None:
            resolve_file_parameters(spec.implementation, spec.parameters, lambda p: Path.cwd(), spec.folder, (param,))
    return out


def apply_swap(sc, component: str, implementation: str, parameters: Mapping[str, Any] | None = None,
               origin: str = API_ORIGIN):
    """A copy of ``sc`` with ``component``'s implementation replaced (see :meth:`Scenario.swap`)."""
    out = copy.deepcopy(sc)
    spec = _component(out, component)
    impl = str(implementation)
    if impl.lower().endswith(".fmu"):
        path = real_path(impl)
        if path.is_dir():
            raise IsADirectoryError(f"swap {component}: FMU file {path} is a folder, not an FMU file")
        if not path.is_file():
            raise FileNotFoundError(f"swap {component}: FMU file {path} not found")
        spec.fmu, spec.implementation = str(path), None
        if parameters is None:
            # the engine's values the FMU does not declare, as for a plug-in (an FMU from another tool names its
            # parameters its own way); an FMU that cannot be read keeps them: building it names the problem
            from rotorcosim.fmus.description import parameter_names

            declared = parameter_names(path)
            if declared is not None:
                drop_undeclared(getattr(out, "engine", None), component, spec.parameters, declared)
                spec.param_origins = {k: v for k, v in spec.param_origins.items() if k in spec.parameters}
    elif Path(impl).exists() and not registry.is_plugin_path(impl) and impl not in registry.available():
        # a file that is no FMU: said so, not listed against the registry's names
        raise ScenarioError(f"swap {component}: {impl} is a {'folder' if Path(impl).is_dir() else 'file'}, not an "
                            "FMU (a file whose name ends in .fmu), a registry name or module:Class")
    else:
        # a plug-in the swap names is imported from the working folder first, as a swapped FMU's path is read
        # from it (the folder of the file the component came from, a shipped template's, is not the user's)
        folder = str(Path.cwd()) if registry.is_plugin_path(impl) else spec.folder
        try:
            registry.lookup(impl, folder)  # fail now, naming the implementation, not at build time
        except ContractError as exc:
            raise ScenarioError(f"swap {component}: {exc}") from None
        spec.implementation, spec.fmu, spec.folder = impl, None, folder
        if parameters is None:
            # the values the component took from the engine that its new implementation does not declare
            drop_undeclared(getattr(out, "engine", None), component, spec.parameters, set(declared_parameters(spec)))
            spec.param_origins = {k: v for k, v in spec.param_origins.items() if k in spec.parameters}
        spec.start = {}  # start values belong to the FMU it replaces
    spec.origin = origin
    if parameters is not None:
        for k, v in parameters.items():
            _check_value(f"{component}.{k}", v)
        spec.parameters = {k: _plain(v) for k, v in parameters.items()}
        spec.param_origins = {k: origin for k in parameters}
    out.edits.append({"swap": component, "implementation": spec.fmu or spec.implementation, "origin": origin,
                      **({"parameters": dict(spec.parameters)} if parameters is not None else {})})
    return out


def set_level(sc, value: float, ref: str | None, *, name: str = "level", option: str = "--level",
              unit: str = "", label: str = "level", key: str = "level_parameter", settings=()) -> None:
    """Set the scenario's level parameter ``ref`` (``comp.param``, named by its ``[results] key``) to ``value``
    (SI, finite, >= 0) and record it in its edits as ``{name: value, "parameter": ref, "origin": option}``;
    ``settings`` are the ``comp.param`` names the same command sets with ``--set``: naming the level parameter
    there too is an error (one of the two values would be dropped without a word). The case's own words
    (``name``, ``option``, ``unit``, ``label``) come from its level (master/case.py)."""
    u = f" {unit}" if unit else ""
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not (value >= 0.0) \
            or value == float("inf"):
        raise ValueError(f"{option} must be a finite {label} >= 0{u}, got {value}")
    if not ref:
        raise ValueError(f"scenario {sc.name!r} has no [results] {key}: {option} does not apply")
    if ref in settings:
        raise ValueError(f"{option} and --set {ref}=... both give the {label} ({ref}, the scenario's [results] "
                         f"{key}): give one of them")
    comp, _, param = ref.partition(".")
    if comp not in sc.components:
        raise ValueError(f"[results] {key} {ref!r}: no component {comp!r}")
    old = sc.components[comp].parameters.get(param)
    sc.components[comp].parameters[param] = float(value)
    sc.edits.append({name: float(value), "parameter": ref, "origin": option})
    if old is None or float(old) != float(value):
        # the run's name says what was run (a scenario named NAME_<level> becomes NAME_<new level>)
        sc.name = f"{sc.name.rsplit('_', 1)[0] if sc.name.rsplit('_', 1)[-1].isdigit() else sc.name}_{value:g}"


def edited_values(sc) -> dict[str, Any]:
    """``{"comp.param": value}``: the values set on ``sc`` since it was loaded, read from its edits (those of
    :func:`apply_set` and :func:`set_level`; a swap sets no value), the last of each in their order."""
    out: dict[str, Any] = {}
    for e in sc.edits:
        if "set" in e:
            out[e["set"]] = e["value"]
        elif "parameter" in e:   # set_level's {name: value, "parameter": ref, "origin": option}
            values = [v for k, v in e.items() if k not in ("parameter", "origin")]
            if len(values) == 1:
                out[e["parameter"]] = values[0]
    return out
