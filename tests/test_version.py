"""One version, written in pyproject.toml: the package's ``__version__`` and CITATION.cff say the same."""
from __future__ import annotations

import re
import sys
from pathlib import Path

import rotorcosim

if sys.version_info >= (3, 11):
    import tomllib
else:
    import tomli as tomllib

ROOT = Path(__file__).resolve().parents[1]


def _pyproject_version() -> str:
    return tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["version"]


def test_the_package_reports_pyprojects_version():
    assert rotorcosim.__version__ == _pyproject_version()


def test_citation_cff_names_pyprojects_version():
    found = re.findall(r"^version:\s*['\"]?([^'\"\s]+)", (ROOT / "CITATION.cff").read_text(), re.M)
    assert found == [_pyproject_version()], (
        f"CITATION.cff says version {found}, pyproject.toml {_pyproject_version()}: change both together")


def test_no_other_file_writes_the_version():
    v = re.escape(_pyproject_version())
    hits = [str(p.relative_to(ROOT)) for part in ("rotorcosim", "components", "master", "fmus", "cases", "interop")
            for p in (ROOT / part).rglob("*.py") if re.search(rf"__version__\s*=\s*['\"]{v}['\"]", p.read_text())]
    assert not hits, hits
