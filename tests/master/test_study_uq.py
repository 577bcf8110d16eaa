"""``rotorcosim uq`` / :func:`rotorcosim.uq`: statistics against known answers.

References: a linear toy whose output is analytically normal (the two-mass system's final position is linear in the
initial displacement, so with x0 normal it is normal with mean a mu and standard deviation |a| sigma, a measured
from the same model); the Ishigami function's exact Sobol' indices (Ishigami & Homma 1990; Sobol' 2007 / Saltelli
et al. 2008 give S1 = 0.3139, 0.4424, 0 and ST = 0.5576, 0.4424, 0.2437 for a = 7, b = 0.1)."""
import csv
import json
import math
import shutil
from pathlib import Path

import pytest

import rotorcosim

TOY = Path(__file__).resolve().parents[1] / "helpers" / "two_masses.toml"
ROOT = Path(__file__).resolve().parents[2]


def write_spec(folder: Path, body: str) -> Path:
    shutil.copy(TOY, folder / "toy.toml")
    spec = folder / "uq.toml"
    spec.write_text('[uq]\nscenario = "toy.toml"\n' + body)
    return spec


def test_linear_toy_statistics_within_their_intervals(tmp_path):
    """Monte Carlo (64 samples, iid): the exact mean, standard deviation and 5th / 50th / 95th percentiles of the
    normal output lie inside the reported 95 % intervals; samples.csv has one row per sample."""
    from scipy.stats import norm

    mu, sigma = 0.1, 0.02
    spec = write_spec(tmp_path, f'''samples = 64
sampler = "mc"
seed = 7
results = ["final_outputs.m1.x"]
[[uq.parameter]]
name = "m1.x0"
distribution = "normal"
mean = {mu}
std = {sigma}
''')
    rep = rotorcosim.uq(spec, tmp_path / "out", serial=True, quiet=True)
    sc = rotorcosim.load_scenario(TOY)
    a = rotorcosim.simulate(sc.set({"m1.x0": 1.0}), record=[]).summary["final_outputs"]["m1.x"][0]
    zero = rotorcosim.simulate(sc.set({"m1.x0": 0.0}), record=[]).summary["final_outputs"]["m1.x"][0]
    assert zero == 0.0                              # linear and homogeneous: x(T) = a x0
    r = rep["results"]["final_outputs.m1.x"]
    exact = {"mean": a * mu, "std": abs(a) * sigma}
    for q, z in (("p5", norm.ppf(0.05)), ("p50", 0.0), ("p95", norm.ppf(0.95))):
        exact[q] = a * mu + abs(a) * sigma * z
    for key, value in exact.items():
        lo, hi = r[f"{key}_ci"]
        assert lo <= value <= hi, (key, value, lo, hi)
        assert hi - lo < 0.5 * abs(a) * sigma * 4      # an interval, not everything
    assert r["n"] == 64 and rep["failed"]["count"] == 0
    with open(tmp_path / "out" / "samples.csv") as fh:
        rows = list(csv.DictReader(fh))
    assert [int(x["sample"]) for x in rows] == list(range(64))
    assert set(rows[0]) >= {"sample", "m1.x0", "final_outputs.m1.x", "status"}
    assert json.loads((tmp_path / "out" / "uq.json").read_text())["results"]["final_outputs.m1.x"]["mean"] == r["mean"]
    for fig in ("uq_histograms.png", "uq_tornado.png"):
        assert (tmp_path / "out" / fig).stat().st_size > 10_000


def test_ishigami_sobol_indices_within_0_05(tmp_path):
    """The sobol sampler (Saltelli, 1024 x 5 runs) through uq() with the Ishigami function as the run: first-order
    and total indices within 0.05 of the exact ones."""
    exact_s1, exact_st = (0.3139, 0.4424, 0.0), (0.5576, 0.4424, 0.2437)
    body = 'samples = 1024\nsampler = "sobol"\nseed = 2\nresults = ["y"]\n'
    for name in ("m1.x0", "m1.v0", "m2.x0"):
        body += f'[[uq.parameter]]\nname = "{name}"\ndistribution = "uniform"\nlower = {-math.pi}\nupper = {math.pi}\n'
    spec = write_spec(tmp_path, body)
    from tests.helpers.study_tasks import ishigami

    rep = rotorcosim.uq(spec, tmp_path / "out", serial=True, quiet=True, task=ishigami)
    assert rep["samples"] == 1024 * 5
    idx = rep["results"]["y"]["sobol"]["indices"]
    for name, s1, st in zip(("m1.x0", "m1.v0", "m2.x0"), exact_s1, exact_st):
        assert abs(idx[name]["S1"] - s1) < 0.05, (name, idx[name])
        assert abs(idx[name]["ST"] - st) < 0.05, (name, idx[name])
    # the moments too: mean a/2 = 3.5, variance a^2/8 + b pi^4/5 + b^2 pi^8/18 + 1/2 = 13.8446
    r = rep["results"]["y"]
    assert r["mean_ci"][0] <= 3.5 <= r["mean_ci"][1]
    assert r["std_ci"][0] <= math.sqrt(13.8446) <= r["std_ci"][1]


