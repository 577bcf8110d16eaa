"""Sweeps under faults, on a real Dask cluster of separate processes (``dask scheduler`` + ``dask worker``, started
and killed here) and on the local cluster: a worker that dies, the scheduler gone, Ctrl-C, ``--resume``, a full
disk, two sweeps into one folder at once.

The faults come from ``tests.helpers.faulty.FaultyNode`` (the toy's thermal node, killing its own process or
sleeping on demand); every case simulates 0.05 s. What is checked each time is what the user sees (exit status,
first line of the error) and what is kept (every finished case's folder whole and readable, sweep.json's
``case_status``, no lock file, no half-written folder).
"""
from __future__ import annotations

import errno
import importlib.util
import json
import os
import pathlib
import signal
import subprocess
import sys
import time
from pathlib import Path

import h5py
import pytest

from rotorcosim.master.cli import main
from rotorcosim.master.run.rundir import LOCK
from rotorcosim.master.sweep import Case, DiskFullError, SweepFolder, run_cases
from tests.helpers import faulty

ROOT = Path(__file__).resolve().parents[2]
_spec = importlib.util.spec_from_file_location("same_results", ROOT / "bench" / "same_results.py")
same_results = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(same_results)


def state(out: Path) -> dict:
    return json.loads((out / "sweep.json").read_text())


def assert_kept(out: Path, names) -> None:
    """Each case of ``names`` is whole and readable; nothing half-written or locked is left in ``out``."""
    for n in names:
        s = json.loads((out / n / "summary.json").read_text())
        assert s["status"] == "complete", (n, s.get("error"))
        with h5py.File(out / n / "timeseries.h5") as f:
            assert f["time"].shape[0] > 10
    left = [p.name for p in out.iterdir() if p.name == LOCK or p.name.endswith(".part")]
    assert not left, left


def cli(*argv, timeout=180, tmpdir=None) -> subprocess.CompletedProcess:
    """``rotorcosim ARGV`` in a process of its own (the way a user runs it); ``tmpdir``: its temporary folder."""
    env = None if tmpdir is None else {**os.environ, "TMPDIR": str(tmpdir)}
    return subprocess.run([sys.executable, "-m", "rotorcosim.master.cli", *map(str, argv)], capture_output=True,
                          text=True, timeout=timeout, env=env)


FOREGROUND = ("import signal, sys\nsignal.signal(signal.SIGINT, signal.default_int_handler)\n"
              "from rotorcosim.master.cli import main\nsys.exit(main(sys.argv[1:]))\n")


def start(*argv) -> subprocess.Popen:
    """``rotorcosim ARGV`` started in a session of its own: a signal to its group is a terminal's Ctrl-C."""
    # SIGINT raising KeyboardInterrupt, as in a terminal's foreground command: pytest started as a background job
    # of a non-interactive shell ignores SIGINT, an ignored signal stays ignored in every child, and the sweep then
    # ran to its end under the Ctrl-C of the test below
    return subprocess.Popen([sys.executable, "-c", FOREGROUND, *map(str, argv)],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, start_new_session=True)


def wait_for(pred, timeout=120.0, what="") -> None:
    deadline = time.monotonic() + timeout
    while not pred():
        if time.monotonic() > deadline:
            pytest.fail(f"timed out waiting for {what}")
        time.sleep(0.05)


@pytest.fixture(scope="module")
def cluster(tmp_path_factory):
    c = faulty.Cluster(tmp_path_factory.mktemp("cluster"), n=2)
    yield c
    c.stop()


def error_line(err: str) -> str:
    """The sweep's one-line error: the line after its wall-time estimate, which it prints once the folder is
    taken, before the first case."""
    lines = err.splitlines()
    assert len(lines) >= 2 and lines[0].startswith("sweep: ") and lines[0].endswith("(estimated)"), err
    return lines[1]


