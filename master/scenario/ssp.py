"""A scenario's system as an SSP 1.0 archive, and an SSP archive back as a scenario our master runs.

Archive layout (``write_ssp``)::

    SystemStructure.ssd      the system (SSP 1.0 namespaces, valid against the SSP 1.0 XSDs fmpy ships)
    resources/<comp>.fmu     one FMU per component (fmus/export.py), parameters baked in as start values

In ``SystemStructure.ssd``: one ``ssd:Component`` per component with a ``ssd:Connector`` per FMU scalar
(``X[1]``.., kind input/output/parameter, ``ssc:Real unit``), its parameter values (and the scenario's constant
inputs) inline in ``ssd:ParameterBindings`` as an ``ssv:ParameterSet`` named ``initialValues`` (engines such
as Ecos apply it by that name), one ``ssd:Connection`` per scalar of every port-to-port connection, the units
(``ssd:Units``, SI base-unit exponents), ``ssd:DefaultExperiment`` (the schedule's duration), and an
annotation of type ``org.rotorcosim.scenario`` holding what SSP has no words for, as JSON: the master's
algorithm, schedule, outputs, results, per-component communication steps and each connection's
averaging/extrapolation/hold settings.

``read_ssp`` reads any SSP 1.0 archive of FMI co-simulation FMUs (flat system): without our annotation it
uses Gauss-Seidel in element order and a monolithic schedule over the DefaultExperiment at the step the
Open Simulation Platform's annotation of it gives (``osp:FixedStepAlgorithm baseStepSize``, libcosim's), else
the smallest DefaultExperiment stepSize of the FMUs. The archive is extracted (safely: safezip.py) into a temporary
folder that lives until the process ends, since the scenario's components point at the FMUs in it.
What it reads is checked as a TOML scenario is: the annotation's settings through the scenario schema
(master/scenario/schema.py), component names (non-empty, no '.', unique), a parameter value written in another unit
(``unit`` attribute) converted through ``ssd:Units`` or the unit grammar, or refused.
"""
from __future__ import annotations

import atexit
import json
import math
import multiprocessing.util
import os
import shutil
import tempfile
import xml.etree.ElementTree as ET
from pathlib import Path

from rotorcosim.components.bounded_read import MAX_ENTRY_BYTES, read_bytes
from rotorcosim.master.core.system import Connection
from rotorcosim.master.scenario.build import ComponentSpec, Scenario, ScenarioError, schedule_of

from rotorcosim.fmus import export
from rotorcosim.master.scenario.export import export_scenario
from rotorcosim.fmus.flatten import scalar_names
from rotorcosim.fmus.description import FMUError, describe, ports_of
from rotorcosim.fmus.model_description import AnnotationError, read_annotation, unit_element
from rotorcosim.fmus.safezip import ArchiveError, open_zip, safe_extract
from rotorcosim.fmus.units import definition, is_dimensionless

NS = {
    "ssd": "http://ssp-standard.org/SSP1/SystemStructureDescription",
    "ssc": "http://ssp-standard.org/SSP1/SystemStructureCommon",
    "ssv": "http://ssp-standard.org/SSP1/SystemStructureParameterValues",
}
ANNOTATION = "org.rotorcosim.scenario"
PARAMETER_SET = "initialValues"
#: the one kind of parameter binding there is to read (SSP 1.0: a parameter set, inline or a .ssv file)
PARAMETER_SET_TYPE = "application/x-ssp-parameter-set"
FMU_TYPE = "application/x-fmu-sharedlibrary"
ET.register_namespace("rc", "urn:rotorcosim:ssp:1")
for _p, _u in NS.items():
    ET.register_namespace(_p, _u)


class SSPError(ScenarioError):
    """An SSP archive that cannot be written or read; the message names the file and the element."""


def _q(prefix: str, tag: str) -> str:
    return f"{{{NS[prefix]}}}{tag}"


def _num(x) -> str:
    return repr(float(x))


