"""Staggered against monolithic for any scenario (master/compare): the toy, which has no case, compared through
the generic function's public interface, as the shipped cases' comparisons use it."""
from __future__ import annotations

import json

import pytest

from rotorcosim.master.api import load_scenario
from rotorcosim.master.compare import compare_schemes, kept_run, pair, rel_error_pct, within
from rotorcosim.master.scenario.build import schedule_of


def _table(runs, timing):
    T = [runs[k]["final_outputs"]["node.T"][0] for k in ("staggered", "monolithic")]
    return {"T": pair(*T), "speedup": timing["speedup"], "wall": timing["wall_time_s"]}


def _compare(out, **kw):
    sc = load_scenario("toy_thermomechanical")
    return compare_schemes(sc, out, schedule_of(sc, "auto", 3.0), schedule_of(sc, "monolithic", 3.0),
                           tabulate=_table, table_name="compare.json", **kw)


def test_any_scenario_is_compared_and_tabulated(tmp_path):
    out = tmp_path / "cmp"
    t = _compare(out)
    assert json.loads((out / "compare.json").read_text()) == json.loads(json.dumps(t))
    a, b = t["T"]["staggered"], t["T"]["monolithic"]
    assert t["T"]["rel_error_pct"] == pytest.approx(100 * abs(a - b) / abs(b)) and 0 < t["T"]["rel_error_pct"] < 2
    assert t["speedup"] == pytest.approx(t["wall"]["monolithic"] / t["wall"]["staggered"])
    for kind, phases in (("staggered", {"TM", "TO"}), ("monolithic", {"TM"})):
        s = kept_run(out / kind)
        assert s["scenario"] == f"toy_thermomechanical_{kind}" and {iv["phase"] for iv in s["timeline"]} == phases
    # a second comparison into the folder is refused; --resume keeps both complete runs and gives the same table
    with pytest.raises(ValueError, match="already holds a comparison"):
        _compare(out)
    stamp = (out / "staggered" / "summary.json").stat().st_mtime_ns
    again = _compare(out, resume=True)
    assert again["T"] == t["T"] and (out / "staggered" / "summary.json").stat().st_mtime_ns == stamp


def test_the_relative_error_of_a_quantity():
    assert rel_error_pct(1.01, 1.0) == pytest.approx(1.0) and rel_error_pct(0.0, 0.0) == 0.0
    assert rel_error_pct(1.0, 0.0) is None and rel_error_pct(None, 1.0) is None
    assert rel_error_pct(float("nan"), 1.0) is None and rel_error_pct(True, 1.0) is None
    assert within([pair(1.01, 1.0), pair(3.0, 3.0)], 2.0) == (pytest.approx(1.0), True)
    assert within([pair(1.03, 1.0)], 2.0)[1] is False and within([pair(None, 1.0)], 2.0) == (None, False)
