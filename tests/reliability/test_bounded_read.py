"""Every file and archive entry the program reads goes through one bounded reader (components/bounded_read.py):
an input beyond a cap is refused in one line naming the limit, exit status 2, no folder left, at a small and
measured cost. The huge inputs are sparse files (holes of zeros), so building them costs nothing."""
from __future__ import annotations

import os
import resource
import subprocess
import sys
import time
from pathlib import Path

import pytest

from rotorcosim.components.bounded_read import (MAX_CHECKPOINT_BYTES, MAX_ENTRY_BYTES, MAX_TABLE_BYTES,
                                                MAX_TEXT_BYTES, MiB, TooLarge, read_entry)
from tests.helpers.huge_zip import sparse_zip

ROOT = Path(__file__).resolve().parents[2]
#: a refusal's whole process (Python, numpy, the scenario) stays below this; the unbounded estimate took 4.2 GB
PEAK_MB = 200.0
#: wall time of a refusal's whole process on a loaded 2-core machine (~3 s measured; the unbounded one 16-63 s)
WALL_S = 15.0


def _measured(argv: list[str], cwd: Path) -> tuple[subprocess.CompletedProcess, float, float]:
    """Run ``argv`` in a wrapper process of its own, so that the children's peak RSS is this command's alone:
    (result, peak MB, wall s)."""
    wrapper = ("import resource, subprocess, sys, time, json\n"
               "t = time.perf_counter(); r = subprocess.run(sys.argv[1:], capture_output=True, text=True)\n"
               "print(json.dumps([r.returncode, r.stdout, r.stderr, time.perf_counter() - t,\n"
               "                  resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024]))")
    env = {**os.environ, "PYTHONPATH": str(ROOT.parent)}
    w = subprocess.run([sys.executable, "-c", wrapper, *argv], capture_output=True, text=True, cwd=cwd, env=env,
                       timeout=600)
    import json

    code, out, err, wall, peak = json.loads(w.stdout.strip().splitlines()[-1])
    return subprocess.CompletedProcess(argv, code, out, err), peak, wall


def _program(*args) -> list[str]:
    return [sys.executable, "-c", f"import sys; sys.path.insert(0, {str(ROOT)!r}); "
            "from rotorcosim.master.cli import main; sys.exit(main())", *args]


def _one_error_line(r) -> str:
    lines = [x for x in r.stderr.splitlines() if x.strip()]
    assert len(lines) == 1 and "Traceback" not in r.stderr, r.stderr
    return lines[0]


@pytest.mark.parametrize("size, limit", [(2 * 1024 ** 3, "512 MiB"), (MAX_ENTRY_BYTES + 1, "64 MiB")])
def test_fmu_with_a_huge_model_description_is_refused_cheaply(tmp_path, size, limit):
    """2 GiB: beyond the archive's total cap; 64 MiB + 1: below it, beyond the cap of an entry read into memory.
    Either way the wall-time estimate, which reads the model description first, refuses it."""
    fmu = sparse_zip(tmp_path / "big.fmu", {"resources/x.txt": b"x"}, "modelDescription.xml", size)
    assert fmu.stat().st_blocks * 512 < MiB   # the test's own cost: a sparse file
    r, peak, wall = _measured(_program("run", "toy_thermomechanical", "--swap", f"node={fmu}", "--duration", "0.01",
                                       "--out", str(tmp_path / "out")), tmp_path)
    line = _one_error_line(r)
    assert r.returncode == 2, r.stderr
    assert str(fmu) in line and limit in line and "modelDescription.xml" in line, line
    assert not (tmp_path / "out").exists()
    assert peak < PEAK_MB, f"peak {peak:.0f} MB"
    assert wall < WALL_S, f"{wall:.1f} s"


def test_entry_reader_refuses_one_byte_beyond_its_cap(tmp_path):
    import zipfile

    p = tmp_path / "a.zip"
    with zipfile.ZipFile(p, "w", zipfile.ZIP_DEFLATED) as z:
        z.writestr("e.xml", b"a" * 5000)
    with zipfile.ZipFile(p) as z:
        with pytest.raises(TooLarge, match=r"entry 'e.xml': 5000 bytes, above the limit of 4999 bytes"):
            read_entry(z, "e.xml", str(p), limit=4999)
        assert read_entry(z, "e.xml", str(p), limit=5000) == b"a" * 5000


def _sparse(path: Path, size: int, head: bytes = b"") -> Path:
    with open(path, "wb") as f:
        f.write(head)
        f.truncate(size)
    return path


@pytest.mark.parametrize("command", ["run", "uq", "calibrate"])
def test_huge_scenario_or_spec_is_refused_naming_the_limit(tmp_path, command):
    big = _sparse(tmp_path / "big.toml", MAX_TEXT_BYTES + 1, b"# a comment\n")
    args = [str(big), "--out", str(tmp_path / "out")]
    r, peak, wall = _measured(_program(command, *args), tmp_path)
    line = _one_error_line(r)
    assert r.returncode == 2
    assert str(big) in line and "16 MiB" in line, line
    assert not (tmp_path / "out").exists()
    assert peak < PEAK_MB, f"peak {peak:.0f} MB"


