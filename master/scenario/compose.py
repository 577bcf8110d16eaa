"""Scenario composition: a scenario file that ``extends`` another one, and where each entry came from.

``[scenario] extends`` names a file (relative to the extending file) or a shipped scenario by name
(``extends = "toy_thermomechanical"``). The rules, applied from the base outwards (a chain of ``extends`` is composed base first):

* **components**: a child's ``[components.NAME]`` merges into the base's. ``implementation`` and ``fmu`` replace
  each other (a child giving one drops the base's other, and an inherited FMU's ``start`` values); ``parameters`` merge key by key; ``step`` is replaced;
  ``remove_parameters = ["p", ...]`` removes inherited parameters (each must exist, or it is an error).
* **connections**: a child's ``[[connections]]`` are added to the base's, not a replacement of the list; an
  entry whose ``to`` port the base already drives replaces the base's entry (an input has one source).
  ``[scenario] remove_connections = [...]`` removes inherited connections by name before the child's are
  added: a name is the driven input (``"node.P_in"``) or ``"src -> dst"``; each must match one.
* every other table (``scenario``, ``inputs``, ``algorithm``, ``schedule``, ``outputs``, ``results``) merges key
  by key, and any other value, lists included (``intervals``, ``record``, ``order``), is replaced; so is
  ``[schedule] cycle`` whole (a period, or a signal with its unit and angle: one choice, not keys to merge).
  ``[scenario] remove_keys = ["table.key", ...]`` removes inherited keys of those tables (each must exist), e.g.
  ``"schedule.speed_rpm"`` where the child gives a ``cycle`` instead.

:func:`compose` returns the composed dict, free of the composition keys (``extends``, ``remove_connections``,
``remove_parameters``), and an :class:`Origins` map that tells which file brought each component, parameter,
connection and input, so that an error found after composition can name the file to edit.
"""
from __future__ import annotations

import copy
import os
import re
import sys
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Mapping

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

from rotorcosim.components import toml_text
from rotorcosim.components.bounded_read import MAX_EXTENDS, read_text
from rotorcosim.components.contract import ContractError
from rotorcosim.master.scenario import templates


class ScenarioError(ContractError):
    """A scenario file that cannot be run; the message names the file and the key."""


#: an error of composition is a scenario error (the name says where it was found)
CompositionError = ScenarioError


@dataclass
class Origins:
    """Which file brought each entry of a composed scenario (paths as strings)."""

    components: dict[str, str] = field(default_factory=dict)            # who set implementation / fmu
    parameters: dict[tuple[str, str], str] = field(default_factory=dict)  # (component, parameter)
    connections: list[str] = field(default_factory=list)                # parallel to data["connections"]
    inputs: dict[str, str] = field(default_factory=dict)
    templated: set[str] = field(default_factory=set)                     # components a template made

    def component(self, name: str) -> str | None:
        """The file that chose component ``name``'s implementation, or None."""
        return self.components.get(name)

    def parameter(self, comp: str, param: str) -> str | None:
        """The file that set parameter ``param`` of ``comp`` (else the one that chose the component), or None."""
        return self.parameters.get((comp, param), self.components.get(comp))


#: composition keys, consumed here and never seen by the parser
SCENARIO_DIRECTIVES = ("extends", "remove_connections", "remove_keys")
COMPONENT_DIRECTIVES = ("remove_parameters",)


def connection_name(con: Mapping[str, Any]) -> str:
    """How a connection is named in messages and in ``remove_connections``: ``"src -> dst"``."""
    return f"{con.get('from')} -> {con.get('to')}"


def _merge(base: dict, top: Mapping) -> dict:
    out = dict(base)
    for k, v in top.items():
        out[k] = _merge(out[k], v) if isinstance(v, Mapping) and isinstance(out.get(k), Mapping) else v
    return out


def real_path(path: str | Path) -> Path:
    """The absolute path without symbolic links (``os.path.realpath``: a link loop is left as it is, for the
    caller's "not found", where ``Path.resolve`` raised RuntimeError on Python 3.11)."""
    return Path(os.path.realpath(Path(path).expanduser()))


