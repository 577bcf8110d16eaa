"""An FMU's model description read and checked, and its variables as contract variables (the first step of
using an FMU as a component: fmus/importer.py).

``describe(path)`` checks the archive (fmus/safezip.py) and its modelDescription.xml (FMI 1.0, 2.0 or 3.0, value
references that do not collide) and returns it parsed by fmpy; ``ports_of`` turns its variables into the
contract's ports: FMI 1.0 / 2.0 scalars ``X[1]..X[n]`` regrouped into a vector port (flatten.py), FMI 3.0 arrays
as vector ports, each with its kind, unit (unit definitions kept: units.py), range, enumeration items and start.
fmpy reads an FMI 1.0 description into FMI 2.0's terms: causality ``internal`` is ``local``, and a variable of
variability ``parameter`` is a parameter.
"""
from __future__ import annotations

import io
import re
import zipfile
import zlib
from dataclasses import replace
from pathlib import Path
from typing import Any, Mapping

import numpy as np

from rotorcosim.components.bounded_read import TooLarge, read_entry
from rotorcosim.components.contract import ContractError, Variable
from rotorcosim.components.value_types import KIND_OF, UNCARRIED

from rotorcosim.fmus import fmi1
from rotorcosim.fmus.flatten import FlattenError, regroup
from rotorcosim.fmus.units import BASE
from rotorcosim.fmus.safezip import ArchiveError, check_entries, open_zip



class FMUError(ContractError):
    """An FMU that cannot be used as a component; the message names the file and the problem."""


def parse_number(text, integer: bool):
    """A declared attribute's text (``min``, ``max``) as an int or a float, None if not declared."""
    if text is None or text == "":
        return None
    return int(text) if integer else float(text)


def _start_values(var: Variable, text: Any) -> Any:
    """An FMU variable's start attribute (text; space-separated for an FMI 3.0 array) as a contract start."""
    kind = var.type
    if kind in UNCARRIED:
        return None
    if text is None:
        one = {"String": "", "Boolean": False, "Integer": 0}.get(kind, 0.0)
        if kind == "Integer" and var.choices:
            one = min(var.choices)
        return one if var.size == 1 else [one] * var.size
    parts = [text] if kind == "String" or var.size == 1 else str(text).split()

    def conv(x):
        if kind == "Real":
            return float(x)
        if kind == "Integer":
            return int(x)
        if kind == "Boolean":
            return str(x).strip().lower() in ("true", "1")
        return x
    values = [conv(x) for x in parts]
    if len(values) == 1 and var.size > 1:
        values = values * var.size
    return values[0] if var.size == 1 else values


def describe(path: str | Path):
    """Check ``path`` as an FMU and return ``(model description xml bytes, fmpy ModelDescription)``.

    Raises FMUError for: a file that is not a zip, unsafe entries, no modelDescription.xml, an unreadable model
    description, a version other than FMI 1.0 / 2.0 / 3.0, an FMU without co-simulation (model exchange only)."""
    from fmpy import read_model_description

    path = Path(path)
    try:
        with open_zip(path, "FMU") as zf:
            check_entries(zf, str(path))
            if "modelDescription.xml" not in zf.namelist():
                raise FMUError(f"{path}: no modelDescription.xml at the top of the archive: not an FMU")
            try:
                xml = read_entry(zf, "modelDescription.xml", str(path))
            except (zipfile.BadZipFile, zlib.error, EOFError, NotImplementedError, RuntimeError) as exc:
                raise FMUError(f"{path}: modelDescription.xml is damaged in the archive ({exc})") from None
    except (ArchiveError, TooLarge) as exc:
        raise FMUError(str(exc)) from None
    _check_description_text(path, xml)
    try:
        md = read_model_description(io.BytesIO(_zip_of({"modelDescription.xml": xml})), validate=False)
    except Exception as exc:  # lxml / fmpy parse errors: an unreadable description
        raise FMUError(f"{path}: modelDescription.xml cannot be read: {exc}") from None
    if not _imported_version(md.fmiVersion):
        raise FMUError(f"{path}: FMI {md.fmiVersion} FMU: {_VERSIONS}")
    _check_value_references(md, str(path), fmi1.aliases(xml) if md.fmiVersion == "1.0" else {})
    if md.coSimulation is None:
        if md.modelExchange is not None:
            raise FMUError(f"{path}: the FMU offers model exchange only, no co-simulation interface: rotorcosim "
                           "needs a co-simulation FMU (one that integrates itself in DoStep)")
        if getattr(md, "scheduledExecution", None) is not None:
            raise FMUError(f"{path}: the FMU offers FMI 3.0 scheduled execution only (neither co-simulation nor "
                           "model exchange): rotorcosim needs a co-simulation FMU (one that integrates itself "
                           "in DoStep); scheduled execution needs a scheduler of model partitions and clocks")
        raise FMUError(f"{path}: the FMU declares no interface (no co-simulation, model exchange or scheduled "
                       "execution element)")
    ident = md.coSimulation.modelIdentifier
    if not ident or not isinstance(ident, str) or ident in (".", "..") or any(c in ident for c in "/\\\0:"):
        # the binary loaded is binaries/<platform>/<modelIdentifier>.so: a path there ('../../x', '/lib/x')
        # loaded a library from outside the archive, past the extraction's checks of every entry
        raise FMUError(f"{path}: CoSimulation modelIdentifier {ident!r} is not a file name (FMI: a C identifier "
                       "naming the binary inside the FMU)")
    step = md.defaultExperiment.stepSize if md.defaultExperiment is not None else None
    if step is not None:
        # the component's preferred step (and an SSP's schedule step) when nothing else gives one: "abc" was a
        # bare "could not convert string to float", 0 or -1 a schedule error naming neither the FMU nor the key
        try:
            value = float(step)
        except (TypeError, ValueError):
            value = float("nan")
        if not (0.0 < value < float("inf")):
            raise FMUError(f"{path}: modelDescription.xml: DefaultExperiment stepSize={step!r} is not a positive "
                           "number of seconds")
    return xml, md


