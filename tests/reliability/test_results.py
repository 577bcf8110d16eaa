"""Results are never mixed or lost: folder policy, lock, status, interruption and a full disk."""
import errno
import json

import h5py
import numpy as np
import pytest

from rotorcosim import scenarios
from rotorcosim.master.run import checkpoint
from rotorcosim.master.cli.run import execute
from rotorcosim.master.observer.recorder import Recorder
from rotorcosim.master.run.rundir import OutputFolderError, RunFolder
from rotorcosim.master.scenario.build import load_scenario


def toy():
    return load_scenario(scenarios.path("toy_thermomechanical"))


def summary(out):
    return json.loads((out / "summary.json").read_text())


def test_complete_run_has_status_and_no_checkpoint(tmp_path):
    s = execute(toy(), tmp_path / "o", duration=1.0, figures=False)
    assert s["status"] == "complete" and summary(tmp_path / "o")["status"] == "complete"
    assert s["estimate"]["steps"] == 300 + 14  # TM 0.3 s at 1 ms + TO 0.7 s at 0.05 s, counted exactly
    assert not (tmp_path / "o" / "checkpoint.pkl").exists()


def test_second_run_refused_then_overwrite_clears_the_old_results(tmp_path):
    out = tmp_path / "o"
    execute(toy(), out, duration=1.0, figures=False)
    (out / "fig99_old.png").write_bytes(b"old figure")
    with pytest.raises(OutputFolderError, match="is not empty .*--overwrite"):
        execute(toy(), out, duration=0.5, figures=False)
    assert summary(out)["duration_s"] == 1.0  # untouched
    s = execute(toy(), out, duration=0.5, figures=False, overwrite=True)
    assert s["duration_s"] == 0.5
    assert not (out / "fig99_old.png").exists()  # the earlier run's files are gone, not mixed in


def test_overwrite_never_clears_foreign_files(tmp_path):
    out = tmp_path / "o"
    out.mkdir()
    (out / "thesis.tex").write_text("precious")
    with pytest.raises(OutputFolderError, match="not a run's results .*thesis.tex"):
        execute(toy(), out, duration=0.5, figures=False, overwrite=True)
    assert (out / "thesis.tex").read_text() == "precious"


def test_lock_stops_a_second_concurrent_run(tmp_path):
    out = tmp_path / "o"
    with RunFolder(out):
        with pytest.raises(OutputFolderError, match=r"another run is writing into this folder \(process \d+\)"):
            execute(toy(), out, duration=0.5, figures=False)
    # released: the lock file goes with the lock, and the refused run wrote nothing
    assert [p.name for p in out.iterdir()] == []
    assert execute(toy(), out, duration=0.5, figures=False)["status"] == "complete"


def test_lock_from_another_process(tmp_path):
    """flock is per open file: a second process is refused while the first holds it."""
    import subprocess
    import sys

    out = tmp_path / "o"
    with RunFolder(out):
        code = (f"from rotorcosim.master.run.rundir import RunFolder\n"
                f"try:\n    RunFolder({str(out)!r}).__enter__()\nexcept ValueError as e:\n    print(e)\n")
        res = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert "another run is writing into this folder" in res.stdout


def test_running_status_is_written_first(tmp_path, monkeypatch):
    """A run killed without a chance to clean up (SIGKILL) leaves status "running", never an older result."""
    from rotorcosim.master.simulation import Simulation

    seen = {}

    def run(self, schedule):
        seen.update(summary(tmp_path / "o"))
        raise SystemExit("killed")

    monkeypatch.setattr(Simulation, "run", run)
    with pytest.raises(SystemExit):
        execute(toy(), tmp_path / "o", duration=0.5, figures=False)
    assert seen["status"] == "running" and seen["pid"] > 0


def test_sigint_ends_with_readable_series_and_summary(tmp_path, sigint_at):
    sigint_at(0.5)
    out = tmp_path / "o"
    with pytest.raises(checkpoint.RunInterrupted, match="SIGINT received"):
        execute(toy(), out, duration=5.0, figures=False)
    s = summary(out)
    assert s["status"] == "interrupted" and "SIGINT" in s["error"]
    with h5py.File(out / "timeseries.h5") as f:
        assert f.attrs["complete"] == False  # noqa: E712 - a numpy bool: `is` would not match
        t = f["time"][...]
        assert len(t) > 100 and np.all(np.diff(t) > 0) and np.all(np.isfinite(f["osc.x"][...]))


