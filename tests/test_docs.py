"""The documentation stays current: the generated reference pages equal what docs/reference/generate.py writes
from the code now, every relative link in README.md and docs/ resolves, and the README keeps its contract."""
import importlib.util
import re
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
GENERATOR = ROOT / "docs" / "reference" / "generate.py"


def _generator():
    spec = importlib.util.spec_from_file_location("docs_reference_generate", GENERATOR)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


#: argparse's help layout changes between Python versions (3.10 says "optional arguments:", 3.13 prints a
#: metavar once per option); the committed cli.md is written with Python 3.11
CLI_LAYOUT = (3, 11) <= sys.version_info[:2] <= (3, 12)


@pytest.mark.parametrize("page", ["cli.md", "components.md", "scenario.md"])
def test_reference_page_is_current(page, tmp_path):
    gen = _generator()
    gen.generate(tmp_path)
    fresh = (tmp_path / page).read_text(encoding="utf-8")
    committed = (ROOT / "docs" / "reference" / page).read_text(encoding="utf-8")
    if page == "cli.md" and not CLI_LAYOUT:
        # another argparse layout: every option of every command must still be in the committed page
        missing = sorted(set(re.findall(r"(?<![\w-])--[a-z][\w-]*", fresh)) -
                         set(re.findall(r"(?<![\w-])--[a-z][\w-]*", committed)))
        assert not missing, f"docs/reference/{page} lacks {missing}: run python docs/reference/generate.py"
        return
    assert fresh == committed, (f"docs/reference/{page} is not what the code gives now: run "
                                f"`python docs/reference/generate.py` and commit the page")


def test_every_schema_key_is_in_the_scenario_page():
    gen = _generator()
    gen._import_checkout()
    schema = gen._schema()
    page = (ROOT / "docs" / "reference" / "scenario.md").read_text(encoding="utf-8")
    keys = {k for t in schema.TABLES.values() for k in t} | set(schema.TABLES)
    keys |= set(schema.COMPONENT) | set(schema.CONNECTION) | set(schema.INTERVAL)
    missing = sorted(k for k in keys if f"`{k}`" not in page and f"[{k}" not in page)
    assert not missing, f"docs/reference/scenario.md does not mention {missing}"


def test_outputs_page_names_every_key(tmp_path):
    """Every key of a run's summary.json and every attribute of its timeseries.h5 is in docs/reference/outputs.md
    (a small run without a case), and so is every Table 4 result of the blade-loss case."""
    import h5py

    gen = _generator()
    gen._import_checkout()
    import rotorcosim
    from rotorcosim.cases.blade_loss import results

    res = rotorcosim.simulate("toy_thermomechanical", duration=0.01, out=tmp_path / "run", figures=False)
    page = (ROOT / "docs" / "reference" / "outputs.md").read_text(encoding="utf-8")
    names = set(res.summary) | set(res.summary["estimate"]) | set(results.RESULT_KEYS)
    names |= {k for interval in res.summary["timeline"] for k in interval}
    with h5py.File(tmp_path / "run" / "timeseries.h5") as f:
        names |= set(f.attrs) | {a for ds in f.values() for a in ds.attrs}
    missing = sorted(n for n in names if f"`{n}`" not in page)
    assert not missing, f"docs/reference/outputs.md does not name {missing}"


def _markdown_files():
    return [ROOT / "README.md"] + sorted((ROOT / "docs").rglob("*.md"))


@pytest.mark.parametrize("path", _markdown_files(), ids=lambda p: str(p.relative_to(ROOT)))
def test_relative_links_resolve(path):
    text = path.read_text(encoding="utf-8")
    broken = []
    for target in re.findall(r"\]\(([^)\s]+)\)", text):
        if re.match(r"[a-z]+:", target) or target.startswith("#"):
            continue
        if not (path.parent / target.split("#")[0]).exists():
            broken.append(target)
    assert not broken, f"{path.relative_to(ROOT)}: links to missing files {broken}"


def test_readme_keeps_its_contract():
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    assert "pip install . && rotorcosim run --out out" in readme
    assert 'pip install ".[test]" && python -m pytest' in readme
    assert ".ci/run" in readme
    assert len(readme.splitlines()) <= 210, "README.md: keep it short, move detail into docs/"
