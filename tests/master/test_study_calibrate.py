"""``rotorcosim calibrate`` / :func:`rotorcosim.calibrate` on the two-mass toy (tests/helpers/two_masses.toml).

The reference is synthetic truth: targets computed by the project itself at known parameter values (k1 = 40 N/m,
kc = 100 N/m), which the calibration must recover from a start away from them, within 1 %."""
import csv
import json
import shutil
from pathlib import Path

import pytest

import rotorcosim
from rotorcosim.master.cli.program import main

TOY = Path(__file__).resolve().parents[1] / "helpers" / "two_masses.toml"
TRUTH = {"m1.k": 40.0, "m2.kc": 100.0}
CASES = {"": {}, "pushed": {"m1.v0": 1.0}, "shifted": {"m2.x0": 0.1}}


def write_study(folder: Path, start=(30.0, 150.0), residual="linear") -> Path:
    """A SPEC and its targets: final positions / velocities of the three cases at the truth; m2.v held out."""
    shutil.copy(TOY, folder / "toy.toml")
    sc = rotorcosim.load_scenario(TOY).set(TRUTH)
    rows = ["case,result,value,holdout"]
    for case, over in CASES.items():
        out = rotorcosim.simulate(sc.set(over), record=[]).summary["final_outputs"]
        for port in ("m1.x", "m1.v", "m2.x", "m2.v"):
            if residual == "log" and out[port][0] <= 0:
                continue                        # a log ratio needs positive values
            rows.append(f"{case},final_outputs.{port},{out[port][0]!r},{int(port == 'm2.v')}")
    (folder / "targets.csv").write_text("\n".join(rows) + "\n")
    spec = folder / "cal.toml"
    spec.write_text(f'''[calibrate]
scenario = "toy.toml"
targets = "targets.csv"
residual = "{residual}"
[calibrate.cases.pushed]
"m1.v0" = 1.0
[calibrate.cases.shifted]
"m2.x0" = 0.1
[[calibrate.parameter]]
name = "m1.k"
lower = 20.0
upper = 80.0
start = {start[0]}
scale = "log"
[[calibrate.parameter]]
name = "m2.kc"
lower = 50.0
upper = 200.0
start = {start[1]}
''')
    return spec


def test_synthetic_truth_is_recovered_and_a_rerun_resumes(tmp_path):
    """Truth recovered within 1 % from 25 % / 50 % away; the report's keys are the contract's; the same command
    again reruns nothing, and a calibration whose table lost its last rows reruns only those."""
    spec = write_study(tmp_path)
    rep = rotorcosim.calibrate(spec, tmp_path / "out", serial=True, quiet=True)
    assert rep["status"] == "converged"
    for name, truth in TRUTH.items():
        p = rep["parameters"][name]
        assert abs(p["value"] / truth - 1) < 0.01, (name, p)
        assert p["std_error"] is not None and p["std_error"] < 0.01 * truth
    assert rep["fit_score"]["within_30pct"] == rep["fit_score"]["targets"] == 9
    assert rep["holdout_score"]["targets"] == 3 and rep["holdout_score"]["within_30pct"] == 3
    assert rep["fit_score_start"]["within_30pct"] < 9
    on_disk = json.loads((tmp_path / "out" / "calibration.json").read_text())
    assert on_disk["parameters"]["m1.k"]["value"] == rep["parameters"]["m1.k"]["value"]
    assert (tmp_path / "out" / "calibration.png").stat().st_size > 10_000
    with open(tmp_path / "out" / "evaluations.csv") as fh:
        rows = list(csv.DictReader(fh))
    assert len(rows) == rep["evaluations"]
    assert set(rows[0]) >= {"case", "m1.k", "m2.kc", "final_outputs.m1.x", "final_outputs.m2.v", "status"}

    again = rotorcosim.calibrate(spec, tmp_path / "out", serial=True, quiet=True)
    assert again["evaluations_this_session"] == 0 and again["resumed"]
    assert again["parameters"] == rep["parameters"]

    table = tmp_path / "out" / "evaluations.csv"
    lines = table.read_text().splitlines()
    table.write_text("\n".join(lines[:-5]) + "\n")        # as if interrupted 5 runs before the end
    cut = rotorcosim.calibrate(spec, tmp_path / "out", serial=True, quiet=True)
    assert cut["evaluations_this_session"] == 5
    assert cut["parameters"] == rep["parameters"]


def test_log_residuals_on_dask_through_the_command(tmp_path, capsys):
    """The command on a local Dask cluster of 2 workers, log residuals: the same truth within 1 %."""
    spec = write_study(tmp_path, start=(70.0, 60.0), residual="log")
    assert main(["calibrate", str(spec), "--out", str(tmp_path / "out"), "--workers", "2", "--quiet"]) == 0
    rep = json.loads((tmp_path / "out" / "calibration.json").read_text())
    assert rep["executed_on"].startswith("local cluster, 2 workers")
    for name, truth in TRUTH.items():
        assert abs(rep["parameters"][name]["value"] / truth - 1) < 0.01
    assert f"m1.k = {rep['parameters']['m1.k']['value']:.6g}" in capsys.readouterr().out


def test_a_parameter_ending_at_its_bound_is_warned_about(tmp_path):
    """With m1.k's range [45, 80] N/m excluding its truth (40), the fit ends at the lower bound and says so."""
    spec = write_study(tmp_path, start=(60.0, 150.0))
    spec.write_text(spec.read_text().replace("lower = 20.0", "lower = 45.0"))
    rep = rotorcosim.calibrate(spec, tmp_path / "out", serial=True, quiet=True)
    assert rep["parameters"]["m1.k"]["at_bound"] == "lower"
    assert rep["parameters"]["m1.k"]["value"] == pytest.approx(45.0, rel=1e-3)   # within the search's tolerance
    assert any(w.startswith("m1.k ends at its lower bound") for w in rep["warnings"])


def test_standard_errors_match_linear_regression():
    """fit_errors on a straight line y = a + b t: the textbook standard errors of ordinary least squares
    (s^2 / Sxx for the slope, s^2 (1/n + mean(t)^2 / Sxx) for the intercept; Montgomery & Runger, Applied
    Statistics, sec. 11-4), and a column no residual depends on gets an infinite standard error."""
    import numpy as np

    from rotorcosim.master.study.statistics import fit_errors

    t = np.linspace(0.0, 4.0, 9)
    r = np.array([0.1, -0.2, 0.05, 0.3, -0.1, 0.0, -0.25, 0.15, -0.05])
    J = np.column_stack([np.ones_like(t), t])
    e = fit_errors(J, r)
    s2 = r @ r / (len(t) - 2)
    sxx = ((t - t.mean()) ** 2).sum()
    assert e["std_error"][1] == pytest.approx(np.sqrt(s2 / sxx), rel=1e-12)
    assert e["std_error"][0] == pytest.approx(np.sqrt(s2 * (1 / len(t) + t.mean() ** 2 / sxx)), rel=1e-12)
    assert e["correlation"][0, 1] == pytest.approx(-t.mean() / np.sqrt(sxx / len(t) + t.mean() ** 2), rel=1e-12)
    blind = fit_errors(np.column_stack([J, np.zeros_like(t)]), r)
    assert np.isinf(blind["std_error"][2]) and np.isfinite(blind["std_error"][:2]).all()
