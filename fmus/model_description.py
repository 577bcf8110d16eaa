"""Finish pythonfmu's modelDescription.xml, and read back what rotorcosim puts in it.

pythonfmu writes variables without units, a random GUID, the build time, and a ModelStructure without
InitialUnknowns (fmpy's validation rejects it: outputs with ``initial="calculated"`` must be listed there).
:func:`finish` rewrites it deterministically from the component's declared variables:

* ``<UnitDefinitions>`` with the SI base-unit exponents of every unit used (see units.py), and the ``unit``
  attribute on each Real (dimensionless ``"1"``: none);
* descriptions on every variable (pythonfmu drops empty ones);
* ``<DefaultExperiment stepSize>`` = the component's preferred communication step;
* ``<VendorAnnotations><Tool name="rotorcosim"><Component .../>``: the implementation name, the phases
  (``"TM"``, ``"TO"``, comma-separated; as declared before set-up), the preferred step, the private code
  package and slave module of the bundle (the importer uses these to tidy ``sys.modules`` when the FMU is
  freed), the names of the phase input / phases output / last-error variables (slave_template.py), and the
  inputs that may stay unconnected (``defaultInputs``: those the native component declares ``has_default``;
  other tools' FMUs may leave every input with a start value unconnected, ours keep the native rule);
* ``<ModelStructure>``: Outputs and InitialUnknowns, both listing every output;
* a GUID that is a hash of the FMU's content (same content, same GUID), no generation date.
"""
from __future__ import annotations

import math
import re
import uuid
import xml.etree.ElementTree as ET
from dataclasses import dataclass

from rotorcosim.components.contract import PHASES

from rotorcosim.fmus.units import BASE, base_units, is_dimensionless

TOOL = "rotorcosim"
_ORDER = ("UnitDefinitions", "TypeDefinitions", "LogCategories", "DefaultExperiment", "VendorAnnotations",
          "ModelVariables", "ModelStructure")


def _fmt(x: float) -> str:
    return repr(float(x))


def unit_element(name: str) -> ET.Element:
    """The ``<Unit>`` element of the unit ``name``, with its SI base-unit exponents and factor where they are known."""
    unit = ET.Element("Unit", {"name": name})
    parsed = base_units(name)
    if parsed is not None:
        exps, factor = parsed
        attrib = {k: str(exps[k]) for k in BASE if exps.get(k)}
        if factor != 1.0:
            attrib["factor"] = _fmt(factor)
        ET.SubElement(unit, "BaseUnit", attrib)
    return unit


def finish(xml: bytes, variables: list[dict], *, implementation: str, phases: list[str], preferred_step: float,
           package: str, slave_module: str, content_hash: str, phase_input: str = "",
           phases_output: str = "", error_variable: str = "", default_inputs: tuple[str, ...] = ()) -> bytes:
    """The finished modelDescription.xml (bytes) for pythonfmu's ``xml`` and our ``variables`` (config dicts)."""
    root = ET.fromstring(xml)
    by_name = {}
    for v in variables:
        size = v["size"]
        names = [v["name"]] if size == 1 else [f"{v['name']}[{i + 1}]" for i in range(size)]
        for n in names:
            by_name[n] = v
    mv = root.find("ModelVariables")
    outputs = []
    units = set()
    for index, sv in enumerate(mv.findall("ScalarVariable"), start=1):
        v = by_name[sv.get("name")]
        if v["description"]:
            sv.set("description", v["description"])
        if sv.get("causality") == "input" and sv[0].tag != "Real":
            sv.set("variability", "discrete")
        typ = sv[0]
        if typ.tag == "Real" and not is_dimensionless(v["unit"]):
            # attribute order: unit first, then pythonfmu's start (cosmetic, but keeps files diff-able)
            start = typ.attrib.pop("start", None)
            typ.set("unit", v["unit"])
            if start is not None:
                typ.set("start", start)
            units.add(v["unit"])
        if sv.get("causality") == "output":
            outputs.append(index)
    # drop the children we regenerate, then re-insert everything in the schema's order
    for tag in ("UnitDefinitions", "DefaultExperiment", "VendorAnnotations", "ModelStructure"):
        for el in root.findall(tag):
            root.remove(el)
    new = {}
    if units:
        ud = ET.Element("UnitDefinitions")
        for u in sorted(units):
            ud.append(unit_element(u))
        new["UnitDefinitions"] = ud
    new["DefaultExperiment"] = ET.Element("DefaultExperiment", {"startTime": "0.0", "stepSize": _fmt(preferred_step)})
    va = ET.Element("VendorAnnotations")
    tool = ET.SubElement(va, "Tool", {"name": TOOL})
    own = {"implementation": implementation, "phases": ",".join(sorted(phases)),
           "preferredStep": _fmt(preferred_step), "package": package, "slaveModule": slave_module,
           "phaseInput": phase_input, "phasesOutput": phases_output, "errorVariable": error_variable}
    if default_inputs:   # (written only when there are some: the other components' FMUs stay as they were)
        own["defaultInputs"] = ",".join(default_inputs)
    ET.SubElement(tool, "Component", own)
    new["VendorAnnotations"] = va
    ms = ET.Element("ModelStructure")
    if outputs:
        for tag in ("Outputs", "InitialUnknowns"):
            block = ET.SubElement(ms, tag)
            for i in outputs:
                ET.SubElement(block, "Unknown", {"index": str(i)})
    new["ModelStructure"] = ms
    children = {c.tag: c for c in list(root)}
    for c in list(root):
        root.remove(c)
    cosim = children.pop("CoSimulation")
    root.append(cosim)
    children.update(new)
    for tag in _ORDER:
        if tag in children:
            root.append(children[tag])
    root.attrib.pop("generationDateAndTime", None)
    root.set("guid", "{" + str(uuid.uuid5(uuid.NAMESPACE_URL, f"rotorcosim:{content_hash}")) + "}")
    ET.indent(root, space="  ")
    return ET.tostring(root, encoding="UTF-8", xml_declaration=True) + b"\n"


