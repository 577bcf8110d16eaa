"""``rotorcosim compare`` under faults: Ctrl-C then ``--resume``, a full disk, two comparisons into one folder.

A comparison is two runs made one after the other in the command's own process (no Dask), so "a worker that
dies" and "the scheduler gone" do not apply; what is checked is what the user sees (exit status, first line) and
what is kept (the complete run's folder, whole and untouched by the resume). 0.2 s of the blade-loss system, 2
revolutions in the staggered run's thermo-mechanical intervals, one timing: a few seconds a comparison.
"""
from __future__ import annotations

import errno
import json
import os
import pathlib
import signal
import subprocess
import sys
import time

import h5py
import pytest

from rotorcosim.master.cli import main
from rotorcosim.master.run.rundir import LOCK
from rotorcosim.master.sweep.lock import FolderLock

#: 6 revolutions: the staggered run's first thermo-mechanical interval (0.011 s) holds the blade release at 0.01 s,
#: as the comparison's own does (with fewer, a thermal-only interval would end at it: a time event, its line on stderr)
ARGS = ["compare", "--duration", "0.2", "--revolutions", "6", "--timing-runs", "1", "--no-figures", "--quiet"]


def summary(folder) -> dict:
    return json.loads((folder / "summary.json").read_text())


def running(folder) -> bool:
    try:
        return summary(folder)["status"] == "running"
    except (OSError, ValueError, KeyError):
        return False


def complete(folder) -> bool:
    try:
        return summary(folder)["status"] == "complete"
    except (OSError, ValueError, KeyError):
        return False


@pytest.mark.slow   # ~12 s of CPU time (measured): three comparisons
def test_ctrl_c_keeps_the_complete_run_and_resume_runs_only_the_other(tmp_path):
    """Ctrl-C (SIGINT to the command's process group) while the monolithic run goes: exit status 130, one line
    saying which run is kept, the staggered run whole, the monolithic one ``interrupted``; ``--resume`` runs the
    monolithic run only and its table's results equal an uninterrupted comparison's, bit for bit."""
    out, ref = tmp_path / "out", tmp_path / "ref"
    p = subprocess.Popen([sys.executable, "-m", "rotorcosim.master.cli", *ARGS, "--out", str(out)],
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, start_new_session=True)
    deadline = time.monotonic() + 120
    while not complete(out / "staggered"):
        assert time.monotonic() < deadline and p.poll() is None, "the staggered run did not complete"
        time.sleep(0.05)
    while not running(out / "monolithic"):   # the monolithic run (~2 s) under way: its summary says so
        assert time.monotonic() < deadline and p.poll() is None, "the monolithic run did not start"
        time.sleep(0.05)
    os.killpg(p.pid, signal.SIGINT)
    _, err = p.communicate(timeout=120)
    assert p.returncode == 130, err
    assert err.splitlines()[0] == (f"rotorcosim compare: interrupted: staggered complete (kept in {out / 'staggered'})"
                                   ", monolithic not complete; continue with --resume"), err
    assert summary(out / "monolithic")["status"] == "interrupted"
    with h5py.File(out / "staggered" / "timeseries.h5") as f:
        assert f["time"].shape[0] > 10
    assert not (out / "table6.json").exists() and not (out / LOCK).exists()
    stamp = (out / "staggered" / "timeseries.h5").stat().st_mtime_ns

    # each in a process of its own, as a user runs them (in this one, what earlier tests ran changes the staggered
    # run's last digits: a run's numbers are the same from one fresh process to another)
    for argv in ([*ARGS, "--out", str(out), "--resume"], [*ARGS, "--out", str(ref)]):
        r = subprocess.run([sys.executable, "-m", "rotorcosim.master.cli", *argv], capture_output=True, text=True,
                           timeout=300)
        assert r.returncode == 0, r.stderr
    assert (out / "staggered" / "timeseries.h5").stat().st_mtime_ns == stamp    # kept, not run again
    a, b = (json.loads((d / "table6.json").read_text()) for d in (out, ref))
    for key in ("results", "largest_error_pct", "timeline_staggered", "monolithic_reused_from"):
        assert a[key] == b[key], key
    assert not (out / LOCK).exists()


def test_resume_of_another_comparison_is_refused(tmp_path, capsys):
    out = tmp_path / "out"
    assert main([*ARGS, "--out", str(out)]) == 0
    argv = [a if a != "0.2" else "0.15" for a in ARGS]
    assert main([*argv, "--out", str(out), "--resume"]) == 2
    assert "holds a run of 'blade_loss_staggered' at 2850.0 N over 0.2 s, not 'blade_loss_staggered' at 2850.0 N " \
           "over 0.15 s" in capsys.readouterr().err
    assert main([*ARGS, "--out", str(tmp_path / "new"), "--resume"]) == 2
    assert "holds no comparison to continue" in capsys.readouterr().err


def test_full_disk_at_the_table_is_named_and_resume_writes_it(tmp_path, monkeypatch, capsys):
    out = tmp_path / "out"
    real = pathlib.Path.write_text

    def full(self, *a, **k):
        if self.name == "table6.json.part":
            raise OSError(errno.ENOSPC, "No space left on device", str(self))
        return real(self, *a, **k)

    monkeypatch.setattr(pathlib.Path, "write_text", full)
    assert main([*ARGS, "--out", str(out)]) == 1
    err = capsys.readouterr().err
    assert err.splitlines()[0] == (f"rotorcosim compare: error: the disk holding {out} is full (writing "
                                   "table6.json); free space and continue with --resume"), err
    assert complete(out / "staggered") and complete(out / "monolithic")
    assert sorted(p.name for p in out.iterdir()) == ["monolithic", "staggered"]
    stamps = [(out / k / "timeseries.h5").stat().st_mtime_ns for k in ("staggered", "monolithic")]
    monkeypatch.setattr(pathlib.Path, "write_text", real)
    assert main([*ARGS, "--out", str(out), "--resume"]) == 0
    assert json.loads((out / "table6.json").read_text())["results"]
    assert [(out / k / "timeseries.h5").stat().st_mtime_ns for k in ("staggered", "monolithic")] == stamps


def test_a_second_comparison_into_the_same_folder_is_refused(tmp_path, capsys):
    out = tmp_path / "out"
    out.mkdir()
    with FolderLock(out, "comparison"):
        assert main([*ARGS, "--out", str(out)]) == 2
        err = capsys.readouterr().err
        assert err.splitlines()[0] == (f"rotorcosim compare: error: --out {out}: another comparison is writing into "
                                       f"this folder (process {os.getpid()}); wait for it to end or choose another "
                                       "folder"), err
    assert [p.name for p in out.iterdir()] == []
