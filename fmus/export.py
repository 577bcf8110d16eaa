"""Export one registered component, with given parameters, as an FMI 2.0 co-simulation FMU (pythonfmu).

The FMU holds: pythonfmu's native wrapper (binaries/), the generic slave (slave_template.py, copied under a
module name unique to the FMU), a JSON configuration beside it (class, parameters, declared variables), the
component's code bundled under a private package name (bundle.py), and a finished, validated
modelDescription.xml (model_description.py). The archive is rewritten with its entries in sorted order and fixed
timestamps, so the same component, parameters and code give the same bytes; it is written to a temporary name
in the destination folder and renamed, so a failed export never leaves a half-written FMU.
"""
from __future__ import annotations

import hashlib
import json
import os
import re
import shutil
import sys
import tempfile
import zipfile
from pathlib import Path
from typing import Any, Mapping

import numpy as np

import rotorcosim
from rotorcosim.components import registry
from rotorcosim.components.contract import Component, ContractError

from rotorcosim.fmus import bundle, model_description
from rotorcosim.fmus.safezip import check_entries, open_zip
from rotorcosim.components.bounded_read import read_entry

TEMPLATE = Path(__file__).with_name("slave_template.py")
#: the schedule phase in, and the phases a component takes part in out (slave_template.py explains)
PHASE_INPUT = "_rcs_phase"
PHASES_OUTPUT = "_rcs_phases"
#: the component's last error message (a local String variable)
ERROR_VARIABLE = "_rcs_error"
#: fixed timestamp of every zip entry (the zip format's epoch): deterministic archives
ZIP_DATE = (1980, 1, 1, 0, 0, 0)


class ExportError(ValueError):
    """A component that cannot be exported; the message names it and why."""


def identifier(name: str) -> str:
    """A C identifier from a component or implementation name (``damper.fast`` -> ``damper_fast``)."""
    out = re.sub(r"[^0-9A-Za-z_]", "_", name)
    return out if out and not out[0].isdigit() else f"c_{out}"


def _jsonable(value: Any) -> Any:
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, np.generic):
        return value.item()
    return value


def variables_config(comp: Component) -> list[dict]:
    """The declared variables as plain dicts; parameters start at the component's current (coerced) values."""
    out = []
    for v in comp.variables:
        start = comp.p[v.name] if v.causality == "parameter" else v.start
        if v.type == "Real" or v.causality != "parameter":
            start = np.broadcast_to(np.asarray(start, dtype=float), (v.size,)).tolist()
            start = start[0] if v.size == 1 else start
        entry = {"name": v.name, "causality": v.causality, "size": int(v.size), "unit": v.unit,
                 "description": v.description, "start": _jsonable(start), "type": v.type}
        if v.has_default:   # (only then: the bundle's config, hence its content hash, stays as it was otherwise)
            entry["has_default"] = True
        out.append(entry)
    return out


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def write_deterministic_zip(entries: Mapping[str, bytes], dest: Path) -> Path:
    """Write ``entries`` (name -> bytes) sorted, with fixed dates and modes, to ``dest`` atomically."""
    dest = Path(dest)
    fd, tmp = tempfile.mkstemp(prefix=f".{dest.name}.", suffix=".part", dir=dest.parent)
    os.close(fd)
    try:
        with zipfile.ZipFile(tmp, "w", zipfile.ZIP_DEFLATED) as zf:
            for name in sorted(entries):
                info = zipfile.ZipInfo(name, ZIP_DATE)
                info.compress_type = zipfile.ZIP_DEFLATED
                info.external_attr = 0o644 << 16
                info.create_system = 3
                zf.writestr(info, entries[name])
        # mkstemp creates the file 0600: give it the mode any new file gets (0644 under the usual umask 022)
        os.chmod(tmp, 0o666 & ~_umask())
        os.replace(tmp, dest)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
    return dest


def _build_with_pythonfmu(stage: Path, slave_module: str, config_file: Path, package_dir: Path, out: Path) -> Path:
    """pythonfmu's builder, with the interpreter left as it was found (it imports the slave to describe it)."""
    from pythonfmu.builder import FmuBuilder

    path_before = list(sys.path)
    modules_before = set(sys.modules)
    try:
        return FmuBuilder.build_FMU(stage / f"{slave_module}.py", dest=out, project_files=[config_file, package_dir],
                                    canGetAndSetFMUstate=True, canHandleVariableCommunicationStepSize=True)
    finally:
        sys.path[:] = path_before
        for name in set(sys.modules) - modules_before:
            if name == slave_module or name.startswith(slave_module + ".") or name.split(".")[0] == package_dir.name:
                del sys.modules[name]


