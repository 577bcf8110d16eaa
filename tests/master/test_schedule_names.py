"""The names the API and the command line take for a schedule and a scenario: ``"scenario"`` (the scenario's own
schedule) and its alias ``"paper"``, the default scenario declared in one place, and what a sweep says it
wrote."""
import json

import pytest

import rotorcosim
from rotorcosim import scenarios
from rotorcosim.master import api
from rotorcosim.master.cli import main
from rotorcosim.master.cli import sweep as sweep_cli

TOY = "toy_thermomechanical"


def test_paper_is_the_scenarios_own_schedule():
    sc = rotorcosim.load_scenario(TOY)
    own, kind = api._schedule(sc, None, 1.0)
    for name in ("scenario", "paper"):
        sch, k = api._schedule(sc, name, 1.0)
        assert k is None and sch == own and len(sch.intervals) == 2    # 0.3 s TM, then TO to 1 s
    assert api._schedule(sc, "monolithic", 1.0)[0] != own
    with pytest.raises(ValueError, match=r"schedule 'papers': use one of \['auto', 'monolithic', 'scenario'\]"):
        api._schedule(sc, "papers", 1.0)


@pytest.mark.parametrize("name", ["paper", "scenario"])
def test_the_summary_names_the_scenarios_own_kind(tmp_path, name):
    """``--schedule paper`` and ``--schedule scenario`` write the same summary ``schedule``: the scenario's kind."""
    out = tmp_path / name
    assert main(["run", TOY, "--schedule", name, "--duration", "0.5", "--out", str(out), "--quiet"]) == 0
    s = json.loads((out / "summary.json").read_text())
    assert s["schedule"] == "timeline" and [u["phase"] for u in s["timeline"]] == ["TM", "TO"]
    assert rotorcosim.simulate(TOY, duration=0.05, schedule=name).summary["schedule"] == "timeline"


def test_the_default_scenario_is_declared_with_the_shipped_ones(monkeypatch):
    assert scenarios.DEFAULT == api.DEFAULT_SCENARIO == "blade_loss_2850"
    assert rotorcosim.load_scenario().name == "blade_loss_2850"
    monkeypatch.setattr(scenarios, "DEFAULT", TOY)
    assert rotorcosim.load_scenario(None).name == TOY


def test_a_sweep_lists_the_files_it_wrote(tmp_path, capsys, monkeypatch):
    """The closing line names the case's tables that were written, and the case's score line follows."""
    argv = ["sweep", "--scenario", TOY, "--serial", "--quiet", "--duration", "0.05", "--unbalance", "3"]
    assert main([*argv, "--out", str(tmp_path / "plain")]) == 0
    line = capsys.readouterr().out.splitlines()[0]
    assert line.endswith(f"); sweep.csv and sweep.json written in {tmp_path / 'plain'}"), line

    def tables(out, by_level):
        (out / "levels.csv").write_text("level\n3\n")
        return {"cells": 1}

    case = {"SWEEP_TABLES": tables, "SWEEP_SCORE": lambda score, out: f"score {score['cells']} in {out}",
            "SWEEP_FILES": ("levels.csv",)}
    monkeypatch.setattr(sweep_cli.cases_, "attribute", lambda kind, name, default=None: case.get(name, default))
    out = tmp_path / "case"
    assert main([*argv, "--out", str(out), "--schedule", "paper"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[0].endswith(f"; levels.csv, sweep.csv and sweep.json written in {out}"), lines
    assert lines[1] == f"score 1 in {out}"
    # a case that declares no SCORE_KEY: the score under "score" (the blade-loss case's: "paper_score")
    assert json.loads((out / "sweep.json").read_text())["score"] == {"cells": 1}
    # the case's files are a sweep's: --overwrite clears them
    assert main([*argv, "--out", str(out), "--overwrite"]) == 0