def _load(path: Path) -> dict:
    if path.is_dir():
        raise IsADirectoryError(f"scenario file {path} is a folder, not a TOML file")
    if not path.is_file():
        raise FileNotFoundError(f"scenario file {path} " + ("is a symbolic link to nothing (dangling, or a loop)"
                                                            if path.is_symlink() else "not found"))
    try:
        return toml_text.loads(read_text(path, "scenario file"))
    except tomllib.TOMLDecodeError as exc:
        m = re.search(r"\(at line (\d+), column \d+\)", str(exc))
        where = f"{path}:{m.group(1)}" if m else str(path)
        raise ScenarioError(f"{where}: not valid TOML: {exc}") from None
    except UnicodeDecodeError as exc:
        raise ScenarioError(f"{path}: not a text file ({exc})") from None
    except OSError as exc:
        raise ScenarioError(f"{path}: cannot read it ({exc.strerror or exc})") from None


def _table(value: Any) -> Mapping:
    """``value`` if it is a table, else an empty one: composition looks only into tables of the right kind and
    leaves a value of the wrong kind where it is (``parameters = 3``), for the schema to name with its file and
    line."""
    return value if isinstance(value, Mapping) else {}


def _own(data: dict, origins: Origins, where: str) -> None:
    """Record ``where`` as the origin of every entry of a file that extends nothing."""
    for name, spec in _table(data.get("components")).items():
        origins.components[name] = where
        for p in _table(_table(spec).get("parameters")):
            origins.parameters[(name, p)] = where
    cons = data.get("connections")
    origins.connections = [where] * (len(cons) if isinstance(cons, list) else 0)
    origins.inputs = {ref: where for ref in _table(data.get("inputs"))}


def _str_list(value: Any, where: str, key: str) -> list[str]:
    if not isinstance(value, list) or not all(isinstance(v, str) for v in value):
        raise CompositionError(f"{where}: {key} must be a list of strings, got {value!r}")
    return value


def _components(base: dict, child: Mapping, origins: Origins, where: str) -> dict:
    out = copy.deepcopy(base)
    for name, spec in child.items():
        if not isinstance(spec, Mapping):
            out[name] = spec  # the parser reports it
            continue
        spec = dict(spec)
        remove = _str_list(spec.pop("remove_parameters", []), f"{where}: [components.{name}]", "remove_parameters")
        if name not in out or not isinstance(out[name], Mapping):
            if remove:
                raise CompositionError(f"{where}: [components.{name}] remove_parameters: the component is new "
                                       f"here, it inherits no parameter to remove")
            out[name] = spec
            origins.components[name] = where
            for p in _table(spec.get("parameters")):
                origins.parameters[(name, p)] = where
            continue
        merged = dict(out[name])
        if "implementation" in spec or "fmu" in spec:
            # a new implementation replaces the inherited one, whichever kind it was (with an FMU's start values)
            merged.pop("implementation", None)
            merged.pop("fmu", None)
            merged.pop("start", None)
            origins.components[name] = where
        params = dict(_table(merged.get("parameters")))
        for p in remove:
            if p not in params:
                raise CompositionError(f"{where}: [components.{name}] remove_parameters: {p!r} is not an "
                                       f"inherited parameter (inherited: {sorted(params) or 'none'})")
            del params[p]
            origins.parameters.pop((name, p), None)
        own = spec.pop("parameters", None)
        if own is not None and not isinstance(own, Mapping):
            raise CompositionError(f"{where}: [components.{name}] parameters: must be a table of name = value "
                                   f"(merged key by key into the inherited ones), got {type(own).__name__}")
        for p, v in _table(own).items():
            params[p] = v
            origins.parameters[(name, p)] = where
        merged.update(spec)
        if params or "parameters" in merged:
            merged["parameters"] = params
        out[name] = merged
    return out


