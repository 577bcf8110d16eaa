"""The hand-written pages checked against the code and the tree: the architecture page's module map and the
README's tree against the folders; docs/reference/api.md, errors.md, engine-format.md and fmi.md against the
functions, constants and formats they describe (tests/test_docs.py checks the generated pages)."""
from __future__ import annotations

import inspect
import re
import sys
from pathlib import Path

import pytest

if sys.version_info >= (3, 11):
    import tomllib
else:
    import tomli as tomllib

ROOT = Path(__file__).resolve().parents[1]
REFERENCE = ROOT / "docs" / "reference"
#: the package folders of the checkout (pyproject's package-dir) whose modules the architecture page maps
PACKAGES = ("components", "master", "fmus", "cases", "interop")


def _page(path: Path) -> str:
    return path.read_text(encoding="utf-8")


def _modules(folder: Path) -> set[str]:
    return {p.name for p in folder.glob("*.py") if p.name != "__init__.py"}


def _subpackages(folder: Path) -> set[str]:
    return {p.name for p in folder.iterdir() if (p / "__init__.py").is_file()}


# -- the tree ---------------------------------------------------------------------------------------------------
def _module_map() -> dict[str, str]:
    """The architecture page's table "Where each thing lives": first cell -> modules cell."""
    rows = {}
    for line in _page(ROOT / "docs" / "explanation" / "architecture.md").splitlines():
        m = re.match(r"\| `([\w/.]+)` \|(.*?)\| .* \|$", line)
        if m:
            rows[m.group(1)] = m.group(2)
    return rows


def test_the_architecture_pages_module_map_is_the_tree():
    rows = _module_map()
    problems = []
    for where, cell in rows.items():
        path = ROOT / where
        if where.endswith(".py"):
            if not path.is_file():
                problems.append(f"{where}: no such module")
            continue
        if not path.is_dir():
            problems.append(f"{where}: no such folder")
            continue
        own = cell.split("one sub-package per kind")[0]   # components/: its kinds' own modules come after
        named = set(re.findall(r"`([\w.]+\.py)`", own))
        if named != _modules(path):
            problems.append(f"{where}: the page names {sorted(named - _modules(path))} that are not there and "
                            f"misses {sorted(_modules(path) - named)}")
        subs = set(re.findall(r"`(\w+)/`", cell)) - {"data"}
        if path.parent == ROOT and subs and subs != _subpackages(path):
            problems.append(f"{where}: sub-packages {sorted(subs)} on the page, {sorted(_subpackages(path))} here")
    # every package folder has its row (the components' kinds are sub-packages of the components row)
    for top in PACKAGES:
        for folder in [ROOT / top, *(ROOT / top).rglob("*")]:
            if not (folder / "__init__.py").is_file() or "__pycache__" in folder.parts:
                continue
            rel = folder.relative_to(ROOT).as_posix()
            if rel.startswith("components/") or rel == "cases":
                continue
            if rel == "master":   # its modules have rows of their own
                missing = [m for m in sorted(_modules(folder)) if f"master/{m}" not in rows]
                problems += [f"master/{m}: no row" for m in missing]
                continue
            if f"{rel}/" not in rows:
                problems.append(f"{rel}/: no row")
    assert not problems, "docs/explanation/architecture.md, the module map:\n" + "\n".join(problems)


def test_the_readmes_tree_is_the_folders():
    readme = _page(ROOT / "README.md")
    block = readme[readme.index("## How it is built"):]
    block = block[block.index("```") + 3:]
    block = block[:block.index("```")]
    listed = {m.group(1): m.group(2) for m in re.finditer(r"^(\w+)/\s+(.*(?:\n {14}.*)*)", block, re.M)}
    folders = {p.name for p in ROOT.iterdir() if p.is_dir() and not p.name.startswith((".", "_"))
               and p.name not in ("build", "dist", "out", "runs") and not p.name.endswith(".egg-info")}
    assert set(listed) == folders, (f"README.md's tree lists {sorted(set(listed) - folders)} that are not here and "
                                    f"misses {sorted(folders - set(listed))}")
    for top in ("components", "master"):   # the sub-packages its line names
        missing = [s for s in _subpackages(ROOT / top) if not re.search(rf"\b{s}\b", listed[top])]
        assert not missing, f"README.md's tree: the {top}/ line does not name {missing}"