# -- writing -------------------------------------------------------------------------------------------
def _ssv_value(parent: ET.Element, name: str, typ: str, value) -> None:
    p = ET.SubElement(parent, _q("ssv", "Parameter"), {"name": name})
    if typ == "Real":
        ET.SubElement(p, _q("ssv", "Real"), {"value": _num(value)})
    elif typ == "Integer":
        ET.SubElement(p, _q("ssv", "Integer"), {"value": str(int(value))})
    elif typ == "Boolean":
        ET.SubElement(p, _q("ssv", "Boolean"), {"value": "true" if value else "false"})
    else:
        ET.SubElement(p, _q("ssv", "String"), {"value": str(value)})


def _flat_values(var, value) -> list:
    if var.type == "String":
        return [value]
    import numpy as np

    return list(np.broadcast_to(np.asarray(value), (var.size,)).tolist())


def system_description(sc: Scenario, fmus: dict[str, Path]) -> bytes:
    """SystemStructure.ssd (bytes) for scenario ``sc`` whose components are the FMUs ``fmus``."""
    root = ET.Element(_q("ssd", "SystemStructureDescription"), {"version": "1.0", "name": sc.name})
    system = ET.SubElement(root, _q("ssd", "System"), {"name": sc.name})
    if sc.description:
        system.set("description", sc.description)
    elements = ET.SubElement(system, _q("ssd", "Elements"))
    units = set()
    ports = {}
    for name, path in fmus.items():
        xml, md = describe(path)
        variables, _ = ports_of(md, str(path), read_annotation(xml).hidden)
        ports[name] = {v.name: v for v in variables}
        comp = ET.SubElement(elements, _q("ssd", "Component"),
                             {"name": name, "type": FMU_TYPE, "source": f"resources/{name}.fmu"})
        cons = ET.SubElement(comp, _q("ssd", "Connectors"))
        for v in variables:
            if not v.carried:
                continue   # Binary / Clock ports: SSP 1.0 connectors have no Clock type, and we carry neither
            for s in scalar_names(v.name, v.size):
                c = ET.SubElement(cons, _q("ssd", "Connector"), {"name": s, "kind": v.causality})
                attrib = {}
                if v.type == "Real" and not is_dimensionless(v.unit):
                    attrib["unit"] = v.unit
                    units.add(v.unit)
                ET.SubElement(c, _q("ssc", v.type), attrib)
        values = []
        for key, value in sc.components[name].parameters.items():
            v = ports[name].get(key)
            if v is None or v.causality != "parameter":
                raise SSPError(f"scenario {sc.name!r}: component {name} has no parameter {key!r}")
            values += [(s, v.type, x) for s, x in zip(scalar_names(v.name, v.size), _flat_values(v, value))]
        for ref, value in sc.inputs.items():
            cname, _, port = ref.partition(".")
            if cname == name:
                v = ports[name].get(port)
                if v is None or v.causality != "input":
                    raise SSPError(f"scenario {sc.name!r}: [inputs] {ref}: component {name} has no input {port!r}")
                values += [(s, "Real", x) for s, x in zip(scalar_names(v.name, v.size), _flat_values(v, value))]
        if values:
            bindings = ET.SubElement(comp, _q("ssd", "ParameterBindings"))
            binding = ET.SubElement(bindings, _q("ssd", "ParameterBinding"),
                                    {"type": PARAMETER_SET_TYPE})
            pv = ET.SubElement(binding, _q("ssd", "ParameterValues"))
            pset = ET.SubElement(pv, _q("ssv", "ParameterSet"), {"version": "1.0", "name": PARAMETER_SET})
            params = ET.SubElement(pset, _q("ssv", "Parameters"))
            for s, typ, x in values:
                _ssv_value(params, s, typ, x)
    connections = ET.SubElement(system, _q("ssd", "Connections"))
    for con in sc.connections:
        (sa, sp), (da, dp) = con.src.split(".", 1), con.dst.split(".", 1)
        try:
            out, inp = ports[sa][sp], ports[da][dp]
        except KeyError:
            raise SSPError(f"scenario {sc.name!r}: connection {con.src} -> {con.dst} names a port its FMU "
                           "does not have") from None
        if out.size != inp.size:
            raise SSPError(f"scenario {sc.name!r}: connection {con.src} -> {con.dst}: sizes differ")
        for s, d in zip(scalar_names(sp, out.size), scalar_names(dp, inp.size)):
            ET.SubElement(connections, _q("ssd", "Connection"),
                          {"startElement": sa, "startConnector": s, "endElement": da, "endConnector": d})
    if units:
        ud = ET.SubElement(root, _q("ssd", "Units"))
        for u in sorted(units):
            unit = unit_element(u)
            unit.tag = _q("ssc", "Unit")
            for b in unit:
                b.tag = _q("ssc", "BaseUnit")
            ud.append(unit)
    try:
        duration = schedule_of(sc).duration
        ET.SubElement(root, _q("ssd", "DefaultExperiment"), {"startTime": "0.0", "stopTime": _num(duration)})
    except Exception:  # no usable schedule: the experiment is the engine's choice
        ET.SubElement(root, _q("ssd", "DefaultExperiment"), {"startTime": "0.0"})
    annotations = ET.SubElement(root, _q("ssd", "Annotations"))
    ann = ET.SubElement(annotations, _q("ssc", "Annotation"), {"type": ANNOTATION})
    payload = {
        "name": sc.name, "description": sc.description, "algorithm": sc.algorithm, "schedule": sc.schedule,
        "outputs": sc.outputs, "results": sc.extra.get("results", {}),
        "steps": {n: c.step for n, c in sc.components.items() if c.step is not None},
        "implementations": {n: c.implementation for n, c in sc.components.items() if c.implementation},
        "connections": [{"from": c.src, "to": c.dst, "average": c.average, "extrapolation": c.extrapolation,
                         "hold": c.hold, "convert": c.convert, "unit": c.unit} for c in sc.connections],
        "inputs": sc.inputs,
    }
    if sc.unconnected_inputs != "start":   # (the default is left out: archives written before stay byte-identical)
        payload["unconnected_inputs"] = sc.unconnected_inputs
    ET.SubElement(ann, "{urn:rotorcosim:ssp:1}Scenario").text = json.dumps(payload, sort_keys=True)
    ET.indent(root, space="  ")
    return ET.tostring(root, encoding="UTF-8", xml_declaration=True) + b"\n"