def _connections(base: list, child: list, removes: list[str], origins: Origins, where: str) -> list:
    out = list(base)
    src = list(origins.connections)
    for name in removes:
        key = name.replace(" ", "")
        hits = [i for i, c in enumerate(out) if key in (str(c.get("to")), connection_name(c).replace(" ", ""))]
        if not hits:
            raise CompositionError(f"{where}: remove_connections: no inherited connection {name!r} (name one by "
                                   f"its driven input, e.g. 'node.P_in', or as 'src -> dst')")
        for i in reversed(hits):
            del out[i], src[i]
    for con in child:
        dst = con.get("to") if isinstance(con, Mapping) else None
        hit = next((i for i, c in enumerate(out) if dst is not None and c.get("to") == dst), None)
        if hit is None:
            out.append(con)
            src.append(where)
        else:  # the input has one source: the child's entry replaces the inherited one
            out[hit] = con
            src[hit] = where
    origins.connections = src
    return out


def _base_path(path: Path, ref: str) -> Path:
    """``extends`` names a file relative to ``path``'s folder, or a shipped scenario by name (no suffix)."""
    p = path.parent / ref
    if p.exists() or Path(ref).suffix:
        return p
    from rotorcosim import scenarios

    return scenarios.path(ref)


def compose(path: str | Path, _seen: tuple = ()) -> tuple[dict, Origins]:
    """The scenario file ``path`` with its ``extends`` chain composed; returns (data, origins)."""
    path = real_path(path)
    if path in _seen:
        raise CompositionError(f"{path}: 'extends' loops back on itself ({' -> '.join(map(str, _seen + (path,)))})")
    if len(_seen) >= MAX_EXTENDS:
        raise CompositionError(f"{_seen[0]}: its 'extends' chain reaches {path} after {len(_seen)} files, above the "
                               f"limit of {MAX_EXTENDS} files a scenario may extend")
    data = _load(path)
    where = str(path)
    head = data.get("scenario", {})
    if not isinstance(head, Mapping):
        raise CompositionError(f"{where}: [scenario] must be a table")
    head = dict(head)
    if isinstance(head.get("engine"), str) and head["engine"]:
        # the engine file is named relative to the file that names it
        head["engine"] = str(real_path(path.parent / head["engine"]))
    base_ref = head.pop("extends", None)
    removes = _str_list(head.pop("remove_connections", []), f"{where}: [scenario]", "remove_connections")
    remove_keys = _str_list(head.pop("remove_keys", []), f"{where}: [scenario]", "remove_keys")
    tpl = data.get("templates")
    if base_ref is None and tpl is None:
        if remove_keys:
            raise CompositionError(f"{where}: [scenario] remove_keys needs 'extends' (nothing is inherited)")
        if removes:
            raise CompositionError(f"{where}: [scenario] remove_connections needs 'extends' (nothing is inherited)")
        origins = Origins()
        _own(data, origins, where)
        for name, spec in _table(data.get("components")).items():
            if isinstance(spec, Mapping) and "remove_parameters" in spec:
                raise CompositionError(f"{where}: [components.{name}] remove_parameters needs 'extends' "
                                       f"(nothing is inherited)")
        if "scenario" in data:
            data["scenario"] = head
        return data, origins
    if base_ref is None:   # the instantiated templates are this file's base
        if remove_keys:
            raise CompositionError(f"{where}: [scenario] remove_keys needs 'extends' (nothing is inherited)")
        base, origins = {}, Origins()
    else:
        if not isinstance(base_ref, str):
            raise CompositionError(f"{where}: [scenario] extends must be a file name, got {base_ref!r}")
        base, origins = compose(_base_path(path, base_ref), _seen + (path,))
        base = _remove_keys(base, remove_keys, where)
    if tpl is not None:
        tpl = _merge(base.get("templates", {}), tpl) if isinstance(tpl, Mapping) else tpl
        base = _instantiate(_strip_templated(base, origins), tpl, origins, where)
    out = dict(base)
    for key, value in data.items():
        if key == "scenario":
            out["scenario"] = _merge(base.get("scenario", {}), head)
        elif key == "components" and isinstance(value, Mapping) and isinstance(base.get("components"), Mapping):
            out["components"] = _components(base["components"], value, origins, where)
        elif key == "connections" and isinstance(value, list):
            out["connections"] = _connections(base.get("connections", []), value, removes, origins, where)
            removes = []
        elif key == "inputs" and isinstance(value, Mapping):
            out["inputs"] = _merge(base.get("inputs", {}), value)
            origins.inputs.update({ref: where for ref in value})
        else:
            out[key] = _merge(base[key], value) if isinstance(value, Mapping) and isinstance(base.get(key), Mapping) \
                else value
            if key == "schedule" and isinstance(value, Mapping) and "cycle" in value and isinstance(out[key], dict):
                # one choice, a period or a signal (with its unit and angle): the child's replaces the base's
                out[key]["cycle"] = copy.deepcopy(value["cycle"])
    if removes:  # removals with no new connections
        out["connections"] = _connections(base.get("connections", []), [], removes, origins, where)
    if "scenario" not in data and "scenario" in base:
        out["scenario"] = dict(base["scenario"])
    if not _seen and "templates" in out:
        out = _expand_entries(out, origins, where)
    return out, origins


