"""numba's internals that rotorcosim relies on (components/numba_internals.py): each one still works with the
installed numba, the installed numba is in the range pyproject.toml pins, and no other module reaches below
numba's public API. A failure names the numba version, so that an upgrade that moves an internal says so at once."""
from __future__ import annotations

import re
from pathlib import Path

import numba
import pytest

from rotorcosim.components import numba_internals

ROOT = Path(__file__).resolve().parents[2]
#: what only numba_internals.py may use (numba's internals: the module docstring lists why each is needed)
INTERNALS = re.compile(r"numba\.core|\.overloads\[|call_conv|no_cfunc_wrapper|_index_key|_load_index|Dispatcher\b"
                       r"|data_model_manager|get_pointer_to_function|cgutils")


def _pinned() -> str:
    text = (ROOT / "pyproject.toml").read_text()
    found = re.findall(r'"numba([^"]*)"', text)
    assert len(found) == 1, f"pyproject.toml should name numba once in its dependencies, found {found}"
    return found[0]


def test_every_internal_works_with_the_installed_numba():
    numba_internals.check()  # raises naming the internal and the numba version


def test_the_installed_numba_is_in_the_pinned_range():
    from packaging.specifiers import SpecifierSet

    spec = _pinned()
    assert SpecifierSet(spec).contains(numba.__version__), (
        f"numba {numba.__version__} is outside the pinned range {spec!r} (pyproject.toml); "
        f"{numba_internals.version_note()}")
    assert all(SpecifierSet(spec).contains(v) for v in numba_internals.TESTED), (
        f"the pin {spec!r} excludes a tested version {numba_internals.TESTED}")


def test_a_failing_internal_names_the_numba_version(monkeypatch):
    monkeypatch.setattr(numba_internals, "layout", lambda ty: (_ for _ in ()).throw(AttributeError("moved")))
    with pytest.raises(RuntimeError, match=rf"numba {re.escape(numba.__version__)} is installed.*tested with"):
        numba_internals.check()


def test_no_other_module_reaches_below_numbas_public_api():
    hits = []
    for part in ("components", "master", "fmus", "cases", "rotorcosim"):
        for path in sorted((ROOT / part).rglob("*.py")):
            if path.name == "numba_internals.py":
                continue
            for i, line in enumerate(path.read_text().splitlines(), 1):
                if INTERNALS.search(line):
                    hits.append(f"{path.relative_to(ROOT)}:{i}: {line.strip()}")
    assert not hits, "numba internals outside components/numba_internals.py:\n" + "\n".join(hits)