def write_ssp(sc: Scenario, path: str | Path) -> Path:
    """Write scenario ``sc`` as an SSP 1.0 archive at ``path`` (atomically; the FMUs are exported afresh)."""
    path = Path(path)
    if path.suffix.lower() != ".ssp":
        raise SSPError(f"{path}: an SSP archive's name must end in .ssp")
    if not path.parent.is_dir():
        raise SSPError(f"output folder {path.parent} does not exist")
    if path.is_dir():
        raise SSPError(f"{path} is a folder, not an archive's name")
    if not os.access(path.parent, os.W_OK | os.X_OK):  # before the (slow) export of the FMUs
        raise SSPError(f"output folder {path.parent} is not writable")
    with tempfile.TemporaryDirectory(prefix="rcs_ssp_") as tmp:
        fmus = export_scenario(sc, Path(tmp))
        entries = {f"resources/{n}.fmu": p.read_bytes() for n, p in fmus.items()}
        entries["SystemStructure.ssd"] = system_description(sc, fmus)
    try:
        return export.write_deterministic_zip(entries, path)
    except OSError as exc:  # an unwritable folder, a full disk: the archive is not written (nor a part of it)
        raise SSPError(f"{path}: cannot write the archive ({exc.strerror or exc})") from None


# -- reading -------------------------------------------------------------------------------------------
#: the archives' extraction folders, each with the process that made it (a forked child inherits the list: it
#: removes its own only, never its parent's, which the parent still runs from)
_extracted: list[tuple[int, Path]] = []
_finalizer_in: int | None = None


@atexit.register
def remove_extracted() -> None:
    """Remove this process's extraction folders (at exit; watchdog.py calls it before it ends a hung process)."""
    mine = [f for pid, f in _extracted if pid == os.getpid()]
    _extracted[:] = [(pid, f) for pid, f in _extracted if pid != os.getpid()]
    for folder in mine:
        shutil.rmtree(folder, ignore_errors=True)


