"""The generic master names no case: no module of master/ (code, docstrings and comments alike) speaks the
shipped cases' vocabulary. What a case needs from the master it declares in its own package (master/case.py:
its level with its unit, label and option spelling, its default scenario, schedule aliases, score and tables).

The words are the blade-loss case's and the reference paper's, chosen so that a generic word of rotordynamics
stays free ("bearing", "rotor", "speed", "spool" and "run down" are the master's to use): the case's level and
its name (unbalance, blade loss), the paper and its tables, the shipped bearings' ids (#0, #5; bearing0,
damper5, X_brg0 ...), the paper's levels in N, its engine's spools and the shipped cases' package paths."""
from __future__ import annotations

import re
from pathlib import Path

import pytest

MASTER = Path(__file__).resolve().parents[1] / "master"

#: pattern -> what it stands for (matched case-insensitively, in every line of every module)
VOCABULARY = {
    r"unbalance": "the blade-loss case's level (a case declares its LEVEL)",
    r"blade": "the blade-loss case",
    r"paper": "the reference paper",
    r"table\s*[456]\b|table[456]\.": "the paper's Tables 4-6",
    r"windmill": "the rundown case's windmilling",
    r"bearing\s*#\s*[05]\b|#[05]\b": "the paper's bearings #0 and #5",
    r"(?:bearing|damper|thermal|rubring|brg|rub|housing)[05]\b": "the shipped bearings' ids 0 and 5",
    r"(?<![\d.])(?:712|1425|2850|5700|8551|11401|14252)(?!\d)": "the paper's unbalance levels [N]",
    r"power[\s_-]*turbine|gas[\s_-]*generator|spool_(?:pt|gg)": "the paper's engine's spools",
    r"cases[./](?:blade_loss|rundown)": "a shipped case's package",
}
PATTERN = re.compile("|".join(f"(?:{p})" for p in VOCABULARY), re.IGNORECASE)


def _modules():
    return sorted(p for p in MASTER.rglob("*.py") if "__pycache__" not in p.parts)


def offending_lines(text: str) -> list[tuple[int, str]]:
    """(line number, line) of each line of ``text`` that speaks a case's vocabulary."""
    return [(i, line.strip()) for i, line in enumerate(text.splitlines(), 1) if PATTERN.search(line)]


def test_the_modules_are_found():
    mods = _modules()
    packages = {p.parent.name for p in mods}
    # every sub-package of master/ is held, the new ones too
    assert {"core", "cli", "sweep", "scenario", "run", "compare", "study", "observer", "schedule"} <= packages
    assert len(mods) > 60


@pytest.mark.parametrize("path", _modules(), ids=lambda p: str(p.relative_to(MASTER)))
def test_no_module_of_the_master_names_a_case(path):
    bad = offending_lines(path.read_text(encoding="utf-8"))
    assert not bad, "\n".join(f"master/{path.relative_to(MASTER)}:{i}: {line}" for i, line in bad)


@pytest.mark.parametrize("line", [
    'scenario: Any = "blade_loss"',
    'p.add_argument("--unbalance", type=float)',
    'info = {"paper_score": score}',
    'row = [c.level if p == "unbalance_N" else ""]',
    "SCHEDULE_ALIASES = {'paper': 'scenario'}",
    '"bearing-static": ("...", "static load distribution of bearing #0 or #5")',
    'for k in (0, 5): out[f"damper{k}"]; x = "rotor.X_brg0"',
    'write_json(out / "table6.json", t)',
    "levels = (712.0, 1425.0, 2850.0)",
    'label="1x power turbine"',
    "from rotorcosim.cases.rundown.compare import _draw",
])
def test_the_check_fails_when_a_case_word_comes_back(line):
    """Each kind of word this check exists for, as it stood in the master before: found."""
    assert offending_lines(line), line


@pytest.mark.parametrize("line", [
    "the bearing's drag power", "a spool running down", "run-down", "rotor speed [rev/min]", "step 1e-5",
    "phase TM / TO", "x = data[:, 0]", "level_parameter", "# 5 cycles", "t = 0.25 s", "bearingA, damperB",
    "rotor.X_brgA", "compare_schemes", "Level(summary_key=...)",
])
def test_generic_words_stay_free(line):
    assert not offending_lines(line), line