def test_a_case_whose_worker_dies_is_retried_once_then_named(cluster, tmp_path):
    """Three cases on the separate cluster: one kills its worker every time (reported failed by name after one
    retry), one kills it the first time only (its retry completes), one runs plainly. The workers' nannies
    restart the killed workers; the sweep goes on and keeps the two."""
    always = faulty.scenario(_dir(tmp_path, "a"), kill_at=0.01)
    once = faulty.scenario(_dir(tmp_path, "b"), kill_at=0.01, marker=str(tmp_path / "killed_once"))
    plain = faulty.scenario(_dir(tmp_path, "c"))
    out = tmp_path / "out"
    done = run_cases([Case("always", always, duration=0.05), Case("once", once, duration=0.05),
                      Case("plain", plain, duration=0.05)], out, scheduler=cluster.address)
    assert (tmp_path / "killed_once").exists(), (done.status, done.errors)   # the first attempt of "once" did die
    assert done.status == {"always": "failed", "once": "complete", "plain": "complete"}
    assert done.errors["always"].startswith("WorkerDied: its worker died while running it, 2 times"), done.errors
    assert_kept(out, ["once", "plain"])
    failed = json.loads((out / "always" / "summary.json").read_text())   # the case's folder says why
    assert failed["status"] == "failed" and failed["error"] == done.errors["always"]
    s = state(out)
    assert s["status"] == "complete" and s["errors"] == done.errors and s["case_status"] == done.status
    assert "always" in (out / "sweep.csv").read_text().splitlines()[1]
    # the retries are reported: which case, the workers that died under it, the one that ran it again, its result
    assert set(s["retries"]) == {"always", "once"}, s["retries"]
    once_ = s["retries"]["once"]
    assert once_["result"] == "complete" and once_["attempt"] == 2 and len(once_["died_on"]) == 1
    assert once_["worker"].startswith("tcp://") and once_["died_on"][0].startswith("tcp://")
    assert s["retries"]["always"]["result"] == "failed" and len(s["retries"]["always"]["died_on"]) == 2


def test_worker_death_on_the_local_cluster_from_the_command_line(tmp_path):
    """The same fault through ``rotorcosim sweep`` on its own local cluster: exit status 1, the failed case named
    on stderr, the other case kept."""
    sc = faulty.scenario(tmp_path, kill_at=0.01)
    tmp = _dir(tmp_path, "tmp")
    r = cli("sweep", sc, "--set", "node.kill_at=-1,0.01", "--duration", "0.05", "--workers", "2", "--quiet",
            "--out", tmp_path / "out", tmpdir=tmp)
    assert r.returncode == 1, r.stderr
    # the killed workers' case folders went with their workers' directories (they stayed in the temporary folder)
    assert not list(tmp.rglob("rotorcosim-case-*")), list(tmp.rglob("*"))
    lines = r.stderr.splitlines()
    assert lines[0].startswith("sweep: 2 runs of about "), r.stderr       # the estimate, before the first case
    assert lines[1].startswith("  case node.kill_at=0.01 was run again on tcp://") and \
        lines[1].endswith(" died: failed"), r.stderr                        # the retry, named
    assert lines[2].startswith("  case node.kill_at=0.01 failed: WorkerDied: its worker died "
                               "while running it, 2 times (retried 1 time(s))"), r.stderr
    assert "Traceback" not in r.stderr
    assert_kept(tmp_path / "out", ["node.kill_at=-1"])


def test_scheduler_gone_ends_the_sweep_and_keeps_the_finished_cases(tmp_path):
    """The scheduler is killed once the first (fast) case is stored while two slow ones run: the command ends
    with one line naming the scheduler (exit status 1), the fast case kept, the slow ones ``interrupted``; with a
    new cluster, ``--resume`` runs only those two."""
    c = faulty.Cluster(_dir(tmp_path, "cluster"), n=2)
    try:
        sc = faulty.scenario(tmp_path, sleep=0.0)
        out = tmp_path / "out"
        p = start("sweep", sc, "--set", "node.sleep=0,0.2,0.21", "--duration", "0.05", "--scheduler", c.address,
                  "--quiet", "--out", out)
        wait_for(lambda: (out / "node.sleep=0").is_dir(), what="the fast case")
        c.kill_scheduler()
        _, err = p.communicate(timeout=120)
    finally:
        c.stop()
    assert p.returncode == 1, err
    first = error_line(err)
    assert first == (f"rotorcosim sweep: error: the Dask scheduler {c.address} went away: the sweep stopped "
                     f"with 1 of 3 cases complete and kept in {out}; start a scheduler and continue with --resume")
    assert_kept(out, ["node.sleep=0"])
    s = state(out)
    assert s["status"] == "failed"
    assert s["case_status"] == {"node.sleep=0": "complete", "node.sleep=0.2": "interrupted",
                                "node.sleep=0.21": "interrupted"}


