"""Scenario templates: a group of components and their connections written once, instantiated per id.

A scenario's ``[templates]`` table names shipped templates (``scenarios/templates/NAME.toml``) and the ids to
instantiate each for::

    [templates]
    bearing = ["0", "5"]      # bearing0 + damper0 + thermal0 and their connections, then the same for 5
    rubring = ["0", "5"]

A template file holds ``[components.*]`` tables and a ``connections`` list whose names and string values carry
``{id}``; a string value that is exactly ``"{id}"`` becomes the integer id when the id is all digits (the Table 3
number a bearing, damper, rub ring or thermal network takes by default: ids that are not such a number need their
``bearing``/``damper`` parameter given by the scenario). In the scenario itself an entry of ``[algorithm] order``
or ``[outputs] record`` that holds ``{NAME}`` (a template's name) stands for one entry per id of that template,
in the ids' order: ``"bearing{bearing}"``, ``"rotor.X_brg{bearing}"``.

Expansion follows composition (``extends``: ``[templates]`` merges key by key, a child's list replaces its base's),
so a scenario that extends another may change the ids. The instantiated components are the base of the scenario's
own tables of the same name (those merge on top: parameters key by key, any other key replaced); the instantiated
connections come first, and a scenario's connection into the same input replaces the template's. A template name
that is not shipped, an id that is not a string of letters, digits or ``_``, or a ``{NAME}`` of no template is a
one-line error.
"""
from __future__ import annotations

import copy
import re
from typing import Any, Mapping

from rotorcosim.components import toml_text
from rotorcosim.master.scenario.compose import CompositionError, Origins

from rotorcosim import scenarios

#: the shipped templates
FOLDER = scenarios.FOLDER / "templates"
ID = re.compile(r"^[A-Za-z0-9_]+$")


def shipped() -> list[str]:
    """The names of the shipped templates."""
    return sorted(p.stem for p in FOLDER.glob("*.toml"))


def _template(name: str, where: str) -> tuple[dict, str]:
    path = FOLDER / f"{name}.toml"
    if not re.match(r"^[A-Za-z0-9_]+$", name) or not path.is_file():
        raise CompositionError(f"{where}: [templates] {name!r} is not a template (shipped: {', '.join(shipped())})")
    return toml_text.loads(path.read_text()), str(path)


def _fill(value: Any, tid: str) -> Any:
    if isinstance(value, str):
        if value == "{id}" and tid.isdigit():
            return int(tid)
        return value.replace("{id}", tid)
    if isinstance(value, Mapping):
        return {_fill(k, tid): _fill(v, tid) for k, v in value.items()}
    if isinstance(value, list):
        return [_fill(v, tid) for v in value]
    return value


def _ids(templates: Any, where: str) -> dict[str, list[str]]:
    if not isinstance(templates, Mapping):
        raise CompositionError(f"{where}: [templates] must be a table of NAME = [ids], got {templates!r}")
    out = {}
    for name, ids in templates.items():
        if not isinstance(ids, list) or not all(isinstance(i, str) and ID.match(i) for i in ids):
            raise CompositionError(f"{where}: [templates] {name} must be a list of ids (strings of letters, digits "
                                   f"or _), got {ids!r}")
        if len(set(ids)) != len(ids):
            raise CompositionError(f"{where}: [templates] {name} lists an id twice: {ids!r}")
        out[name] = ids
    return out


def _expand_list(values: Any, ids: dict[str, list[str]], where: str) -> Any:
    """Entries holding ``{NAME}`` become one entry per id of template NAME."""
    if not isinstance(values, list):
        return values
    out = []
    for v in values:
        names = re.findall(r"\{([A-Za-z0-9_]+)\}", v) if isinstance(v, str) else []
        if not names:
            out.append(v)
            continue
        for n in names:
            if n not in ids:
                raise CompositionError(f"{where}: {v!r} names template {{{n}}}, which [templates] does not "
                                       f"instantiate (it has: {', '.join(ids) or 'none'})")
        if len(set(names)) > 1:
            raise CompositionError(f"{where}: {v!r} names two templates; one per entry")
        out += [v.replace(f"{{{names[0]}}}", i) for i in ids[names[0]]]
    return out


def expand(data: dict, origins: Origins, where: str) -> dict:
    """The composed scenario ``data`` with its ``[templates]`` instantiated (module docstring); ``origins`` is
    updated to name the template file of every component and connection it brings."""
    if "templates" not in data:
        return data
    data = dict(data)
    ids = _ids(data.pop("templates"), where)
    comps: dict[str, dict] = {}
    comp_src: dict[str, str] = {}
    cons: list = []
    con_src: list[str] = []
    for name, id_list in ids.items():
        tpl, path = _template(name, where)
        unknown = set(tpl) - {"components", "connections"}
        if unknown:
            raise CompositionError(f"{path}: a template holds [components.*] and connections only, not "
                                   f"{', '.join(sorted(unknown))}")
        # kind by kind (bearing0, bearing5, damper0, damper5...): the order of the components' tables
        for key, tid in [(k, i) for k in tpl.get("components", {}) for i in id_list]:
            for cname, spec in _fill({key: tpl["components"][key]}, tid).items():
                if cname in comps:
                    raise CompositionError(f"{where}: [templates] {name} id {tid!r} makes component {cname!r} "
                                           "a second time")
                comps[cname] = spec
                comp_src[cname] = path
        for tid in id_list:
            for con in _fill(tpl.get("connections", []), tid):
                cons.append(con)
                con_src.append(path)
    own = data.get("components")
    own = dict(own) if isinstance(own, Mapping) else {}
    out = {k: v for k, v in own.items() if k not in comps}      # the scenario's own (the rotor) first
    for cname, spec in comps.items():
        mine = own.get(cname)
        tpl_path = comp_src[cname]
        if not (isinstance(mine, Mapping) and ("implementation" in mine or "fmu" in mine)):
            origins.components[cname] = tpl_path
        for p in spec.get("parameters", {}):
            if not (isinstance(mine, Mapping) and p in (mine.get("parameters") or {})):
                origins.parameters[(cname, p)] = tpl_path
        if isinstance(mine, Mapping):
            spec = copy.deepcopy(spec)
            if "implementation" in mine or "fmu" in mine:
                for k in ("implementation", "fmu", "start"):
                    spec.pop(k, None)
            params = dict(spec.get("parameters", {}))
            if isinstance(mine.get("parameters"), Mapping):
                params.update(mine["parameters"])
            spec.update({k: v for k, v in mine.items() if k != "parameters"})
            if params:
                spec["parameters"] = params
        out[cname] = spec
    data["components"] = out
    mine_cons = data.get("connections") if isinstance(data.get("connections"), list) else []
    mine_src = list(origins.connections) if len(origins.connections) == len(mine_cons) else [where] * len(mine_cons)
    driven = {c.get("to") for c in mine_cons if isinstance(c, Mapping)}
    keep = [i for i, c in enumerate(cons) if c.get("to") not in driven]
    data["connections"] = [cons[i] for i in keep] + list(mine_cons)
    origins.connections = [con_src[i] for i in keep] + mine_src
    if isinstance(data.get("algorithm"), Mapping) and "order" in data["algorithm"]:
        data["algorithm"] = {**data["algorithm"],
                             "order": _expand_list(data["algorithm"]["order"], ids, f"{where}: [algorithm] order")}
    if isinstance(data.get("outputs"), Mapping) and "record" in data["outputs"]:
        data["outputs"] = {**data["outputs"],
                           "record": _expand_list(data["outputs"]["record"], ids, f"{where}: [outputs] record")}
    return data

