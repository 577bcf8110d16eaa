"""The Table 5 score (cases/blade_loss/paper_comparison.py): which cells are compared and how a cell is judged."""
import csv
import copy

import pytest

from rotorcosim.cases.blade_loss import paper_comparison as pc
from rotorcosim.cases.blade_loss.table5 import paper_table5


def _paper_as_ours():
    """The paper's Table 5 in the shape of our sweep's summaries (unbalance N -> summary)."""
    by_level = {}
    for (key, k), row in paper_table5().items():
        for level, v in row.items():
            by_level.setdefault(level, {"bearings": {"0": {}, "5": {}}})["bearings"][str(k)][key] = v
    return by_level


def test_the_paper_against_itself_scores_152_of_152():
    rows = pc.compare(_paper_as_ours())
    s = pc.score(rows)
    assert s["cells"] == 152 and s["within_30pct"] == 152 and s["within_x2"] == 152 and not s["outside_x2"]
    compared = {(r["result"], r["bearing"], r["unbalance_N"]) for r in rows}
    # the two printed zeros that are rounding are left out; the rub power's zeros are compared
    assert ("transmissibility", 5, 712.0) not in compared and ("sfd_power_W", 5, 712.0) not in compared
    assert ("rub_power_W", 0, 712.0) in compared and ("rub_power_W", 5, 14252.0) in compared


@pytest.mark.parametrize("key,k,level,value,in30,inx2", [
    ("whirl_amplitude_mm", 0, 712.0, 0.0512 * 1.29, True, True),
    ("whirl_amplitude_mm", 0, 712.0, 0.0512 * 1.31, False, True),
    ("drag_power_W", 5, 2850.0, 624.6 * 0.69, False, True),
    ("drag_power_W", 5, 2850.0, 624.6 * 2.01, False, False),
    ("max_contact_load_N", 0, 14252.0, 2252.5 * 0.49, False, False),
    ("rub_power_W", 0, 2850.0, 0.5, True, True),          # no rub where the paper has none
    ("rub_power_W", 0, 2850.0, 500.0, False, False),      # a rub where the paper has none
    ("rub_power_W", 0, 5700.0, 0.0, False, False),        # no rub where the paper rubs
])
def test_one_cell_judged(key, k, level, value, in30, inx2):
    ours = copy.deepcopy(_paper_as_ours())
    ours[level]["bearings"][str(k)][key] = value
    rows = pc.compare(ours)
    (row,) = [r for r in rows if (r["result"], r["bearing"], r["unbalance_N"]) == (key, k, level)]
    assert (row["within_30"], row["within_x2"]) == (in30, inx2)
    s = pc.score(rows)
    assert s["within_30pct"] == 151 + in30 and s["within_x2"] == 151 + inx2


def test_missing_level_or_value_counts_as_a_miss_and_files_are_written(tmp_path):
    ours = _paper_as_ours()
    del ours[14252.0]                                      # a level not run: its cells are not compared
    ours[712.0]["bearings"]["0"].pop("T_ball_C")           # a value missing: compared and missed
    ours[11401.0]["error"] = "stopped at t = 33 s"          # a case that stopped: its (partial) values are misses
    sc = pc.write(tmp_path, ours)
    assert sc["cells"] == 152 - 22 and sc["within_30pct"] == sc["cells"] - 1 - 22
    with open(tmp_path / "paper_comparison.csv") as f:
        rows = list(csv.reader(f))
    assert rows[0] == ["result", "bearing", "unbalance_N", "paper", "ours", "ratio"]
    assert len(rows) == 1 + sc["cells"]
    assert (tmp_path / "paper_comparison.png").stat().st_size > 10_000


def test_a_sweep_of_another_engine_is_not_scored_against_the_paper(tmp_path):
    """The paper's Table 5 is of its own engine: a sweep at the paper's levels of an engine of one's own (its
    rotor's model file another) writes its values alone, for its own bearings, and no comparison or score."""
    ours = {}
    for level in (712.0, 1425.0):
        ours[level] = {"provenance": {"parameters": {"rotor": {"parameters": {"model_file": "/x/engine.toml"}}}},
                       "bearings": {"1": {"whirl_amplitude_mm": 0.25}, "2": {"whirl_amplitude_mm": 0.5}}}
    assert pc.sweep_tables(tmp_path, ours) is None
    assert sorted(p.name for p in tmp_path.iterdir()) == ["table5.csv", "table5.md"]
    with open(tmp_path / "table5.csv") as f:
        rows = [r for r in csv.reader(f) if r and not r[0].startswith("#")]
    assert ["whirl_amplitude_mm", "1", "0.25", "0.25"] in rows and ["whirl_amplitude_mm", "2", "0.5", "0.5"] in rows
    assert not [r for r in rows if r[1] in ("0", "5")]
    md = (tmp_path / "table5.md").read_text()
    assert "| whirl_amplitude_mm | 1 | 0.25 | 0.25 |" in md and " / " not in md     # no "ours / paper" cell


def test_a_sweep_of_the_paper_engine_is_scored(tmp_path):
    from rotorcosim.components.rotor.model import DEFAULT_FILE

    ours = _paper_as_ours()
    for s in ours.values():
        s["provenance"] = {"parameters": {"rotor": {"parameters": {"model_file": str(DEFAULT_FILE)}}}}
    assert pc.sweep_tables(tmp_path, ours)["within_30pct"] == 152
    assert (tmp_path / "paper_comparison.csv").exists() and "/ 0.0512 (+0 %)" in (tmp_path / "table5.md").read_text()


def test_a_sweep_of_a_copy_of_the_paper_engine_is_scored(tmp_path):
    """A byte-for-byte copy of the shipped engine file (test_sweep_cluster's grid over rotor.model_file) is the
    paper's engine; an edited copy is not."""
    from rotorcosim.cases.blade_loss.paper_comparison import of_the_paper_engine
    from rotorcosim.components.rotor.model import DEFAULT_FILE

    copy = tmp_path / "engine copy.toml"
    copy.write_bytes(DEFAULT_FILE.read_bytes())
    edited = tmp_path / "edited.toml"
    edited.write_bytes(DEFAULT_FILE.read_bytes() + b"\n# a comment: another file\n")

    def summary(path):
        return {"provenance": {"parameters": {"rotor": {"parameters": {"model_file": str(path)}}}}}

    assert of_the_paper_engine(summary(copy)) and of_the_paper_engine(summary(DEFAULT_FILE))
    assert not of_the_paper_engine(summary(edited))
    assert not of_the_paper_engine(summary(tmp_path / "gone.toml"))
