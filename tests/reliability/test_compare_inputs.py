"""`rotorcosim compare`'s inputs: a scenario without bearing results, and --monolithic folders that are not the
monolithic run this comparison needs (another scenario, a damaged summary): one line before any run."""
import json
from pathlib import Path

import pytest

from rotorcosim.master.cli import main
from rotorcosim.cases.blade_loss.compare import KEYS, reuse_monolithic

NAME = "blade_loss_monolithic"


def _summary(**changes):
    s = {"scenario": NAME, "status": "complete", "timeline": [{"phase": "TM", "t_start": 0.0, "t_end": 0.1}],
         "t_end_s": 0.1, "unbalance_N": 2850.0, "wall_time_s": 1.5, "bearings": {"0": {k: 1.0 for k in KEYS}}}
    s.update(changes)
    return s


def _folder(tmp_path, summary):
    d = tmp_path / "mono"
    d.mkdir(exist_ok=True)
    (d / "summary.json").write_text(summary if isinstance(summary, str) else json.dumps(summary))
    return d


def test_a_matching_monolithic_run_is_reused(tmp_path):
    assert reuse_monolithic(_folder(tmp_path, _summary()), 2850.0, 0.1, NAME, 0)["wall_time_s"] == 1.5


@pytest.mark.parametrize("summary, message", [
    (_summary(scenario="blade_loss_fe_monolithic"), "a run of scenario 'blade_loss_fe_monolithic', not "
                                                    "'blade_loss_monolithic'"),
    ("[1, 2]", "not a run's summary (a JSON list)"),
    (_summary(t_end_s="abc"), "t_end_s is 'abc', not a number (damaged summary)"),
    (_summary(wall_time_s=None), "wall_time_s is None, not a number"),
    (_summary(bearings={"5": {}}), "no results of bearing #0"),
    (_summary(bearings=[]), "no results of bearing #0"),
    (_summary(bearings={"0": {"transmissibility": "high"}}), "no results of bearing #0"),
    ("{", "no readable summary.json"),
    (_summary(timeline="TM"), "not a complete monolithic run"),
    (_summary(timeline=["TM"]), "not a complete monolithic run"),
    (_summary(unbalance_N=712.0), "unbalance_N is 712.0 N, not 2850.0 N"),
])
def test_a_monolithic_folder_that_does_not_fit_is_refused(tmp_path, summary, message):
    with pytest.raises(ValueError) as err:
        reuse_monolithic(_folder(tmp_path, summary), 2850.0, 0.1, NAME, 0)
    assert message in str(err.value) and "--monolithic" in str(err.value)


def test_a_scenario_without_bearing_results(tmp_path, capsys):
    """The toy has no bearing results: refused before running anything (was: both runs, then "error: 'bearings'")."""
    rc = main(["compare", "--scenario", "toy_thermomechanical", "--duration", "3", "--revolutions", "20",
               "--unbalance", "50", "--no-figures", "--quiet", "--out", str(tmp_path / "o")])
    err = capsys.readouterr().err
    assert rc == 2 and "has no bearing results to compare" in err and "Traceback" not in err
    assert not (tmp_path / "o" / "staggered").exists()