_VERSIONS = "rotorcosim imports FMI 1.0, 2.0 and 3.0 co-simulation FMUs"


def parameter_names(path: str | Path) -> set[str] | None:
    """The parameters an FMU declares, by port name (``X[1]..X[n]`` regrouped as ``X``), read from its model
    description without loading it; None when the file is no readable FMU (building the component then names the
    problem). What a scenario's engine values are checked against when an FMU takes a bound component's place."""
    from rotorcosim.fmus.model_description import AnnotationError, read_annotation

    try:
        xml, md = describe(path)
        variables, _ = ports_of(md, str(path), read_annotation(xml, str(path)).hidden)
    except (FMUError, AnnotationError, OSError):
        return None
    return {v.name for v in variables if v.causality == "parameter"}


def _imported_version(version: str) -> bool:
    return version in ("1.0", "2.0") or version.startswith("3.")


def _check_description_text(path: Path, xml: bytes) -> None:
    """Before fmpy reads it: no DTD (entity bombs, external entities), and an FMI version we import."""
    if b"<!DOCTYPE" in xml or b"<!ENTITY" in xml:
        raise FMUError(f"{path}: modelDescription.xml declares a DTD or entities, which FMI never needs: refused")
    m = re.search(rb'fmiVersion\s*=\s*["\']([^"\']*)["\']', xml)
    version = m.group(1).decode("ascii", "replace") if m else None
    start = re.search(rb"<fmiModelDescription\b[^>]*>", xml)
    if version is None and start is not None and b"fmiVersion" not in start.group(0):
        # a whole start tag without the attribute: fmpy's own message was "'NoneType' object has no attribute
        # 'startswith'"
        raise FMUError(f"{path}: modelDescription.xml gives no fmiVersion: not an FMI 1.0, 2.0 or 3.0 model "
                       "description")
    if version is not None and not _imported_version(version):
        raise FMUError(f"{path}: FMI {version} FMU: {_VERSIONS}")
    if version == "1.0" and start is not None:
        # fmpy reads these two unchecked: an FMI 2.0 description labelled 1.0 was "int() argument must be ..."
        missing = [a for a in ("modelIdentifier", "numberOfContinuousStates")
                   if not re.search(rb"\s" + a.encode() + rb"\s*=", start.group(0))]
        if missing:
            raise FMUError(f"{path}: modelDescription.xml (fmiVersion 1.0) gives no {' and no '.join(missing)} on "
                           "fmiModelDescription, which FMI 1.0 requires")


def _check_value_references(md, where: str, declared_aliases: Mapping[str, str]) -> None:
    """Two variables of one type may share a valueReference only as aliases of one output; an input or a
    parameter sharing one with another variable would be set through the other's name. An FMI 1.0 variable
    declared an alias (``declared_aliases``) shares its reference on purpose, with an input too."""
    seen: dict[tuple, object] = {}
    for v in md.modelVariables:
        key = (v.type, v.valueReference)
        other = seen.get(key)
        if other is None:
            seen[key] = v
            continue
        if v.name in declared_aliases or other.name in declared_aliases:
            continue
        if {other.causality, v.causality} & {"input", "parameter"}:
            raise FMUError(f"{where}: variables {other.name!r} ({other.causality}) and {v.name!r} ({v.causality}) "
                           f"share the {v.type} valueReference {v.valueReference}: the FMU's variables collide")


def _zip_of(entries: Mapping[str, bytes]) -> bytes:
    """A zip in memory (fmpy reads a model description from a zip or a folder, not from bare bytes)."""
    import zipfile

    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w") as zf:
        for k, v in entries.items():
            zf.writestr(k, v)
    return buf.getvalue()