# -- api.md -----------------------------------------------------------------------------------------------------
def test_the_api_page_names_every_name_and_parameter():
    import rotorcosim
    from rotorcosim import interop
    from rotorcosim.master.api import Result, Scenario

    page = _page(REFERENCE / "api.md")
    missing = [n for n in (*rotorcosim._API, *rotorcosim._STUDIES) if f"`{n}`" not in page and f"## {n}" not in page]
    for fn in (rotorcosim.load_scenario, rotorcosim.simulate, rotorcosim.calibrate, rotorcosim.uq,
               interop.from_ross, interop.to_ross, interop.write_engine):
        missing += [f"{fn.__name__}({p.name})" for p in inspect.signature(fn).parameters.values()
                    if p.kind != p.VAR_KEYWORD and not re.search(rf"\b{p.name}\b", page)]
    for cls in (Result, Scenario):   # their methods and properties (a Scenario's fields are the scenario file's)
        public = [n for n in dir(cls) if not n.startswith("_")
                  and isinstance(inspect.getattr_static(cls, n), (property, type(lambda: 0)))]
        missing += [f"{cls.__name__}.{n}" for n in public if not re.search(rf"\b{n}\b", page)]
    assert not missing, f"docs/reference/api.md does not name {missing}"


def test_the_api_pages_defaults_are_the_codes():
    import rotorcosim

    page = _page(REFERENCE / "api.md")
    heading = re.search(r"^## simulate\((.*)\) -> Result$", page, re.M).group(1)
    keyword = page[page.index(heading):].split("\n\n")[1]
    import ast

    params = inspect.signature(rotorcosim.simulate).parameters
    found = re.findall(r"`(\w+)=([^`]+)`", heading + " " + keyword) + re.findall(r"\b(\w+)=([\w.]+)", heading)
    assert len(found) >= 8
    for name, text in found:
        if text == "...":
            continue
        assert name in params, f"api.md: simulate has no parameter {name}"
        assert ast.literal_eval(text) == params[name].default, (
            f"api.md: simulate's {name} defaults to {params[name].default!r}, not {text}")
    from rotorcosim.master.run import checkpoint

    assert f"`checkpoint_every` (s, default {checkpoint.EVERY_S:g})" in page


# -- errors.md --------------------------------------------------------------------------------------------------
def test_the_errors_page_states_the_codes_limits():
    from rotorcosim.fmus import safezip
    from rotorcosim.master.cli import program
    from rotorcosim.master.schedule import budget

    page = _page(REFERENCE / "errors.md")
    statuses = {int(s) for s in re.findall(r"^\| (\d+) \|", page, re.M)}
    assert statuses == {0, 1, 2, 130}
    assert program.describe_error(ValueError("x"))[0] == 2 and program.describe_error(OSError("x"))[0] == 1
    mib = safezip.MAX_TOTAL_BYTES / 1024 ** 2
    entries = f"{safezip.MAX_ENTRIES:,}".replace(",", " ")
    caps = (f"{mib:g} MiB in all, {entries} entries, no entry above {safezip.RATIO_FLOOR_BYTES / 1024 ** 2:g} MiB "
            f"expanding more than {safezip.MAX_RATIO:g} times")
    assert caps in " ".join(page.split()), "errors.md: the archive caps are not fmus/safezip.py's"
    assert f"above {budget.LIMIT_S / 3600:g} h it is refused" in page


# -- engine-format.md -------------------------------------------------------------------------------------------
def _engine_example() -> str:
    page = _page(REFERENCE / "engine-format.md")
    return re.search(r"## An example\n.*?```toml\n(.*?)```", page, re.S).group(1)


def test_the_engine_format_pages_example_is_read(tmp_path):
    from rotorcosim.components.rotor import model as fem

    f = tmp_path / "engine.toml"
    f.write_text(_engine_example())
    m = fem.load(f)
    spools = tomllib.loads(_engine_example())["spool"]
    assert list(m.info["spools"]) == list(spools) and m.n >= 6 * sum(len(s["z_mm"]) for s in spools.values())


#: tables whose children are names the engine file chooses (a spool's, a material's...), not keys of the format
_NAMED = {"spool", "material", "pedestal", "calibration", "hubs"}


def _keys(table: dict, out: set, parent: str = "") -> set:
    for k, v in table.items():
        if parent not in _NAMED:
            out.add(k)
        items = v if isinstance(v, list) else [v]
        for item in items:
            if isinstance(item, dict):
                _keys(item, out, "" if parent in _NAMED else k)
    return out