def _remove_at_exit(folder: Path) -> None:
    global _finalizer_in
    _extracted.append((os.getpid(), folder))
    if _finalizer_in != os.getpid():
        # a multiprocessing child (fork: a sweep's worker) ends with os._exit, which runs no atexit handler, and
        # clears the finalizers it inherits: registered in the process that extracts
        multiprocessing.util.Finalize(None, remove_extracted, exitpriority=0)
        _finalizer_in = os.getpid()


def _value(p: ET.Element, where: str):
    """The value of an ``ssv:Parameter`` and the unit it is written in (its ``unit`` attribute, or None)."""
    values = [c for c in p if c.tag.split("}")[-1] in ("Real", "Float64", "Float32", "Integer", "Int32",
                                                        "Enumeration", "Boolean", "String")]
    if len(values) > 1:  # else the first would be taken, the others dropped without a word
        raise SSPError(f"{where}: parameter {p.get('name')!r} has {len(values)} values; give one")
    for child in values:
        tag = child.tag.split("}")[-1]
        return _typed(p, child, tag, where), child.get("unit") or None
    raise SSPError(f"{where}: parameter {p.get('name')!r} has no value this reader understands")


def _typed(p: ET.Element, child: ET.Element, tag: str, where: str):
    v = child.get("value")
    if v is None:
        raise SSPError(f"{where}: parameter {p.get('name')!r}: <ssv:{tag}> has no value attribute")
    try:
        if tag in ("Real", "Float64", "Float32"):
            return float(v)
        if tag in ("Integer", "Int32", "Enumeration"):
            return int(v)
    except ValueError:
        raise SSPError(f"{where}: parameter {p.get('name')!r}: <ssv:{tag} value={v!r}> is not a number") from None
    if tag == "Boolean":
        if v.strip().lower() not in ("true", "false", "1", "0"):
            raise SSPError(f"{where}: parameter {p.get('name')!r}: <ssv:Boolean value={v!r}> is not true/false")
        return v.strip().lower() in ("true", "1")
    return v


def parse_xml(path: Path, what: str) -> ET.Element:
    """An XML file of the archive, refusing DTDs (entity bombs, external entities) and reporting malformed XML
    with the file's name."""
    try:
        data = read_bytes(path, what, MAX_ENTRY_BYTES)
    except OSError as exc:
        raise SSPError(f"{what}: cannot be read ({exc.strerror or exc})") from None
    if b"<!DOCTYPE" in data or b"<!ENTITY" in data:
        raise SSPError(f"{what}: declares a DTD or entities, which SSP files never need: refused (entity bomb or "
                       "external entity)")
    try:
        return ET.fromstring(data)
    except ET.ParseError as exc:
        raise SSPError(f"{what}: not well-formed XML ({exc})") from None


#: the attributes of ``ssc:BaseUnit`` (SSP 1.0, as FMI 2.0's BaseUnit)
BASE_UNITS = ("kg", "m", "s", "A", "K", "mol", "cd", "rad")


def _units_of(root: ET.Element, where: str, path: str = "ssd:Units/ssc:Unit") -> dict[str, tuple]:
    """The unit definitions under ``root`` (the SSD's ``ssd:Units``, or a parameter set's ``ssv:Units``):
    name -> (base-unit exponents, factor, offset). A malformed definition is an error: read by its name instead,
    a unit the file defines otherwise would be misread."""
    out = {}
    for u in root.findall(path, NS):
        name, b = u.get("name"), u.find("ssc:BaseUnit", NS)
        if not name:
            raise SSPError(f"{where}: a unit definition (ssc:Unit) has no name")
        if b is None:   # SSP: no BaseUnit is a unit of dimension one
            out[name] = ({}, 1.0, 0.0)
            continue
        unknown = sorted(set(b.attrib) - set(BASE_UNITS) - {"factor", "offset"})
        if unknown:
            raise SSPError(f"{where}: unit {name!r}: unknown BaseUnit attribute(s) {', '.join(unknown)} (known: "
                           f"{', '.join(BASE_UNITS)}, factor, offset)")
        try:
            exps = {k: int(v) for k, v in b.attrib.items() if k in BASE_UNITS and int(v)}
            factor, offset = float(b.get("factor", 1.0)), float(b.get("offset", 0.0))
        except ValueError:
            raise SSPError(f"{where}: unit {name!r}: a BaseUnit exponent is not a whole number, or its factor or "
                           "offset not a number") from None
        if not (math.isfinite(factor) and factor > 0.0 and math.isfinite(offset)):
            raise SSPError(f"{where}: unit {name!r}: factor must be a finite number > 0 and offset finite, got "
                           f"factor={factor!r}, offset={offset!r}")
        out[name] = (exps, factor, offset)
    return out