def test_sigterm_too(tmp_path, monkeypatch):
    import os
    import signal

    from rotorcosim.master.observer.progress import Progress

    original = Progress.step

    def step(self, sim, t):
        if t > 0.2 and not getattr(self, "_sent", False):
            self._sent = True
            os.kill(os.getpid(), signal.SIGTERM)
        original(self, sim, t)

    monkeypatch.setattr(Progress, "step", step)
    with pytest.raises(checkpoint.RunInterrupted, match="SIGTERM"):
        execute(toy(), tmp_path / "o", duration=5.0, figures=False)
    assert summary(tmp_path / "o")["status"] == "interrupted"
    # the handlers are restored after the run
    assert signal.getsignal(signal.SIGTERM) in (signal.SIG_DFL, None) or callable(signal.getsignal(signal.SIGTERM))


def test_disk_full_keeps_what_was_flushed(tmp_path, monkeypatch):
    """The disk fills after the first chunks: a clear OSError, status failed, and the flushed rows readable."""
    calls = []
    original = Recorder.flush

    def flush(self):
        calls.append(1)
        if len(calls) > 2:
            raise OSError(errno.ENOSPC, "No space left on device", str(self.path))
        original(self)

    monkeypatch.setattr(Recorder, "flush", flush)
    # chunks of 300 rows, so that the disk fills in mid-run (interval ends no longer flush: checkpoint.END_GAP_S)
    monkeypatch.setattr("rotorcosim.master.run.session.Recorder", lambda *a, **kw: Recorder(*a, chunk=300, **kw))
    out = tmp_path / "o"
    sc = toy()
    with pytest.raises(OSError, match="No space left"):
        execute(sc, out, duration=20.0, figures=False)
    s = summary(out)
    assert s["status"] == "failed" and "No space left" in s["error"] and s["t_end_s"] < 20.0
    with h5py.File(out / "timeseries.h5") as f:
        n = f["time"].shape[0]
        assert n == 600  # the two chunks flushed before the disk filled
        assert np.all(np.isfinite(f["time"][...])) and np.all(np.diff(f["time"][...]) > 0)
        assert f.attrs["complete"] == False  # noqa: E712 - a numpy bool: `is` would not match


def test_disk_nearly_full_is_refused_before_hdf5_breaks(tmp_path, monkeypatch):
    """A write the disk cannot hold is refused before HDF5 starts it (a failed HDF5 write leaves a file that
    cannot be closed: measured on a full 300 KiB tmpfs, the process then crashed); the disk 'fills' after the
    first flushes here, through the free space the recorder asks the system for."""
    import os as _os

    from rotorcosim.master.observer import recorder

    real = _os.statvfs
    calls = []

    class Full:
        def __init__(self, st):
            self.f_frsize = st.f_frsize
            self.f_bavail = 0 if len(calls) > 2 else st.f_bavail

    def statvfs(path):
        calls.append(path)
        return Full(real(path))

    monkeypatch.setattr(recorder.os, "statvfs", statvfs)
    # chunks of 300 rows, so that the disk fills in mid-run (interval ends no longer flush: checkpoint.END_GAP_S)
    monkeypatch.setattr("rotorcosim.master.run.session.Recorder", lambda *a, **kw: recorder.Recorder(*a, chunk=300, **kw))
    out = tmp_path / "o"
    with pytest.raises(OSError, match="No space left on device for the time series"):
        execute(toy(), out, duration=20.0, figures=False)
    assert summary(out)["status"] == "failed"
    with h5py.File(out / "timeseries.h5") as f:
        assert f["time"].shape[0] >= 300 and f.attrs["complete"] == False  # noqa: E712 - a numpy bool: `is` would not match
        assert "No space left" in f.attrs["error"]