def test_failed_samples_are_counted_and_named_and_a_rerun_resumes(tmp_path, capsys):
    """Samples whose run fails stay in samples.csv (status failed, the error) and are named in uq.json; the
    command exits 1 and says how many failed; the same command again runs nothing."""
    spec = write_spec(tmp_path, '''samples = 16
sampler = "lhs"
seed = 1
results = ["y"]
[[uq.parameter]]
name = "m1.x0"
distribution = "normal"
mean = 0.0
std = 1.0
''')
    from tests.helpers.study_tasks import fails_when_negative

    rep = rotorcosim.uq(spec, tmp_path / "out", serial=True, quiet=True, task=fails_when_negative)
    with open(tmp_path / "out" / "samples.csv") as fh:
        rows = list(csv.DictReader(fh))
    bad = [int(r["sample"]) for r in rows if r["status"] == "failed"]
    assert len(rows) == 16 and bad and len(bad) < 16
    assert rep["failed"]["count"] == len(bad)
    assert [s["sample"] for s in rep["failed"]["samples"]] == bad
    assert all("diverged" in s["error"] for s in rep["failed"]["samples"])
    assert rep["results"]["y"]["n"] == 16 - len(bad)
    again = rotorcosim.uq(spec, tmp_path / "out", serial=True, quiet=True, task=fails_when_negative)
    assert again["samples_this_session"] == 0 and again["failed"] == rep["failed"]


def test_a_study_whose_every_sample_fails_reports_them(tmp_path):
    """Every sample failed (a normal of mean -10: all negative): the study reports them all and no statistics;
    the analysis crashed on the empty set of results (numpy's ptp of a zero-size array)."""
    spec = write_spec(tmp_path, '''samples = 4
sampler = "mc"
seed = 1
results = ["y"]
[[uq.parameter]]
name = "m1.x0"
distribution = "normal"
mean = -10.0
std = 1.0
''')
    from tests.helpers.study_tasks import fails_when_negative

    rep = rotorcosim.uq(spec, tmp_path / "out", serial=True, quiet=True, task=fails_when_negative)
    assert rep["failed"]["count"] == 4 and rep["results"]["y"]["n"] == 0 and "sobol" not in rep["results"]["y"]


@pytest.mark.slow   # ~14-18 s (measured; two studies in subprocesses, a worker killed)
def test_a_worker_that_dies_is_retried_once_then_reported(tmp_path):
    """On a local Dask cluster of one worker (its nanny restarts it after each death): a sample whose worker dies
    once is run again and succeeds; a sample whose worker dies every time is reported failed after a second try,
    not lost and not retried forever. Each study runs in a process of its own under a timeout, so that a study
    left waiting for a worker fails here instead of hanging the suite (each takes ~5 s)."""
    import os
    import subprocess
    import sys

    spec = write_spec(tmp_path, '''samples = 2
sampler = "mc"
results = ["y"]
[[uq.parameter]]
name = "m1.x0"
distribution = "uniform"
lower = 0.0
upper = 1.0
''')
    env = {**os.environ, "PYTHONPATH": f"{ROOT}:{os.environ.get('PYTHONPATH', '')}", "STUDY_MARKERS": str(tmp_path)}

    def study(task: str) -> dict:
        code = (f"import json, rotorcosim; from tests.helpers.study_tasks import {task}; "
                f"rep = rotorcosim.uq({str(spec)!r}, {str(tmp_path / task)!r}, workers=1, quiet=True, task={task}); "
                f"print(json.dumps({{'failed': rep['failed'], 'n': rep['results'].get('y', {{}}).get('n')}}))")
        proc = subprocess.run([sys.executable, "-c", code], env=env, cwd=ROOT, capture_output=True, text=True,
                              timeout=120)
        assert proc.returncode == 0, proc.stderr
        return json.loads(proc.stdout.splitlines()[-1])

    rep = study("dies_once")
    assert rep["failed"]["count"] == 0 and rep["n"] == 2
    assert len(list(tmp_path.glob("0.*"))) == 2          # both samples' first worker did die
    rep = study("always_dies")
    assert rep["failed"]["count"] == 2
    assert all(s["error"].startswith("KilledWorker: ") and "tried 2 times" in s["error"]
               for s in rep["failed"]["samples"]), rep["failed"]