def _in_unit(value, unit: str, var, units: dict, where: str, local: dict | None = None):
    """``value`` written in ``unit`` converted to the variable's unit; a unit that cannot be read, or of another
    dimension, is refused (never read as if it were the variable's own: a silent misreading). ``unit`` is looked
    up in ``local`` (the parameter set's own ssv:Units) first, then ``units`` (the SSD's), then read by its name;
    the variable's unit is the FMU's own definition, else the SSD's, else its name's."""
    src = (local or {}).get(unit) or units.get(unit) or definition(unit)
    dst = var.unit_definition or units.get(var.unit) or definition(var.unit)
    if isinstance(value, (bool, str)) or src is None or dst is None:
        raise SSPError(f"{where}: given in {unit!r}, which cannot be converted to the variable's unit {var.unit!r} "
                       "(define it in ssd:Units, or give the value in the variable's unit)")
    if src[0] != dst[0] or not (src[1] > 0 and dst[1] > 0):
        raise SSPError(f"{where}: given in {unit!r}, not a unit of the variable's quantity ({var.unit!r})")
    return ((float(value) * src[1] + src[2]) - dst[2]) / dst[1]


def _parameter_values(comp: ET.Element, folder: Path, where: str) -> dict[str, tuple]:
    """All values of a component's parameter bindings (inline or from .ssv files), later ones winning: name ->
    (value, unit or None, the unit definitions of the parameter set that holds it, ``ssv:Units``)."""
    out = {}
    for b in comp.findall("ssd:ParameterBindings/ssd:ParameterBinding", NS):
        if b.get("prefix"):
            raise SSPError(f"{where}: parameter bindings with a prefix are not supported")
        if b.find("ssd:ParameterMapping", NS) is not None:
            # a mapping renames or transforms the values: applying them unmapped would misread them
            raise SSPError(f"{where}: parameter bindings with a ParameterMapping (.ssm) are not supported")
        if b.get("type", PARAMETER_SET_TYPE) != PARAMETER_SET_TYPE:
            raise SSPError(f"{where}: parameter binding of type {b.get('type')!r} is not supported (only "
                           f"{PARAMETER_SET_TYPE!r}, SSP parameter values)")
        source = b.get("source")
        if source:
            target = (folder / source).resolve()
            if folder.resolve() not in target.parents or not target.is_file():
                raise SSPError(f"{where}: parameter source {source!r} is not a file inside the archive")
            what = f"{where}: parameter file {source!r}"
            pset = parse_xml(target, what)
        else:
            what = f"{where}: parameter values"
            pset = b.find("ssd:ParameterValues/ssv:ParameterSet", NS)
            if pset is None:
                continue
        local = _units_of(pset, what, "ssv:Units/ssc:Unit")
        names = set()
        for p in pset.findall("ssv:Parameters/ssv:Parameter", NS):
            # a later binding overrides an earlier one, but one parameter set giving a name twice says two
            # things at once (else the last one would be taken without a word)
            if p.get("name") in names:
                raise SSPError(f"{what}: parameter {p.get('name')!r} is given twice in one parameter set")
            names.add(p.get("name"))
            out[p.get("name")] = (*_value(p, where), local)
    return out


#: the annotation's keys (what write_ssp puts there) -> the container each must be
_PAYLOAD = {"name": str, "description": str, "algorithm": dict, "schedule": (dict, type(None)), "outputs": dict,
            "results": dict, "steps": dict, "implementations": dict, "connections": list, "inputs": dict,
            "unconnected_inputs": str}


_JSON = {dict: "object", list: "array", str: "string", int: "number", float: "number", bool: "boolean",
         type(None): "null"}