def test_an_out_folder_holding_a_comparison_is_refused_before_any_run(tmp_path, capsys):
    """A folder with a previous comparison's runs is refused at once (the message names --overwrite and
    --resume), and the previous results stay as they were."""
    out = tmp_path / "cmp"
    (out / "staggered").mkdir(parents=True)
    (out / "staggered" / "summary.json").write_text("{}")
    assert main(["compare", "--duration", "2", "--unbalance", "712", "--out", str(out), "--quiet"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "already holds a comparison (staggered)" in err[0] and "--overwrite" in err[0]
    assert "--resume to continue it" in err[0]
    assert (out / "staggered" / "summary.json").read_text() == "{}" and not (out / "monolithic").exists()


def test_an_interrupted_overwrite_leaves_no_previous_table(tmp_path, monkeypatch):
    """compare --overwrite interrupted during its runs: the previous table6.json is gone, not left beside runs it
    does not describe (it was kept, with the new runs' folders half made, before)."""
    from rotorcosim.master.compare import schemes as cmp

    out = tmp_path / "cmp"
    out.mkdir()
    (out / "table6.json").write_text('{"speedup": 99}')

    def interrupted(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(cmp, "_warm_up", lambda *a, **k: None)
    monkeypatch.setattr(cmp, "simulate", interrupted)
    assert main(["compare", "--duration", "2", "--unbalance", "712", "--out", str(out), "--quiet", "--overwrite"]) == 130
    assert not (out / "table6.json").exists()


@pytest.mark.parametrize("option", [[], ["--overwrite"], ["--resume"]])
def test_an_out_folder_holding_another_command_s_results_is_refused(tmp_path, capsys, option):
    """A run's folder given to compare: its runs and table were written beside the run's summary.json and
    timeseries.h5, a folder of both (with or without --overwrite); refused before any run, left as it was."""
    out = tmp_path / "o"
    out.mkdir()
    (out / "summary.json").write_text('{"status": "complete"}')
    (out / "timeseries.h5").write_bytes(b"x")
    assert main(["compare", "--duration", "2", "--unbalance", "712", "--out", str(out), "--quiet", *option]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and (f"--out {out} holds files that are not a comparison's (summary.json, timeseries.h5): "
                              "results are never mixed") in err[0], err
    assert sorted(p.name for p in out.iterdir()) == ["summary.json", "timeseries.h5"]


def test_a_table_without_its_runs_is_a_previous_comparison(tmp_path, capsys):
    """Without --overwrite it was dropped unasked; it is refused as a comparison held, and kept."""
    out = tmp_path / "o"
    out.mkdir()
    (out / "table6.json").write_text("{}")
    assert main(["compare", "--duration", "2", "--unbalance", "712", "--out", str(out), "--quiet"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "already holds a comparison (table6.json)" in err[0], err
    assert (out / "table6.json").read_text() == "{}"


EXAMPLES = Path(__file__).resolve().parents[2] / "docs" / "examples"


def test_a_bearing_the_scenario_does_not_have_is_refused_before_any_run(tmp_path, capsys):
    """An engine of bearings 1, 2, 3: the table's bearing 0 was looked up after both runs ("error: '0'", their
    folders left without a table), and --bearing took only 0 or 5."""
    scenario = str(EXAMPLES / "three_bearings" / "blade_loss.toml")
    rc = main(["compare", scenario, "--bearing", "0", "--duration", "0.2", "--revolutions", "4", "--no-figures",
               "--quiet", "--out", str(tmp_path / "o")])
    err = [line for line in capsys.readouterr().err.splitlines() if line.strip()]
    assert rc == 2 and err == ["rotorcosim compare: error: --bearing 0: scenario 'three_bearings_blade_loss' has "
                               "no bearing 0 (its bearings: 1, 2, 3)"], err
    assert not (tmp_path / "o").exists()


def test_an_own_engine_is_compared_at_its_own_level_and_first_bearing():
    """Without --unbalance or --bearing, a scenario of one's own ran at the paper's 2850 N (its own blade is
    1500 N) and tabled bearing 0; the shipped scenarios keep Table 6's 2850 N and bearing 0."""
    from rotorcosim.cases.blade_loss.compare import default_unbalance, table_bearing
    from rotorcosim.master.cli.run import resolve

    own = resolve(str(EXAMPLES / "three_bearings" / "blade_loss.toml"))
    assert default_unbalance(own) == 1500.0 and table_bearing(own, None) == 1 and table_bearing(own, "3") == 3
    for name in ("blade_loss", "blade_loss_712"):
        paper = resolve(name)
        assert default_unbalance(paper) == 2850.0 and table_bearing(paper, None) == 0