@dataclass
class Annotation:
    """What an FMU exported by rotorcosim says about itself (None fields: not one of ours)."""

    implementation: str | None = None
    phases: frozenset[str] | None = None
    preferred_step: float | None = None
    package: str | None = None
    slave_module: str | None = None
    phase_input: str | None = None
    phases_output: str | None = None
    error_variable: str | None = None
    #: the inputs that may stay unconnected (keeping their start values)
    default_inputs: frozenset[str] = frozenset()

    @property
    def hidden(self) -> set[str]:
        """FMU variables that carry the schedule, not component ports."""
        return {n for n in (self.phase_input, self.phases_output) if n}


class AnnotationError(ValueError):
    """Our vendor annotation in a model description that says something we cannot act on."""


#: the names :func:`finish` gives the bundle's private package and slave module; the importer deletes modules
#: of these names from ``sys.modules`` (``_purge_cached``), so any other name (``numpy``, ``rotorcosim``) is
#: refused rather than purged
_PACKAGE = re.compile(r"_rcs_[A-Za-z0-9_]+")
_SLAVE_MODULE = re.compile(r"rcs_slave_[A-Za-z0-9_]+")


def read_annotation(xml: bytes, where: str = "modelDescription.xml") -> Annotation:
    """Our vendor annotation from a modelDescription.xml, or an empty Annotation when there is none.

    Its values are checked (AnnotationError naming ``where``): phases among TM / TO (``phases="XX"`` made a
    component that no interval ever stepped), a finite positive preferred step (``"abc"`` was a bare
    ValueError, ``0`` accepted), and the bundle's module names."""
    root = ET.fromstring(xml)
    for tool in root.findall("VendorAnnotations/Tool"):
        if tool.get("name") != TOOL:
            continue
        comp = tool.find("Component")
        if comp is None:
            continue
        what = f"{where}: vendor annotation of {TOOL}"
        phases = comp.get("phases")
        chosen = frozenset(p.strip() for p in phases.split(",") if p.strip()) if phases is not None else None
        if chosen is not None and (not chosen or not chosen <= set(PHASES)):
            raise AnnotationError(f"{what}: phases={phases!r} must name one or both of {', '.join(PHASES)}")
        step = comp.get("preferredStep")
        try:
            preferred = float(step) if step is not None else None
        except ValueError:
            preferred = math.nan
        if preferred is not None and not (math.isfinite(preferred) and preferred > 0):
            raise AnnotationError(f"{what}: preferredStep={step!r} is not a positive number of seconds")
        for key, pattern in (("package", _PACKAGE), ("slaveModule", _SLAVE_MODULE)):
            value = comp.get(key)
            if value is not None and not pattern.fullmatch(value):
                raise AnnotationError(f"{what}: {key}={value!r} is not a name rotorcosim gives its bundles "
                                      f"({pattern.pattern})")
        return Annotation(comp.get("implementation"), chosen, preferred, comp.get("package"),
                          comp.get("slaveModule"), comp.get("phaseInput") or None, comp.get("phasesOutput") or None,
                          comp.get("errorVariable") or None,
                          frozenset(n.strip() for n in (comp.get("defaultInputs") or "").split(",") if n.strip()))
    return Annotation()