def _payload_shapes(payload: dict, where: str) -> None:
    """The annotation's keys and their containers (its values are checked by the scenario schema, later)."""
    what = f"{where}: SystemStructure.ssd: annotation {ANNOTATION}"
    for key, value in payload.items():
        if key not in _PAYLOAD:
            raise SSPError(f"{what}: unknown key {key!r}; known: {', '.join(_PAYLOAD)}")
        if not isinstance(value, _PAYLOAD[key]):
            raise SSPError(f"{what}: {key!r} must be a JSON {_JSON[_PAYLOAD[key] if isinstance(_PAYLOAD[key], type) else dict]}, "
                           f"got a JSON {_JSON.get(type(value), type(value).__name__)}")
    if not all(isinstance(c, dict) for c in payload.get("connections", [])):
        raise SSPError(f"{what}: 'connections' must be a list of JSON objects")
    for key in ("steps", "implementations"):
        for name, value in payload.get(key, {}).items():
            ok = isinstance(value, str) if key == "implementations" else \
                isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value) and value > 0
            if not ok:
                raise SSPError(f"{what}: {key}[{name!r}] = {value!r} is not " +
                               ("an implementation's name" if key == "implementations" else "a positive step [s]"))


def _check_payload(payload: dict, where: str, components: dict) -> None:
    """The annotation's scenario settings through the scenario schema, as a TOML scenario's (master/scenario/schema.py)."""
    from rotorcosim.master.scenario import schema

    data = {"components": {n: {"fmu": c.fmu, **({"step": c.step} if c.step is not None else {})}
                           for n, c in components.items()},
            "scenario": {k: payload[k] for k in ("name", "description", "unconnected_inputs") if k in payload},
            "connections": [{k: v for k, v in c.items() if v is not None} for c in payload.get("connections", [])],
            "inputs": payload.get("inputs", {})}
    data.update({k: payload[k] for k in ("algorithm", "schedule", "outputs", "results") if payload.get(k)})
    try:
        schema.check(data)
    except schema.SchemaError as exc:
        msg = str(exc).removeprefix("scenario: ")
        raise SSPError(f"{where}: SystemStructure.ssd: annotation {ANNOTATION}: {msg}") from None


def _time(de, key: str, default: float, where: str) -> float:
    text = de.get(key) if de is not None else None
    if text is None or text == "":
        return default
    try:
        value = float(text)
    except ValueError:
        value = float("nan")
    if not math.isfinite(value):
        raise SSPError(f"{where}: ssd:DefaultExperiment: {key}={text!r} is not a finite number of seconds")
    return value


#: the Open Simulation Platform's annotation of an SSP system's co-simulation algorithm (libcosim, Ecos)
OSP_ANNOTATION = "com.opensimulationplatform"
OSP_NS = "http://opensimulationplatform.com/SSP/OSPAnnotations"


def _osp_base_step(de, where: str) -> float | None:
    """The communication step [s] an OSP annotation of ``ssd:DefaultExperiment`` gives
    (``osp:Algorithm/osp:FixedStepAlgorithm baseStepSize``, as libcosim reads it), or None without one."""
    for ann in (de.findall("ssd:Annotations/ssc:Annotation", NS) if de is not None else []):
        if ann.get("type") != OSP_ANNOTATION:
            continue
        algo = ann.find(f"{{{OSP_NS}}}Algorithm/{{{OSP_NS}}}FixedStepAlgorithm")
        text = algo.get("baseStepSize") if algo is not None else None
        if text is None:
            continue
        try:
            value = float(text)
        except ValueError:
            value = float("nan")
        if not (math.isfinite(value) and value > 0.0):
            raise SSPError(f"{where}: ssd:DefaultExperiment: {OSP_ANNOTATION} FixedStepAlgorithm baseStepSize="
                           f"{text!r} is not a positive number of seconds")
        return value
    return None


def read_ssp(path: str | Path) -> Scenario:
    """The scenario of the SSP archive at ``path`` (components given as the FMUs inside it)."""
    path = Path(path)
    try:
        with open_zip(path, "SSP archive") as zf:
            if "SystemStructure.ssd" not in zf.namelist():
                raise SSPError(f"{path}: no SystemStructure.ssd at the top of the archive: not an SSP archive")
        folder = safe_extract(path, "SSP archive", prefix="rcs_ssp_")
    except ArchiveError as exc:
        raise SSPError(str(exc)) from None
    _remove_at_exit(folder)
    try:
        return _scenario_of(path, folder)
    except BaseException:  # a malformed archive: its extraction folder goes at once, not at exit
        shutil.rmtree(folder, ignore_errors=True)
        _extracted.remove((os.getpid(), folder))
        raise