def test_every_key_of_the_shipped_engines_is_on_the_engine_format_page():
    page = _page(REFERENCE / "engine-format.md")
    files = [ROOT / "components" / "rotor" / "data" / "engine.toml",
             *sorted((ROOT / "cases" / "blade_loss" / "data").glob("textbook_*.toml"))]
    keys: set = set()
    for f in files:
        data = tomllib.loads(f.read_text())
        if "engine" in data:   # an engine file (the others there are scenarios)
            _keys(data, keys)
    assert {"z_mm", "attach"} <= keys
    quoted = set(re.findall(r"\w+", " ".join(re.findall(r"`([^`]*)`", page))))
    attach = re.compile(r"(bearing|rubring)\w+")   # [attach] entries: bearing<ID>, rubring<ID>
    missing = sorted(k for k in keys if k not in quoted and not attach.fullmatch(k))
    assert not missing, f"docs/reference/engine-format.md does not name {missing}"


def test_every_key_on_the_engine_format_page_is_read_by_the_code():
    page = _page(REFERENCE / "engine-format.md")
    table = page[page.index("## Tables and keys"):page.index("## `[attach]`")]
    named = set()
    for line in table.splitlines()[4:]:
        first = line.split(" | ")[0]
        if "free text" in line:   # name, description, source: for the reader of the file, not the program
            continue
        named |= set(re.findall(r"\w+", " ".join(re.findall(r"`([^`]*)`", first))))
    # the readers: the rotor model, the attachments, the parts at each attachment (engine_parts.py)
    source = "".join(_page(ROOT / "components" / "rotor" / f) for f in ("model.py", "attach.py", "engine_parts.py",
                                                                       "mounts.py"))
    read = set(re.findall(r"[\"'](\w+)[\"']", source))
    words = {"NAME", "hub", "ground", "rotor", "casing", "x", "y", "z", "dir"}   # names and values, not keys
    unread = sorted(k for k in named - words if k not in read and not k[0].isupper() and not k.isdigit())
    assert not unread, f"docs/reference/engine-format.md names keys the reader does not use: {unread}"


# -- fmi.md -----------------------------------------------------------------------------------------------------
def test_the_fmi_page_has_every_type_and_conversion():
    from rotorcosim.components.value_types import KIND_OF, UNCARRIED
    from rotorcosim.master.core.conversions import CONVERSIONS

    page = _page(REFERENCE / "fmi.md")
    table = page[page.index("## Types"):]
    table = "\n".join(line for line in table.splitlines() if line.startswith("|"))
    missing = [t for t in KIND_OF if not re.search(rf"\b{t}\b", table)]
    missing += [f'convert = "{c}"' for c in CONVERSIONS if f'"{c}"' not in page]
    missing += [t for t in UNCARRIED if f"| {t}" not in table and f", {t}" not in table]
    assert not missing, f"docs/reference/fmi.md does not name {missing}"


@pytest.mark.parametrize("page", ["api.md", "errors.md", "engine-format.md", "fmi.md"])
def test_every_module_a_reference_page_names_exists(page):
    text = _page(REFERENCE / page)
    named = set(re.findall(r"`((?:components|master|fmus|cases|interop)/[\w/]+\.py)", text))
    missing = sorted(p for p in named if not (ROOT / p).is_file())
    assert not missing, f"docs/reference/{page} names modules that are not there: {missing}"


# -- no history -------------------------------------------------------------------------------------------------
#: what tells the story of how the code came about rather than what it is: issue numbers, a session, "the issue"
HISTORY = re.compile(r"\bissues? ?#?\d+|\bissue-\d+|\bthe issue'?s?\b|\b(first|second|third|fourth|this|last|"
                     r"earlier|previous) session\b|\bDESIGN \"", re.IGNORECASE)


def test_no_history_in_the_docs_docstrings_and_comments():
    files = [ROOT / "README.md", *sorted((ROOT / "docs").rglob("*.md"))]
    for part in (*PACKAGES, "rotorcosim", "scenarios", "tests", "bench"):
        files += sorted((ROOT / part).rglob("*.py")) + sorted((ROOT / part).rglob("*.toml"))
    hits = [f"{f.relative_to(ROOT)}:{i}: {line.strip()}" for f in files if f.name != "test_docs_code.py"
            for i, line in enumerate(f.read_text(encoding="utf-8").splitlines(), 1) if HISTORY.search(line)]
    assert not hits, "history in the docs or the code's text (say what is, not how it came about):\n" + \
        "\n".join(hits)
