"""The package's layers and import cycles (the import-linter contracts in pyproject.toml), and what the generic
master must not know.

import-linter reads the package from the file system; in a checkout the sub-packages are sibling folders that
``rotorcosim/__init__.py`` joins at import time, so the test copies the sources into the installed layout first.
"""
from __future__ import annotations

import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
#: folder in the checkout -> folder in the installed package (pyproject's package-dir)
PARTS = {"rotorcosim": "", "components": "components", "master": "master", "fmus": "fmus", "cases": "cases",
         "interop": "interop", "scenarios": "scenarios"}


def _installed_layout(dest: Path) -> Path:
    pkg = dest / "rotorcosim"
    for src, sub in PARTS.items():
        shutil.copytree(ROOT / src, pkg / sub, dirs_exist_ok=True,
                        ignore=shutil.ignore_patterns("__pycache__", "*.pyc", "data", "*.toml", "*.csv"))
    shutil.copy(ROOT / "pyproject.toml", dest / "pyproject.toml")
    return dest


def _lint(tree: Path) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-c", "import sys; from importlinter.cli import lint_imports_command;"
                           "sys.exit(lint_imports_command())", "--config", str(tree / "pyproject.toml"), "--no-cache"],
                          cwd=tree, capture_output=True, text=True, env={"PYTHONPATH": str(tree), "PATH": ""},
                          timeout=300)


def test_the_layer_contract_holds(tmp_path):
    r = _lint(_installed_layout(tmp_path))
    assert r.returncode == 0, r.stdout + r.stderr
    assert "Contracts: 2 kept, 0 broken" in r.stdout, r.stdout


def test_a_forbidden_import_breaks_it(tmp_path):
    """The contract has teeth: the core importing the command line is reported, naming both modules."""
    tree = _installed_layout(tmp_path)
    system = tree / "rotorcosim" / "master" / "core" / "system.py"
    system.write_text(system.read_text() + "\nfrom rotorcosim.master.cli import program  # noqa: F401 - the breach the test plants\n")
    r = _lint(tree)
    assert r.returncode != 0
    assert "rotorcosim.master.core.system -> rotorcosim.master.cli.program" in r.stdout, r.stdout


#: words of the paper's case that the generic master must not contain (its case lives in rotorcosim.cases)
CASE_WORDS = re.compile(r"bearing|unbalance|blade|table ?[56]|\bpaper\b|16 ?000|15 ?000|speed_rpm", re.IGNORECASE)
GENERIC = ["core", "schedule", "manipulator", "observer", "compiled"]


@pytest.mark.parametrize("sub", GENERIC)
def test_the_generic_master_names_no_part_of_the_papers_case(sub):
    hits = []
    for path in sorted((ROOT / "master" / sub).rglob("*.py")):
        for i, line in enumerate(path.read_text().splitlines(), 1):
            if CASE_WORDS.search(line):
                hits.append(f"{path.relative_to(ROOT)}:{i}: {line.strip()}")
    assert not hits, "the generic master names the paper's case:\n" + "\n".join(hits)
