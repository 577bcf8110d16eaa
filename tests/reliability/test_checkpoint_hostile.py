"""A checkpoint.pkl is read without running what it names: unpickling calls whatever the file says, so a hostile
(or corrupted) checkpoint must be refused with a CheckpointError before anything in it is called."""
import os
import pickle

import pytest

from rotorcosim import scenarios
from rotorcosim.master.run import checkpoint
from rotorcosim.master.cli.run import execute
from rotorcosim.master.scenario.build import load_scenario

DURATION = 1.0


def toy():
    return load_scenario(scenarios.path("toy_thermomechanical"))


@pytest.fixture
def interrupted(tmp_path, sigint_at):
    """A toy run interrupted mid-interval: its folder and the real checkpoint's plain fields (format, key)."""
    out = tmp_path / "run"
    sigint_at(0.15)
    with pytest.raises(checkpoint.RunInterrupted):
        execute(toy(), out, duration=DURATION, figures=False)
    fields = checkpoint._peek((out / "checkpoint.pkl").read_bytes())
    return out, fields


def _marker(tmp_path):
    return tmp_path / "PWNED"


class _Call:
    """Pickles as a call of ``func(*args)`` (what a hostile file writes)."""

    def __init__(self, func, *args):
        self.func, self.args = func, args

    def __reduce__(self):
        return self.func, self.args


def _str(text: str) -> bytes:
    raw = text.encode()
    return b"\x8c" + bytes([len(raw)]) + raw  # SHORT_BINUNICODE


def _global(module: str, name: str) -> bytes:
    """Protocol-4 opcodes pushing the global ``module name`` (dotted names allowed by the format)."""
    return _str(module) + _str(name) + b"\x93"  # STACK_GLOBAL


def _fields_then(fields, payload: bytes) -> bytes:
    """A pickle of the real checkpoint's plain fields with ``payload`` (opcodes leaving one value) as "x"."""
    head = pickle.dumps({k: fields[k] for k in ("format", "key", "interval", "k", "t_start", "t")}, protocol=4)
    assert head.endswith(b"u."), head[-4:]  # ... SETITEMS STOP: add one more item before STOP
    return head[:-1] + _str("x") + payload + b"s."


@pytest.mark.parametrize("how", ["call", "dotted", "module-attribute", "new", "truncated"])
def test_hostile_checkpoint_is_refused_without_running_it(tmp_path, interrupted, how):
    out, fields = interrupted
    marker = _marker(tmp_path)
    cmd = f"touch {marker}"
    if how == "call":  # os.system(cmd) through REDUCE, with the right format and key
        raw = pickle.dumps({**{k: fields[k] for k in ("format", "key", "interval", "k", "t_start", "t")},
                            "x": _Call(os.system, cmd)}, protocol=4)
    elif how == "dotted":  # protocol 4 resolves dotted names: os.system reached through one of our modules
        raw = _fields_then(fields, _global("rotorcosim.master.run.checkpoint", "os.system") + _str(cmd) + b"\x85R")
    elif how == "module-attribute":  # a module (not a class) of ours, then getattr on it
        raw = _fields_then(fields, _global("builtins", "getattr") + _global("rotorcosim.master.run.checkpoint", "os")
                           + _str("system") + b"\x86R" + _str(cmd) + b"\x85R")
    elif how == "new":  # __new__ of a type outside the allowed ones
        raw = _fields_then(fields, _global("subprocess", "Popen") + b")\x81")
    else:
        raw = (out / "checkpoint.pkl").read_bytes()[:-200]
    (out / "checkpoint.pkl").write_bytes(raw)
    with pytest.raises(checkpoint.CheckpointError) as err:
        execute(toy(), out, duration=DURATION, figures=False, resume=True)
    msg = str(err.value)
    assert "\n" not in msg and "--resume" in msg
    assert ("not a readable checkpoint" in msg or "is not readable" in msg) if how == "truncated" \
        else "may not" in msg, msg
    assert not marker.exists()


def test_real_checkpoint_reads_with_the_guard(tmp_path, interrupted):
    """The guard lets a genuine checkpoint through (the resume tests check the bits; this, that it completes)."""
    out, _ = interrupted
    summary = execute(toy(), out, duration=DURATION, figures=False, resume=True)
    assert summary["status"] == "complete" and summary["resumed_from_t_s"] is not None


@pytest.mark.parametrize("damage", ["garbage", "truncated", "dataset-removed"])
def test_damaged_time_series_refuses_resume_and_leaves_the_folder(interrupted, damage):
    """A damaged timeseries.h5 beside a good checkpoint: resume refused in one line naming the file, and the
    folder left as it was (was: the file renamed to timeseries.h5.part; a removed dataset was a bare KeyError)."""
    import h5py

    out, _ = interrupted
    h5 = out / "timeseries.h5"
    if damage == "garbage":
        h5.write_bytes(b"garbage")
    elif damage == "truncated":
        h5.write_bytes(h5.read_bytes()[: h5.stat().st_size // 2])
    else:
        with h5py.File(h5, "r+") as f:
            del f["osc.x"]
    before = sorted(p.name for p in out.iterdir())
    with pytest.raises(ValueError) as err:
        execute(toy(), out, duration=DURATION, figures=False, resume=True)
    assert str(h5) in str(err.value) and "resume impossible" in str(err.value) and "\n" not in str(err.value)
    assert sorted(p.name for p in out.iterdir()) == before