def test_huge_inputs_of_every_reader_are_refused(tmp_path):
    """Each reader of a user's file, called as the program calls it, refuses a file one byte beyond its cap."""
    from rotorcosim.components.rotor.model import load_data
    from rotorcosim.interop.ross_toml import read as read_ross
    from rotorcosim.master.run.checkpoint import CheckpointError, load as load_checkpoint
    from rotorcosim.master.study.store import RowStore
    from rotorcosim.master.study.targets import read_targets

    text = _sparse(tmp_path / "t.toml", MAX_TEXT_BYTES + 1)
    with pytest.raises(TooLarge, match="rotor model file .* above the limit of 16 MiB"):
        load_data(text)
    with pytest.raises(TooLarge, match="ROSS rotor file .* above the limit of 16 MiB"):
        read_ross(text)
    with pytest.raises(TooLarge, match="targets file .* above the limit of 16 MiB"):
        read_targets(_sparse(tmp_path / "t.csv", MAX_TEXT_BYTES + 1), {})
    with pytest.raises(TooLarge, match="study table .* above the limit of 64 MiB"):
        RowStore(_sparse(tmp_path / "s.csv", MAX_TABLE_BYTES + 1), ["a"]).read()
    with pytest.raises(CheckpointError, match="above the limit of 256 MiB"):
        load_checkpoint(_sparse(tmp_path / "c.pkl", MAX_CHECKPOINT_BYTES + 1), "key")


def test_a_device_that_never_ends_is_read_no_further_than_the_cap():
    from rotorcosim.components.bounded_read import read_bytes

    t = time.perf_counter()
    with pytest.raises(TooLarge, match="more than 1 MiB"):
        read_bytes("/dev/zero", "scenario file", limit=MiB)
    assert time.perf_counter() - t < 5.0
    assert resource.getrusage(resource.RUSAGE_SELF).ru_maxrss > 0


def test_count_caps_of_a_scenario_are_named(tmp_path, capsys):
    """An ``extends`` chain of 70 files and a template listed for 1001 ids: each refused naming its limit, before
    the files are read on or the components built."""
    from rotorcosim.components.bounded_read import MAX_EXTENDS, MAX_TEMPLATE_IDS
    from rotorcosim.master.cli import main

    (tmp_path / "s0.toml").write_text((ROOT / "scenarios" / "toy_thermomechanical.toml").read_text())
    for i in range(1, MAX_EXTENDS + 6):
        (tmp_path / f"s{i}.toml").write_text(f'[scenario]\nname = "s{i}"\nextends = "s{i - 1}.toml"\n')
    ids = ", ".join(f'"{i}"' for i in range(MAX_TEMPLATE_IDS + 1))
    (tmp_path / "many.toml").write_text(f'[scenario]\nname = "many"\nextends = "{ROOT / "scenarios" / "blade_loss.toml"}"'
                                        f'\n[templates]\nbearing = [{ids}]\n')
    for name, words in ((f"s{MAX_EXTENDS + 5}.toml", f"above the limit of {MAX_EXTENDS} files a scenario may extend"),
                        ("many.toml", f"lists {MAX_TEMPLATE_IDS + 1} ids, above the limit of {MAX_TEMPLATE_IDS} ids")):
        rc = main(["run", str(tmp_path / name), "--duration", "0.01", "--out", str(tmp_path / "out")])
        err = capsys.readouterr().err
        assert rc == 2 and words in _one_error_line(subprocess.CompletedProcess([], rc, "", err)), err
        assert not (tmp_path / "out").exists()
    assert main(["run", str(tmp_path / f"s{MAX_EXTENDS - 1}.toml"), "--duration", "0.01", "--no-figures", "--quiet",
                 "--out", str(tmp_path / "ok")]) == 0   # a chain within the limit runs


def test_a_time_series_declaring_a_huge_dataset_is_refused_before_the_read(tmp_path):
    """An HDF5 file of 2 kB may declare a dataset of 18 GiB (chunked, nothing written): reading it back whole
    would allocate all of it. The reader of a run's series refuses it by its declared size."""
    import h5py

    from rotorcosim.components.bounded_read import MAX_DATASET_BYTES
    from rotorcosim.master.observer.series import SeriesFile

    p = tmp_path / "timeseries.h5"
    with h5py.File(p, "w") as f:
        f.create_dataset("time", data=[0.0, 1.0])
        f.create_dataset("rotor.X", shape=(2 ** 28, 9), dtype="f8", chunks=(1024, 9))
    assert p.stat().st_size < 4096
    s = SeriesFile(p)
    assert list(s["time"]) == [0.0, 1.0]
    with pytest.raises(TooLarge, match=r"dataset 'rotor.X': 18432 MiB, above the limit of 1024 MiB"):
        s["rotor.X"]
    assert MAX_DATASET_BYTES == 1024 * MiB
