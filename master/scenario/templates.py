"""Scenario templates: a group of components and their connections written once, instantiated per id.

A scenario's ``[templates]`` table names shipped templates (``scenarios/templates/NAME.toml``) and the ids to
instantiate each for::

    [templates]
    bearing = ["A", "B"]      # bearingA + damperA + thermalA and their connections, then the same for B
    rubring = ["0", "5"]

A template file holds ``[components.*]`` tables and a ``connections`` list whose names and string values carry
``{id}``; a string value that is exactly ``"{id}"`` becomes the integer id when the id is all digits (the Table 3
number a bearing, damper, rub ring or thermal network takes by default: ids that are not such a number need their
``bearing``/``damper`` parameter given by the scenario). In the scenario itself an entry of ``[algorithm] order``
or ``[outputs] record`` that holds ``{NAME}`` (a template's name) stands for one entry per id of that template,
in the ids' order: ``"bearing{bearing}"``, ``"rotor.X_brg{bearing}"``.

A scenario with ``[templates]`` reads the instantiated templates as a base of its own (one virtual file per
template, read after its ``extends`` base: master/scenario/compose.py), so its own tables and the
files that extend it change an instantiated component or connection as they would an inherited one
(``[components.bearingB]``, ``remove_parameters``, ``remove_connections``). A file that gives ``[templates]``
again (``extends`` merges the table key by key, a list replaced) drops what its base's templates made and
instantiates its own ids. The ``{NAME}`` entries are expanded last, with the composed ``[templates]``. A template
name that is not shipped, an id that is not a string of letters, digits or ``_``, or a ``{NAME}`` of no template
is a one-line error.
"""
from __future__ import annotations

import re
from pathlib import Path
from typing import Any, Mapping

from rotorcosim import scenarios
from rotorcosim.components import toml_text
from rotorcosim.components.bounded_read import MAX_TEMPLATE_IDS, read_text
from rotorcosim.components.contract import ContractError

#: the shipped templates
FOLDER = scenarios.FOLDER / "templates"
ID = re.compile(r"^[A-Za-z0-9_]+$")


class TemplateError(ContractError):
    """A bad [templates] entry (compose.py reports it as a scenario error)."""


def shipped() -> list[str]:
    """The names of the shipped templates."""
    return sorted(p.stem for p in FOLDER.glob("*.toml"))


def is_template_file(path: str | None) -> bool:
    """True for a path of a shipped template (an origin of a component or a connection)."""
    try:
        return path is not None and Path(path).resolve().parent == FOLDER.resolve()
    except (OSError, TypeError):
        return False


def _template(name: str, where: str) -> tuple[dict, str]:
    path = FOLDER / f"{name}.toml"
    if not ID.match(name) or not path.is_file():
        raise TemplateError(f"{where}: [templates] {name!r} is not a template (shipped: {', '.join(shipped())})")
    tpl = toml_text.loads(read_text(path, "template file"))
    unknown = set(tpl) - {"components", "connections"}
    if unknown:
        raise TemplateError(f"{path}: a template holds [components.*] and connections only, not "
                            f"{', '.join(sorted(unknown))}")
    return tpl, str(path)


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


def ids_of(templates: Any, where: str) -> dict[str, list[str]]:
    """The ``[templates]`` table checked: template name -> its ids."""
    if not isinstance(templates, Mapping):
        raise TemplateError(f"{where}: [templates] must be a table of NAME = [ids], got {templates!r}")
    out = {}
    for name, ids in templates.items():
        if not isinstance(ids, list) or not all(isinstance(i, str) and ID.match(i) for i in ids):
            raise TemplateError(f"{where}: [templates] {name} must be a list of ids (strings of letters, digits "
                                f"or _), got {ids!r}")
        if len(ids) > MAX_TEMPLATE_IDS:
            raise TemplateError(f"{where}: [templates] {name} lists {len(ids)} ids, above the limit of "
                                f"{MAX_TEMPLATE_IDS} ids a template may be instantiated for")
        if len(set(ids)) != len(ids):
            raise TemplateError(f"{where}: [templates] {name} lists an id twice: {ids!r}")
        out[name] = ids
    return out


def instances(templates: Any, where: str) -> list[tuple[str, dict]]:
    """(template file, its components and connections for all its ids) per template of ``[templates]``: the
    files a scenario with templates extends. Components kind by kind (bearingA, bearingB, damperA, damperB...),
    connections id by id."""
    out = []
    made: dict[str, str] = {}
    for name, id_list in ids_of(templates, where).items():
        tpl, path = _template(name, where)
        comps = {}
        for key, tid in [(k, i) for k in tpl.get("components", {}) for i in id_list]:
            for cname, spec in _fill({key: tpl["components"][key]}, tid).items():
                if cname in made:
                    raise TemplateError(f"{where}: [templates] {name} id {tid!r} makes component {cname!r}, which "
                                        f"template {made[cname]} makes too")
                made[cname] = name
                comps[cname] = spec
        cons = [con for tid in id_list for con in _fill(tpl.get("connections", []), tid)]
        out.append((path, {"components": comps, "connections": cons}))
    return out


def expand_list(values: Any, templates: Any, where: str) -> Any:
    """Entries holding ``{NAME}`` become one entry per id of template NAME, in the ids' order."""
    if not isinstance(values, list):
        return values
    ids = ids_of(templates, where) if templates is not None else {}
    out = []
    for v in values:
        names = re.findall(r"\{([A-Za-z0-9_]+)\}", v) if isinstance(v, str) else []
        if not names:
            out.append(v)
            continue
        for n in names:
            if n not in ids:
                raise TemplateError(f"{where}: {v!r} names template {{{n}}}, which [templates] does not "
                                    f"instantiate (it has: {', '.join(ids) or 'none'})")
        if len(set(names)) > 1:
            raise TemplateError(f"{where}: {v!r} names two templates; one per entry")
        out += [v.replace(f"{{{names[0]}}}", i) for i in ids[names[0]]]
    return out