def _strip_templated(base: dict, origins: Origins) -> dict:
    """``base`` without the components and connections its templates made (a file that instantiates its own)."""
    if not origins.templated:
        return base
    out = dict(base)
    out["components"] = {k: v for k, v in _table(base.get("components")).items() if k not in origins.templated}
    for k in origins.templated:
        origins.components.pop(k, None)
    origins.parameters = {kp: v for kp, v in origins.parameters.items() if kp[0] not in origins.templated}
    keep = [i for i, src in enumerate(origins.connections) if not templates.is_template_file(src)]
    out["connections"] = [base.get("connections", [])[i] for i in keep]
    origins.connections = [origins.connections[i] for i in keep]
    origins.templated = set()
    return out


def _instantiate(base: dict, tpl: Any, origins: Origins, where: str) -> dict:
    """``base`` extended by the instantiated templates of ``tpl`` (templates.py), one virtual file per template."""
    try:
        files = templates.instances(tpl, where)
    except templates.TemplateError as exc:
        raise CompositionError(str(exc)) from None
    out = dict(base)
    for path, virtual in files:
        out["components"] = _components(_table(out.get("components")), virtual["components"], origins, path)
        out["connections"] = _connections(out.get("connections", []), virtual["connections"], [], origins, path)
        origins.templated |= set(virtual["components"])
    return out


def _expand_entries(data: dict, origins: Origins, where: str) -> dict:
    """The composed scenario without its [templates] table: the ``{NAME}`` entries of ``[algorithm] order`` and
    ``[outputs] record`` expanded per id, and the components in the order the file gave its own (the rotor) first,
    then the instantiated ones."""
    out = dict(data)
    tpl = out.pop("templates")
    try:
        for table, key in (("algorithm", "order"), ("outputs", "record")):
            if isinstance(out.get(table), Mapping) and key in out[table]:
                out[table] = {**out[table], key: templates.expand_list(out[table][key], tpl,
                                                                     f"{where}: [{table}] {key}")}
    except templates.TemplateError as exc:
        raise CompositionError(str(exc)) from None
    comps = _table(out.get("components"))
    out["components"] = {**{k: v for k, v in comps.items() if k not in origins.templated},
                         **{k: v for k, v in comps.items() if k in origins.templated}}
    return out


def _remove_keys(base: dict, keys: list[str], where: str) -> dict:
    """``base`` without the inherited ``"table.key"`` entries of ``remove_keys`` (each must exist)."""
    if not keys:
        return base
    out = dict(base)
    for ref in keys:
        table, _, key = ref.partition(".")
        if table in ("components", "connections", "scenario") or not key:
            raise CompositionError(f"{where}: [scenario] remove_keys: {ref!r} is not 'table.key' of inputs, algorithm, "
                                   "schedule, outputs or results")
        if not isinstance(out.get(table), Mapping) or key not in out[table]:
            raise CompositionError(f"{where}: [scenario] remove_keys: no inherited key {ref!r}")
        out[table] = {k: v for k, v in out[table].items() if k != key}
    return out