def _scenario_of(path: Path, folder: Path) -> Scenario:
    where = str(path)
    root = parse_xml(folder / "SystemStructure.ssd", f"{where}: SystemStructure.ssd")
    if root.tag != _q("ssd", "SystemStructureDescription"):
        raise SSPError(f"{where}: SystemStructure.ssd is not an SSP 1.0 system structure description "
                       f"(root element {root.tag})")
    system = root.find("ssd:System", NS)
    if system is None:
        raise SSPError(f"{where}: SystemStructure.ssd has no ssd:System")
    payload = {}
    ours = [a for a in root.findall("ssd:Annotations/ssc:Annotation", NS) if a.get("type") == ANNOTATION]
    if len(ours) > 1:  # else the last one would be read, the others dropped without a word
        raise SSPError(f"{where}: SystemStructure.ssd has {len(ours)} annotations {ANNOTATION}; give one")
    for ann in ours:
        if len(ann):
            try:
                payload = json.loads(ann[0].text or "{}")
            except json.JSONDecodeError as exc:
                raise SSPError(f"{where}: SystemStructure.ssd: annotation {ANNOTATION} is not valid JSON ({exc})") from None
            if not isinstance(payload, dict):
                raise SSPError(f"{where}: SystemStructure.ssd: annotation {ANNOTATION} must hold a JSON object")
    _payload_shapes(payload, where)
    units = _units_of(root, f"{where}: SystemStructure.ssd")
    components: dict[str, ComponentSpec] = {}
    scalars: dict[str, dict[str, tuple]] = {}
    inputs: dict[str, list] = {}
    steps = []
    for comp in system.findall("ssd:Elements/*", NS):
        tag = comp.tag.split("}")[-1]
        cname = comp.get("name")
        w = f"{where}: component {cname!r}"
        if not cname or "." in cname:
            raise SSPError(f"{w}: a component's name must be non-empty and contain no '.'")
        if cname in components:
            raise SSPError(f"{w}: two components have this name")
        if tag != "Component":
            raise SSPError(f"{w}: nested {tag} elements are not supported (flat systems of FMUs only)")
        if comp.get("type", FMU_TYPE) != FMU_TYPE:
            raise SSPError(f"{w}: type {comp.get('type')!r} is not an FMU")
        source = comp.get("source", "")
        fmu = (folder / source).resolve()
        if folder.resolve() not in fmu.parents or not fmu.is_file():
            raise SSPError(f"{w}: source {source!r} is not an FMU inside the archive")
        try:
            xml, md = describe(fmu)
            variables, _ = ports_of(md, f"{w} ({source})", read_annotation(xml, f"{w} ({source})").hidden)
        except (FMUError, AnnotationError) as exc:
            # named by the archive and the entry, not by the temporary folder it was unpacked into
            msg = str(exc).replace(str(fmu), f"{source!r}")
            raise SSPError(msg if msg.startswith(w) else f"{w}: {msg}") from None
        if md.defaultExperiment is not None and md.defaultExperiment.stepSize:
            steps.append(float(md.defaultExperiment.stepSize))
        scalars[cname] = {s: (v, i) for v in variables for i, s in enumerate(scalar_names(v.name, v.size))}
        params: dict[str, list] = {}
        for sname, (value, unit, local) in _parameter_values(comp, folder, w).items():
            if sname not in scalars[cname]:
                continue   # SSP: names that match no variable are ignored
            v, i = scalars[cname][sname]
            if unit is not None and (unit != v.unit or unit in local):
                # the parameter set's own definitions first (ssv:Units), then the SSD's, then the unit's name
                value = _in_unit(value, unit, v, units, f"{w}: parameter {sname!r}", local)
            if v.causality == "parameter":
                params.setdefault(v.name, [None] * v.size)[i] = value
            elif v.causality == "input":
                inputs.setdefault(f"{cname}.{v.name}", list(v.start_array()))[i] = float(value)
        parameters = {}
        for pname, values in params.items():
            v = scalars[cname][scalar_names(pname, len(values))[0]][0]
            full = [x if x is not None else s for x, s in zip(values, _flat_values(v, v.start))]
            parameters[pname] = full[0] if len(full) == 1 else full
        components[cname] = ComponentSpec(cname, fmu=str(fmu), parameters=parameters,
                                          step=payload.get("steps", {}).get(cname), fmu_label=f"{source!r} in {path}")
    if not components:
        raise SSPError(f"{where}: the system has no components")
    # scalar connections back to port connections
    grouped: dict[tuple, list] = {}
    for c in system.findall("ssd:Connections/ssd:Connection", NS):
        se, sc_, ee, ec = (c.get(k) for k in ("startElement", "startConnector", "endElement", "endConnector"))
        if not se or not ee:
            raise SSPError(f"{where}: connection {sc_} -> {ec} touches the system's own connectors: "
                           "only component-to-component connections are supported")
        for e, n in ((se, sc_), (ee, ec)):
            if e not in scalars:   # it said "bearing9.X[1] is not a variable of its FMU": there is no such FMU
                raise SSPError(f"{where}: connection {se}.{sc_} -> {ee}.{ec}: the system has no component {e!r} "
                               f"(its components: {', '.join(scalars)})")
            if n not in scalars[e]:
                raise SSPError(f"{where}: connection {se}.{sc_} -> {ee}.{ec}: {e}.{n} is not a variable of "
                               f"its FMU")
        (sv, si), (dv, di) = scalars[se][sc_], scalars[ee][ec]
        grouped.setdefault((se, sv.name, ee, dv.name), []).append((si, di, sv.size, dv.size))
    # the settings through the schema first: a connection record refuses a bad value when it is made
    _check_payload(payload, where, components)
    settings = {(c["from"], c["to"]): c for c in payload.get("connections", [])}
    connections = []
    for (se, sp, ee, dp), pairs in grouped.items():
        src, dst = f"{se}.{sp}", f"{ee}.{dp}"
        ssize, dsize = pairs[0][2], pairs[0][3]
        if ssize != dsize or sorted((a, b) for a, b, _, _ in pairs) != [(i, i) for i in range(ssize)]:
            raise SSPError(f"{where}: the scalar connections from {src} to {dst} do not connect the two "
                           f"ports element by element (sizes {ssize} and {dsize})")
        s = settings.pop((src, dst), {})
        connections.append(Connection(src, dst, s.get("average", "mean"), s.get("extrapolation", "hold"),
                                      s.get("hold"), s.get("convert"), s.get("unit")))
    if settings:  # settings (averaging, conversion, unit) for a connection the system does not have: not applied
        src, dst = next(iter(settings))
        raise SSPError(f"{where}: SystemStructure.ssd: annotation {ANNOTATION}: connection {src} -> {dst} has "
                       "settings but no ssd:Connection")
    schedule = payload.get("schedule")
    if not schedule:
        de = root.find("ssd:DefaultExperiment", NS)
        start = _time(de, "startTime", 0.0, where)
        stop = _time(de, "stopTime", start + 1.0, where)
        if not stop > start:
            raise SSPError(f"{where}: ssd:DefaultExperiment: stopTime {stop!r} is not after startTime {start!r}")
        step = _osp_base_step(de, where)
        schedule = {"kind": "monolithic", "duration": stop - start,
                    "step": step if step is not None else min(steps) if steps else 1e-3}
    algorithm = payload.get("algorithm") or {"kind": "gauss-seidel", "order": list(components)}
    for ref, values in payload.get("inputs", {}).items():
        inputs[ref] = list(values) if isinstance(values, list) else values
    return Scenario(name=payload.get("name", system.get("name", path.stem)), components=components,
                    connections=connections, inputs=inputs, algorithm=algorithm, schedule=schedule,
                    outputs=payload.get("outputs", {}), source=path, description=payload.get("description", ""),
                    extra={"results": payload.get("results", {})},
                    unconnected_inputs=payload.get("unconnected_inputs", "start"))