@pytest.mark.slow   # ~10-12 s (measured; a sweep interrupted and resumed)
def test_ctrl_c_stops_cleanly_and_resume_reruns_only_the_rest_bit_identical(tmp_path):
    """A terminal's Ctrl-C (SIGINT to the command's whole process group, its local workers too) once the first
    case is stored: exit status 130, one line saying what was kept, the finished cases whole, the others
    ``interrupted`` (running) or ``pending``; ``--resume`` runs only those, leaves the kept ones untouched, and
    every case equals an uninterrupted sweep's, bit for bit (bench/same_results.py)."""
    sc = faulty.scenario(tmp_path, sleep=0.01)
    out, ref = tmp_path / "out", tmp_path / "ref"
    args = ["sweep", sc, "--unbalance", "1,2,3,4", "--duration", "0.05", "--quiet"]
    p = start(*args, "--workers", "2", "--out", out)
    wait_for(lambda: any(out.glob("level_*")), what="the first case")
    os.killpg(p.pid, signal.SIGINT)
    _, err = p.communicate(timeout=120)
    assert p.returncode == 130, err
    s = state(out)
    kept = [n for n, st in s["case_status"].items() if st == "complete"]
    assert error_line(err) == (f"rotorcosim sweep: interrupted: {len(kept)} of 4 cases complete and kept in "
                                   f"{out} (sweep.json: case_status); continue with --resume"), err
    assert "Traceback" not in err
    assert s["status"] == "interrupted" and 1 <= len(kept) < 4
    assert set(s["case_status"].values()) <= {"complete", "interrupted", "pending"}
    assert "interrupted" in s["case_status"].values()
    assert_kept(out, kept)
    stamps = {n: (out / n / "timeseries.h5").stat().st_mtime_ns for n in kept}

    # each in a process of its own, as a user runs them (the numbers are the same from one fresh process to another)
    assert cli(*args, "--serial", "--resume", "--out", out).returncode == 0
    assert cli(*args, "--serial", "--out", ref).returncode == 0
    assert {n: (out / n / "timeseries.h5").stat().st_mtime_ns for n in kept} == stamps   # not run again
    assert state(out)["status"] == "complete"
    for n in ("level_1", "level_2", "level_3", "level_4"):
        assert same_results.differences(out / n, ref / n) == [], n
    assert (out / "sweep.csv").read_text() == (ref / "sweep.csv").read_text()
    assert_kept(out, ["level_1", "level_2", "level_3", "level_4"])


def test_resume_refuses_another_sweep(tmp_path, capsys):
    sc = faulty.scenario(tmp_path)
    out = tmp_path / "out"
    base = ["sweep", str(sc), "--duration", "0.05", "--serial", "--quiet", "--out", str(out)]
    assert main([*base, "--unbalance", "1,2"]) == 0
    assert main([*base, "--unbalance", "1,3", "--resume"]) == 2
    assert "holds a sweep of other cases (level_1, level_2): give the same levels" in capsys.readouterr().err
    assert main([*base[:2], "--duration", "0.04", *base[4:], "--unbalance", "1,2", "--resume"]) == 2
    assert "give the same scenario, duration and schedule" in capsys.readouterr().err
    assert main([*base, "--unbalance", "1,2", "--resume"]) == 0   # nothing left to run: complete at once
    assert state(out)["executed_on"] == "nothing to run (every case complete)"


def test_full_disk_is_named_and_the_stored_cases_kept(tmp_path, monkeypatch, capsys):
    """The disk fills while the second case is stored: one line naming the folder (exit status 1), the first
    case whole, no half-written folder; after space is freed, ``--resume`` completes the sweep."""
    sc = faulty.scenario(tmp_path)
    out = tmp_path / "out"
    real = pathlib.Path.write_bytes

    def full(self, data):
        if ".level_2.part" in str(self):
            raise OSError(errno.ENOSPC, "No space left on device", str(self))
        return real(self, data)

    monkeypatch.setattr(pathlib.Path, "write_bytes", full)
    argv = ["sweep", str(sc), "--unbalance", "1,2,3", "--duration", "0.05", "--serial", "--quiet", "--out", str(out)]
    assert main(argv) == 1
    err = capsys.readouterr().err
    assert error_line(err) == (f"rotorcosim sweep: error: the disk holding {out} is full (storing case level_2); "
                                   "free space and continue with --resume"), err
    assert_kept(out, ["level_1"])
    assert not (out / "level_2").exists() and not (out / "level_3").exists()
    assert state(out)["case_status"] == {"level_1": "complete", "level_2": "interrupted", "level_3": "pending"}
    monkeypatch.setattr(pathlib.Path, "write_bytes", real)
    assert main([*argv, "--resume"]) == 0
    assert_kept(out, ["level_1", "level_2", "level_3"])


