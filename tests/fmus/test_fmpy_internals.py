"""fmpy's internals that rotorcosim relies on (fmus/fmpy_internals.py): each one still works with the installed
fmpy, the installed fmpy is in the range pyproject.toml allows, and no other module reaches below fmpy's public API.
A failure names the fmpy version, so that an upgrade that moves an internal says so at once."""
from __future__ import annotations

import re
from pathlib import Path

import fmpy
import pytest
from fmpy.fmi1 import FMU1Slave
from fmpy.fmi2 import FMU2Slave
from fmpy.fmi3 import FMU3Slave
from packaging.specifiers import SpecifierSet

from rotorcosim.fmus import fmpy_internals

ROOT = Path(__file__).resolve().parents[2]
#: what only fmpy_internals.py may use: fmpy's private attributes (a name with a leading underscore on an fmpy
#: object or imported from an fmpy module)
INTERNALS = re.compile(r"\._functions\b|from fmpy[\w.]* import [^\n]*\b_\w|fmpy(\.\w+)*\._[a-z]")


def _pinned() -> str:
    found = re.findall(r'"fmpy([^"]*)"', (ROOT / "pyproject.toml").read_text())
    assert len(found) == 1, f"pyproject.toml should name fmpy once in its dependencies, found {found}"
    return found[0]


def _loaded(fmu: Path, slave_class, token_attr: str, tmp_path: Path):
    from fmpy import extract, read_model_description

    md = read_model_description(str(fmu))
    slave = slave_class(guid=getattr(md, token_attr), modelIdentifier=md.coSimulation.modelIdentifier,
                        unzipDirectory=extract(str(fmu), str(tmp_path / "x")), instanceName="canary")
    slave.instantiate()
    return slave


def test_every_internal_works_with_the_installed_fmpy_fmi2(mass_fmu, tmp_path):
    slave = _loaded(mass_fmu, FMU2Slave, "guid", tmp_path)
    try:
        fmpy_internals.check(slave, "2")   # raises naming the internal and the fmpy version
    finally:
        slave.freeInstance()


def test_every_internal_works_with_the_installed_fmpy_fmi3(types3_fmu, tmp_path):
    slave = _loaded(types3_fmu, FMU3Slave, "instantiationToken", tmp_path)
    try:
        fmpy_internals.check(slave, "3")
    finally:
        slave.freeInstance()


def test_every_internal_works_with_the_installed_fmpy_fmi1(reference1_fmus, tmp_path):
    slave = _loaded(reference1_fmus["dahlquist1"], FMU1Slave, "guid", tmp_path)
    try:
        fmpy_internals.check(slave, "1")
    finally:
        slave.freeInstance()


def test_the_installed_fmpy_is_in_the_capped_range():
    spec = _pinned()
    assert SpecifierSet(spec).contains(fmpy.__version__), (
        f"fmpy {fmpy.__version__} is outside the range {spec!r} (pyproject.toml); {fmpy_internals.version_note()}")
    assert all(SpecifierSet(spec).contains(v) for v in fmpy_internals.TESTED), (
        f"the range {spec!r} excludes a tested version {fmpy_internals.TESTED}")
    assert "<" in spec, f"fmpy is not capped in pyproject.toml ({spec!r}): a new fmpy may move its internals"


def test_a_moved_internal_names_the_fmpy_version(monkeypatch):
    class Moved:   # an fmpy whose slaves no longer keep the table
        pass

    with pytest.raises(RuntimeError, match=rf"fmi2DoStep .*fmpy {re.escape(fmpy.__version__)} is installed.*"
                                           r"tested with"):
        fmpy_internals.check(Moved(), "2")


def test_no_other_module_reaches_below_fmpys_public_api():
    hits = []
    for part in ("components", "master", "fmus", "cases", "interop", "rotorcosim"):
        for path in sorted((ROOT / part).rglob("*.py")):
            if path.name == "fmpy_internals.py":
                continue
            for i, line in enumerate(path.read_text().splitlines(), 1):
                if INTERNALS.search(line):
                    hits.append(f"{path.relative_to(ROOT)}:{i}: {line.strip()}")
    assert not hits, "fmpy internals outside fmus/fmpy_internals.py:\n" + "\n".join(hits)