def test_a_time_series_the_disk_cannot_hold_is_refused_before_the_run(tmp_path, monkeypatch, capsys):
    """A run whose timeline records more than the disk's free space (an hour of the blade-loss system on the
    monolithic schedule: ~36 GB) started and failed when the disk filled, hours in; it is refused at its start,
    one line, exit 2, no folder. Here the disk has 6 MiB free and the toy records rows of 5 values every
    1 ms: 200 s (7.63 MiB) do not fit, 20 s (0.76 MiB) do."""
    import os as _os

    from rotorcosim.master.cli import main
    from rotorcosim.master.observer import recorder

    real = _os.statvfs

    class SixMiB:
        def __init__(self, st):
            self.f_frsize = st.f_frsize
            self.f_bavail = 6 * 2 ** 20 // st.f_frsize

    monkeypatch.setattr(recorder.os, "statvfs", lambda path: SixMiB(real(path)))
    out = tmp_path / "o"
    rc = main(["run", "toy_thermomechanical", "--schedule", "monolithic", "--duration", "200", "--quiet",
               "--no-figures", "--out", str(out)])
    err = [x for x in capsys.readouterr().err.splitlines() if x.strip()]
    assert rc == 2 and err == [f"rotorcosim run: error: the time series would take about 7.63 MiB (200,001 rows of 5 "
                               f"values), more than the 6 MiB free on the disk holding {out}: record fewer signals "
                               "(--record), a longer [outputs] record_step or a shorter --duration"], err
    assert not out.exists()
    assert main(["run", "toy_thermomechanical", "--schedule", "monolithic", "--duration", "20", "--quiet",
                 "--no-figures", "--out", str(out)]) == 0


def test_a_run_that_failed_before_its_first_step_does_not_block_its_folder(tmp_path):
    """A bad parameter found when the components are set up leaves no folder (nothing was computed); the
    corrected run takes the same --out, while a folder with results is still refused."""
    out = tmp_path / "o"
    sc = toy()
    sc.components["node"].parameters["C"] = -10.0
    with pytest.raises(Exception, match="C"):
        execute(sc, out, duration=0.01, figures=False)
    assert not out.exists()
    execute(toy(), out, duration=0.01, figures=False)
    assert summary(out)["status"] == "complete"
    with pytest.raises(OutputFolderError, match="not empty"):
        execute(toy(), out, duration=0.01, figures=False)


def test_resume_into_a_missing_folder_creates_nothing(tmp_path):
    with pytest.raises(OutputFolderError, match="does not exist"):
        execute(toy(), tmp_path / "nope", duration=0.01, figures=False, resume=True)
    assert not (tmp_path / "nope").exists()


def _h5_contents(path):
    """Every attribute and dataset of an HDF5 file, as plain Python values."""
    out = {}

    def visit(name, obj):
        out[name] = ({k: np.asarray(v).tolist() for k, v in obj.attrs.items()},
                     obj[...].tolist() if isinstance(obj, h5py.Dataset) else None)

    with h5py.File(path) as f:
        out["/"] = ({k: np.asarray(v).tolist() for k, v in f.attrs.items()}, None)
        f.visititems(visit)
    return out


def test_a_second_recording_of_the_same_layout_is_the_same_file(tmp_path):
    """The recorder makes the empty HDF5 file once per process and layout and copies it for the next runs
    (recorder_hdf5.TEMPLATES): the second run's file holds the same attributes, datasets and rows as the first's,
    and a run of another sampling interval gets its own attributes (no template of another layout)."""
    from rotorcosim.master.observer import recorder_hdf5

    recorder_hdf5.TEMPLATES.clear()
    execute(toy(), tmp_path / "a", duration=0.02, figures=False)
    assert len(recorder_hdf5.TEMPLATES) == 1
    execute(toy(), tmp_path / "b", duration=0.02, figures=False)
    assert len(recorder_hdf5.TEMPLATES) == 1
    a, b = _h5_contents(tmp_path / "a" / "timeseries.h5"), _h5_contents(tmp_path / "b" / "timeseries.h5")
    assert a == b and len(a) > 3 and a["time"][1]
    other = toy()
    other.outputs["record_step"] = 2 * float(other.outputs.get("record_step", 1e-4))
    execute(other, tmp_path / "c", duration=0.02, figures=False)
    c = _h5_contents(tmp_path / "c" / "timeseries.h5")
    assert len(recorder_hdf5.TEMPLATES) == 2
    assert c["/"][0]["sampling_interval_s"] == 2 * a["/"][0]["sampling_interval_s"]