@pytest.mark.slow   # ~8-10 s (measured; a study stopped and resumed)
def test_a_study_stopped_by_sigterm_says_so_and_resumes(tmp_path):
    """A UQ process stopped by SIGTERM half-way writes uq.json with status "interrupted" and keeps the finished
    samples; the same call again runs only the others and ends complete with every sample."""
    import os
    import signal
    import subprocess
    import sys
    import time

    spec = write_spec(tmp_path, '''samples = 30
sampler = "lhs"
results = ["y"]
[[uq.parameter]]
name = "m1.x0"
distribution = "uniform"
lower = 0.0
upper = 1.0
''')
    code = ("import rotorcosim; from tests.helpers.study_tasks import slow; "
            f"rotorcosim.uq({str(spec)!r}, {str(tmp_path / 'out')!r}, serial=True, quiet=True, task=slow)")
    env = {**os.environ, "PYTHONPATH": f"{ROOT}:{os.environ.get('PYTHONPATH', '')}"}
    proc = subprocess.Popen([sys.executable, "-c", code], env=env, cwd=ROOT, stderr=subprocess.PIPE)
    table = tmp_path / "out" / "samples.csv"
    deadline = time.time() + 60
    while time.time() < deadline and (not table.exists() or len(table.read_text().splitlines()) < 6):
        time.sleep(0.05)
    proc.send_signal(signal.SIGTERM)
    proc.wait(timeout=60)
    report = json.loads((tmp_path / "out" / "uq.json").read_text())
    assert report["status"] == "interrupted", report
    done = len(table.read_text().splitlines()) - 1
    assert 5 <= done < 30
    from tests.helpers.study_tasks import slow

    rep = rotorcosim.uq(spec, tmp_path / "out", serial=True, quiet=True, task=slow)
    assert rep["status"] == "complete" and rep["samples_this_session"] == 30 - done
    assert rep["results"]["y"]["n"] == 30


def test_on_a_running_scheduler_by_its_address(tmp_path, monkeypatch):
    """scheduler=ADDRESS (``--scheduler``): the samples run on that cluster's workers, which stay up after."""
    import os

    from dask.distributed import LocalCluster

    monkeypatch.setenv("PYTHONPATH", f"{ROOT}:{os.environ.get('PYTHONPATH', '')}")
    spec = write_spec(tmp_path, '''samples = 4
sampler = "mc"
results = ["final_outputs.m1.x"]
[[uq.parameter]]
name = "m1.x0"
distribution = "uniform"
lower = 0.05
upper = 0.15
''')
    with LocalCluster(n_workers=1, threads_per_worker=1, processes=True, dashboard_address=":0") as cluster:
        rep = rotorcosim.uq(spec, tmp_path / "out", scheduler=cluster.scheduler_address, quiet=True)
        assert rep["executed_on"] == f"{cluster.scheduler_address}, 1 workers"
        assert rep["failed"]["count"] == 0 and rep["results"]["final_outputs.m1.x"]["n"] == 4
        assert len(cluster.scheduler_info["workers"]) == 1


@pytest.mark.parametrize("samples", [24, 40, 44])
def test_first_order_indices_only_from_enough_samples(tmp_path, samples):
    """RBD-FAST's indices (an lhs sample) are reported from 44 samples on, each with a confidence half-width above 0;
    below, uq.json says why there are none. Before: 24 samples gave indices summing to about 2 with half-widths 0,
    and 40 samples ended the study, all its runs done, in SALib's ZeroDivisionError (uq.json left 'running')."""
    body = f'samples = {samples}\nsampler = "lhs"\nseed = 1\nresults = ["y"]\n'
    for name in ("m1.x0", "m1.v0", "m2.x0"):
        body += f'[[uq.parameter]]\nname = "{name}"\ndistribution = "uniform"\nlower = {-math.pi}\nupper = {math.pi}\n'
    spec = write_spec(tmp_path, body)
    from tests.helpers.study_tasks import ishigami

    rep = rotorcosim.uq(spec, tmp_path / "out", serial=True, quiet=True, task=ishigami)
    assert rep["status"] == "complete"
    sobol = rep["results"]["y"]["sobol"]
    if samples < 44:
        assert "indices" not in sobol and f"from {samples} successful samples" in sobol["note"], sobol
        assert "needs 44 at least" in sobol["note"]
    else:
        assert all(i["S1_conf"] > 0 for i in sobol["indices"].values()), sobol