def export_component(implementation: str, dest: str | Path, *, instance_name: str | None = None,
                     parameters: Mapping[str, Any] | None = None, model_identifier: str | None = None) -> Path:
    """Build the FMU of registered ``implementation`` with ``parameters`` into ``dest`` (a .fmu file or a folder).

    ``instance_name`` names the component inside (default: the implementation); ``model_identifier`` the FMU
    (default: the instance name made a C identifier). Returns the path written."""
    try:
        cls = registry.lookup(implementation)
    except ContractError as exc:
        raise ExportError(str(exc)) from None
    instance_name = instance_name or implementation
    try:
        comp = cls(instance_name, dict(parameters or {}))   # checks the parameters' names, sizes and types
    except ContractError as exc:
        raise ExportError(f"cannot export {instance_name} ({implementation}): {exc}") from None
    problem = comp.standalone_problem()
    if problem is not None:   # its FMU would be written, and fail at its first fmi2ExitInitializationMode
        raise ExportError(f"cannot export {instance_name} ({implementation}): {problem}")
    try:
        module_path, class_name = bundle.component_location(cls)
        files = bundle.bundle_files(module_path)
    except bundle.BundleError as exc:
        raise ExportError(f"cannot export {instance_name} ({implementation}): {exc}") from None
    model_id = identifier(model_identifier or instance_name)
    variables = variables_config(comp)
    baked = {k: _jsonable(comp.p[k]) for k in (parameters or {})}
    config = {
        "model_identifier": model_id,
        "implementation": implementation,
        "instance_name": instance_name,
        "description": (comp.description or cls.__doc__ or implementation).strip().splitlines()[0],
        "version": rotorcosim.__version__,
        "module": module_path,
        "class": class_name,
        "parameters": baked,
        "variables": variables,
        "preferred_step": float(comp.preferred_step),
        "phases": sorted(comp.phases),
        "phase_input": PHASE_INPUT,
        "phases_output": PHASES_OUTPUT,
        "error_variable": ERROR_VARIABLE,
    }
    code_hash = bundle.digest(files)
    content_hash = hashlib.sha256(json.dumps(config, sort_keys=True).encode() + code_hash.encode()
                                  + TEMPLATE.read_bytes()).hexdigest()
    short = content_hash[:10]
    package = f"_rcs_{model_id}_{short}"
    slave_module = f"rcs_slave_{model_id}_{short}"
    config["package"] = package
    dest = Path(dest)
    if dest.suffix.lower() != ".fmu":
        dest = dest / f"{model_id}.fmu"
    if not dest.parent.is_dir():
        raise ExportError(f"output folder {dest.parent} does not exist")
    with tempfile.TemporaryDirectory(prefix="rcs_fmu_") as tmp:
        stage = Path(tmp) / "stage"
        stage.mkdir()
        shutil.copyfile(TEMPLATE, stage / f"{slave_module}.py")
        config_file = stage / f"{slave_module}.json"
        config_file.write_text(json.dumps(config, indent=1, sort_keys=True), encoding="utf-8")
        package_dir = bundle.write_bundle(files, stage, package)
        built = _build_with_pythonfmu(stage, slave_module, config_file, package_dir, Path(tmp) / f"{model_id}.fmu")
        entries = {}
        with zipfile.ZipFile(built) as zf:
            for info in zf.infolist():
                if info.is_dir() or "__pycache__" in info.filename.split("/"):
                    continue
                entries[info.filename] = zf.read(info)
    phase_vars = [{"name": n, "causality": c, "size": 1, "unit": "1", "description": "", "start": 0,
                   "type": t} for n, c, t in ((PHASE_INPUT, "input", "Integer"), (ERROR_VARIABLE, "local", "String"),
                                              (PHASES_OUTPUT, "output", "Integer"))]
    entries["modelDescription.xml"] = model_description.finish(
        entries["modelDescription.xml"], variables + phase_vars, implementation=implementation,
        phases=config["phases"], phase_input=PHASE_INPUT, phases_output=PHASES_OUTPUT,
        error_variable=ERROR_VARIABLE, default_inputs=tuple(v["name"] for v in variables if v.get("has_default")),
        preferred_step=config["preferred_step"], package=package, slave_module=slave_module,
        content_hash=content_hash)
    return write_deterministic_zip(entries, dest)


def fmu_entries(path: Path) -> dict[str, bytes]:
    """The entries of the FMU ``path``, each read through the caps of an archive (safezip, bounded_read)."""
    with open_zip(path, "FMU") as zf:
        check_entries(zf, str(path))
        return {i.filename: read_entry(zf, i, str(path)) for i in zf.infolist() if not i.is_dir()}