def _unit_definitions(md) -> dict[str, tuple]:
    """``{unit name: (base-unit exponents, factor, offset)}`` from the FMU's <UnitDefinitions>."""
    out = {}
    for u in getattr(md, "unitDefinitions", None) or []:
        b = u.baseUnit
        if b is None:
            continue
        exps = {k: int(getattr(b, k)) for k in BASE if int(getattr(b, k) or 0)}
        out[u.name] = (exps, float(b.factor), float(b.offset))
    return out


def declared_attribute(e, attr: str):
    """A variable's attribute ``attr`` (``unit``, ``min``, ``max``), or its declared type's when it gives none."""
    value = getattr(e, attr, None)
    if value is None and e.declaredType is not None:
        value = getattr(e.declaredType, attr, None)
    return value


def ports_of(md, where: str, hidden=frozenset(), defaults=None) -> tuple[list[Variable], dict[str, list]]:
    """Contract variables from the FMU's variables, and ``{port: [fmpy variables by index]}``.

    FMI 1.0 / 2.0 scalars ``X[1]..X[n]`` are regrouped into a port ``X`` of size n; an FMI 3.0 array variable is
    one port of size prod(shape) (row-major, as FMI serialises arrays). Every type of FMI 1.0 / 2.0 / 3.0
    co-simulation is a port (value_types.py); Binary and Clock ports are declared but carry no value. All the problems found
    are reported at once. ``hidden``: variables that are not ports (our FMUs' schedule phase variables).

    An input may stay unconnected (``has_default``, keeping its start value, as fmpy, Ecos and OMSimulator do)
    when every element declares a start value; ``defaults``, for an FMU exported by rotorcosim, names the inputs
    whose native component declared a default instead (the others stay required, as they are natively)."""
    by_name = {v.name: v for v in md.modelVariables
               if v.causality in ("parameter", "input", "output") and v.name not in hidden}
    units = _unit_definitions(md)
    problems: list[str] = []
    arrays = {n for n, v in by_name.items() if getattr(v, "dimensions", None)}
    try:
        groups = regroup([n for n in by_name if n not in arrays], where)
    except FlattenError as exc:
        raise FMUError(str(exc)) from None
    for n in arrays:
        groups[n] = [n]
    variables, scalars = [], {}
    for port, names in groups.items():
        elems = [by_name[n] for n in names]
        first = elems[0]
        bad = False
        for attr in ("causality", "type"):
            values = {getattr(e, attr) for e in elems}
            if len(values) > 1:
                problems.append(f"the elements of {port!r} differ in {attr} ({sorted(values)}): they cannot "
                                "form one port")
                bad = True
        unit_names = {declared_attribute(e, "unit") or "1" for e in elems}
        if len(unit_names) > 1:
            problems.append(f"the elements of {port!r} have different units {sorted(unit_names)}")
            bad = True
        kind = KIND_OF.get(first.type)
        if kind is None:
            problems.append(f"variable {first.name!r} has type {first.type}, which is not an FMI "
                            "co-simulation type")
            bad = True
        if bad:
            continue
        size = len(elems)
        if first.name in arrays:
            shape = tuple(int(x) for x in (first.shape or ()))
            size = int(np.prod(shape)) if shape else 1
            if size < 1:
                problems.append(f"array {first.name!r} has shape {shape}: no elements")
                continue
        unit = unit_names.pop()
        choices = None
        if first.type == "Enumeration" and first.declaredType is not None and first.declaredType.items:
            choices = tuple(sorted(int(i.value) for i in first.declaredType.items))
        integer = kind == "Integer"
        lo = parse_number(declared_attribute(first, "min"), integer) if kind in ("Real", "Integer") else None
        hi = parse_number(declared_attribute(first, "max"), integer) if kind in ("Real", "Integer") else None
        if choices and lo is None:
            lo, hi = min(choices), max(choices)
        shell = Variable(port, first.causality, size, unit, first.description or "", None, kind, first.type,
                         lo, hi, choices, units.get(unit))
        try:
            starts = [_start_values(Variable(port, first.causality, 1 if first.name not in arrays else size, unit,
                                             type=kind, fmi_type=first.type, choices=choices), e.start)
                      for e in elems]
            start = starts[0] if len(starts) == 1 else starts
            if first.causality != "input":
                optional = False
            elif defaults is not None:
                optional = port in defaults
            else:
                optional = all(e.start is not None for e in elems)
            variables.append(replace(shell, start=start, has_default=optional))
        except (ContractError, ValueError) as exc:
            problems.append(f"{port!r}: {exc}")
            continue
        scalars[port] = elems
    if problems:
        raise FMUError(f"{where}: " + "; ".join(problems))
    return variables, scalars