def test_full_disk_from_the_api_is_a_disk_full_error(tmp_path, monkeypatch):
    sc = faulty.scenario(tmp_path)
    monkeypatch.setattr(pathlib.Path, "write_bytes",
                        lambda self, data: (_ for _ in ()).throw(OSError(errno.EDQUOT, "Disk quota exceeded")))
    with pytest.raises(DiskFullError, match="is full"):
        run_cases([Case("a", sc, duration=0.05)], tmp_path / "out", serial=True)


def test_a_second_sweep_into_the_same_folder_is_refused_and_no_lock_is_left(tmp_path, capsys):
    sc = faulty.scenario(tmp_path)
    out = tmp_path / "out"
    argv = ["sweep", str(sc), "--unbalance", "1", "--duration", "0.05", "--serial", "--quiet", "--out", str(out)]
    with SweepFolder(out):   # a sweep holding the folder (its lock is an flock: any other holder is refused)
        assert main(argv) == 2
        err = capsys.readouterr().err
        assert err.splitlines()[0] == (f"rotorcosim sweep: error: --out {out}: another sweep is writing into this "
                                       f"folder (process {os.getpid()}); wait for it to end or choose another "
                                       "folder"), err
        assert (out / LOCK).exists()   # the refused sweep left the holder's lock alone
    assert not out.exists() or [p.name for p in out.iterdir()] == []
    assert main(argv) == 0
    assert sorted(p.name for p in out.iterdir()) == ["level_1", "sweep.csv", "sweep.json"]   # no lock file left


def test_a_second_sweep_at_once_from_another_process(tmp_path):
    """Two ``rotorcosim sweep`` processes into one folder: the second is refused naming the first's process. The
    first is held open (its node waits for a file) until the second has been refused, whatever the load."""
    release = tmp_path / "release"
    sc = faulty.scenario(tmp_path, hold=str(release), started=str(tmp_path / "started"))
    out = tmp_path / "out"
    argv = ["sweep", sc, "--unbalance", "1,2", "--duration", "0.05", "--serial", "--quiet", "--out", out]
    first = start(*argv)
    try:
        wait_for(lambda: (tmp_path / "started").exists(), what="the first sweep's first case to step")
        r = cli(*argv)
    finally:
        release.write_text("")
    first.communicate(timeout=120)
    assert r.returncode == 2
    assert f"another sweep is writing into this folder (process {first.pid})" in r.stderr.splitlines()[0]
    assert first.returncode == 0
    assert_kept(out, ["level_1", "level_2"])


def _dir(root: Path, name: str) -> Path:
    (root / name).mkdir()
    return root / name


@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM])
def test_a_serial_sweep_stops_at_a_signal_during_a_case(tmp_path, sig):
    """``--serial``: the case running takes the signal over (a run stops at its next checkpoint, or completes when
    none comes, as these 0.05 s cases do); the sweep still stops after it, exit status 130, the cases not started
    ``pending`` (it went on to the next case before)."""
    started = tmp_path / "started"
    sc = faulty.scenario(tmp_path, sleep=0.02, started=str(started))
    out = tmp_path / "out"
    p = start("sweep", sc, "--unbalance", "1,2,3", "--duration", "0.05", "--serial", "--quiet", "--out", out)
    # the second case has taken its first step (each takes ~1 s of sleeping steps: the signal comes within it)
    wait_for(lambda: started.exists() and len(started.read_text().splitlines()) >= 2, what="the second case")
    os.killpg(p.pid, sig)
    _, err = p.communicate(timeout=120)
    assert p.returncode == 130, err
    assert error_line(err).startswith("rotorcosim sweep: interrupted: "), err
    s = state(out)
    assert s["status"] == "interrupted" and s["case_status"]["level_3"] == "pending", s["case_status"]
    assert s["case_status"]["level_2"] in ("complete", "interrupted")
    assert_kept(out, [n for n, st in s["case_status"].items() if st == "complete"])
