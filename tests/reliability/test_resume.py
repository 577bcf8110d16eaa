"""Interrupted runs end with a readable time series and a summary, and resume bit-identically."""
import json

import h5py
import numpy as np
import pytest

from rotorcosim import scenarios
from rotorcosim.components.contract import Component, Variable
from rotorcosim.components.registry import register
from rotorcosim.master.run import checkpoint
from rotorcosim.master.cli.run import execute
from rotorcosim.master.scenario.build import load_scenario

DURATION = 5.6  # toy timeline: TM 0.3 + TO 4.7 + TM 0.3 + TO 0.3 (cut)


def toy():
    return load_scenario(scenarios.path("toy_thermomechanical"))


def series(folder):
    with h5py.File(folder / "timeseries.h5") as f:
        return {k: f[k][...] for k in f}, dict(f.attrs)


@pytest.fixture(scope="module")
def reference(tmp_path_factory):
    out = tmp_path_factory.mktemp("ref")
    summary = execute(toy(), out, duration=DURATION, figures=False)
    return out, summary


@pytest.mark.parametrize("t_signal", [0.1502, 2.0, 5.25])  # mid-TM, mid-TO, in the second TM interval
def test_interrupt_then_resume_is_bit_identical(tmp_path, reference, sigint_at, t_signal):
    out = tmp_path / "run"
    fired = sigint_at(t_signal)
    with pytest.raises(checkpoint.RunInterrupted):
        execute(toy(), out, duration=DURATION, figures=False)
    assert fired
    s = json.loads((out / "summary.json").read_text())
    assert s["status"] == "interrupted" and s["checkpoint"] == "checkpoint.pkl"
    assert s["t_end_s"] < DURATION
    data, attrs = series(out)  # readable, marked incomplete
    assert attrs["complete"] == False  # noqa: E712 - a numpy bool: `is` would not match
    assert data["time"][-1] <= s["t_end_s"] + 1e-12
    # the same command with resume
    summary = execute(toy(), out, duration=DURATION, figures=False, resume=True)
    assert summary["resumed_from_t_s"] is not None and summary["resumed_from_t_s"] <= s["t_end_s"] + 1e-12
    assert not (out / "checkpoint.pkl").exists()
    _same_as(out, summary, reference)


def test_resume_refuses_other_options(tmp_path, sigint_at):
    out = tmp_path / "run"
    sigint_at(0.2)
    with pytest.raises(checkpoint.RunInterrupted):
        execute(toy(), out, duration=DURATION, figures=False)
    with pytest.raises(checkpoint.CheckpointError, match="another scenario or with other options"):
        execute(toy(), out, duration=DURATION + 1, figures=False, resume=True)


def test_a_checkpoint_of_another_format_is_refused_by_name(tmp_path, sigint_at, monkeypatch):
    """A checkpoint of an earlier layout (format 4: no timeline position) is a CheckpointError, not a crash."""
    out = tmp_path / "run"
    sigint_at(0.2)
    monkeypatch.setattr(checkpoint, "FORMAT", 4)
    with pytest.raises(checkpoint.RunInterrupted):
        execute(toy(), out, duration=DURATION, figures=False)
    monkeypatch.undo()
    with pytest.raises(checkpoint.CheckpointError, match="another version of rotorcosim"):
        execute(toy(), out, duration=DURATION, figures=False, resume=True)


def test_resume_needs_a_checkpoint(tmp_path):
    with pytest.raises(ValueError, match="no checkpoint.pkl"):
        execute(toy(), tmp_path / "empty", duration=1.0, figures=False, resume=True)


def test_periodic_checkpoints_inside_an_interval(tmp_path, monkeypatch):
    """With a zero period, checkpoints are taken inside intervals too (every stride), not only at their ends."""
    out = tmp_path / "run"
    saved = []
    original = checkpoint.Checkpointer.save

    def save(self, sim, k, next_interval=False):
        saved.append((sim.interval_index, k, next_interval))
        original(self, sim, k, next_interval)

    monkeypatch.setattr(checkpoint.Checkpointer, "save", save)
    execute(toy(), out, duration=0.31, figures=False, checkpoint_every=1e-9)
    assert any(k > 0 and not nxt for _, k, nxt in saved)
    assert saved[-1][2]  # the interval end


def test_two_runs_are_bit_identical(tmp_path, reference):
    """Determinism: the same scenario run twice gives the same bits (the resume tests rely on it)."""
    ref_out, ref = reference
    again = execute(toy(), tmp_path / "again", duration=DURATION, figures=False)
    got, _ = series(tmp_path / "again")
    want, _ = series(ref_out)
    assert all(np.array_equal(got[k], want[k]) for k in want)
    assert again["final_outputs"] == ref["final_outputs"]


def test_command_line_interrupt_and_resume(tmp_path, reference, sigint_at, capsys):
    """`rotorcosim run ...` interrupted (exit 130, one line) and `... --resume` (exit 0): the reference's bits."""
    from rotorcosim.master.cli import main

    ref_out, _ = reference
    args = ["run", "toy_thermomechanical", "--out", str(tmp_path / "o"), "--duration", str(DURATION), "--quiet",
            "--no-figures"]
    sigint_at(2.0)
    assert main(args) == 130
    err = capsys.readouterr().err
    assert "interrupted" in err and "--resume" in err and "Traceback" not in err
    assert main(args + ["--resume"]) == 0
    got, attrs = series(tmp_path / "o")
    want, _ = series(ref_out)
    assert attrs["complete"] == True and all(np.array_equal(got[k], want[k]) for k in want)  # noqa: E712 - a numpy bool: `is` would not match


@pytest.fixture(scope="module")
def auto_reference(tmp_path_factory):
    out = tmp_path_factory.mktemp("auto_ref")
    summary = execute(toy(), out, "auto", duration=DURATION, figures=False)
    return out, summary


def test_automatic_schedule_writes_its_interval_ends_at_the_checkpoint_pace(tmp_path, monkeypatch):
    """Each interval end of the automatic schedule is taken, but written only when the last write is
    END_GAP_S old (a run of hours has hundreds of them, tens of MB each): a run of a few seconds writes none."""
    writes, taken = [], []
    write, save = checkpoint.Checkpointer._write, checkpoint.Checkpointer.save

    def counted_write(self, data):
        writes.append(len(data))
        write(self, data)

    def counted_save(self, sim, k, next_interval=False, write=True):
        taken.append(write)
        save(self, sim, k, next_interval, write)

    monkeypatch.setattr(checkpoint.Checkpointer, "_write", counted_write)
    monkeypatch.setattr(checkpoint.Checkpointer, "save", counted_save)
    summary = execute(toy(), tmp_path / "run", "auto", duration=DURATION, figures=False)
    assert len(taken) == len(summary["timeline"]) >= 4 and not any(taken)
    assert writes == [] and summary["status"] == "complete"


@pytest.mark.parametrize("t_signal", [2.0, 5.3])  # inside a TO interval, inside a later TM interval
def test_automatic_schedule_resumes_bit_identically(tmp_path, auto_reference, sigint_at, t_signal):
    """The automatic schedule is checkpointed at interval ends (with its own loop state): interrupted inside an
    interval, it resumes from the previous end, makes the same decisions, and gives the same bits."""
    ref_out, ref = auto_reference
    assert len(ref["timeline"]) >= 4  # several TM/TO decisions, so the loop state matters
    out = tmp_path / "run"
    fired = sigint_at(t_signal)
    with pytest.raises(checkpoint.RunInterrupted):
        execute(toy(), out, "auto", duration=DURATION, figures=False)
    assert fired
    s = json.loads((out / "summary.json").read_text())
    assert s["status"] == "interrupted" and s["checkpoint"] == "checkpoint.pkl"
    summary = execute(toy(), out, "auto", duration=DURATION, figures=False, resume=True)
    assert summary["status"] == "complete"
    assert summary["resumed_from_t_s"] < t_signal
    got, _ = series(out)
    want, _ = series(ref_out)
    for k in want:
        assert np.array_equal(got[k], want[k]), k
    assert summary["timeline"] == ref["timeline"]
    assert summary["final_outputs"] == ref["final_outputs"]


# -- a time event in a held interval: the coupled rest after it, and the intervals it shortens ----------------------
class Tick(Component):
    """Schedules one change at ``t_event`` (a time event, as the rotor's blade release): the toy's held interval
    that spans it ends there and the rest of it runs coupled. Stepped at 2 ms (the scenario's step) in 1 ms
    intervals: every coupled interval is whole pairs of base steps, so the rest runs past the held interval's end
    and the next intervals are shortened."""

    variables = (Variable("t_event", "parameter", unit="s", start=1.0, event="the tick"),
                 Variable("n", "output", unit="1"))

    def do_step(self, t, h):
        self.time = t + h
        self.y["n"] = self.y["n"] + 1.0

    def next_event(self, t):
        return self.p["t_event"] if self.p["t_event"] >= t - 1e-9 else None


EVENT_TOML = """
[scenario]
name = "toy_time_event"
extends = "toy_thermomechanical"

[components.tick]
implementation = "testing.resume_tick"
step = 2e-3
parameters = { t_event = 2.0012 }
"""


def toy_event(folder):
    register("testing.resume_tick")(Tick)
    path = folder / "toy_time_event.toml"
    path.write_text(EVENT_TOML)
    return load_scenario(path)


@pytest.fixture(scope="module")
def event_reference(tmp_path_factory):
    folder = tmp_path_factory.mktemp("event_ref")
    summary = execute(toy_event(folder), folder / "out", duration=DURATION, figures=False)
    # TM 0.3, TO cut at the event, its coupled rest past 5.0 s, TM shortened (past 5.3 s), TO shortened
    assert [(iv["phase"], iv["reason"]) for iv in summary["timeline"]] == [
        ("TM", ""), ("TO", "event"), ("TM", "after an event"), ("TM", ""), ("TO", "")]
    rest, tm, to = summary["timeline"][2:]
    assert rest["t_end"] > 5.0 + 1e-6 and tm["t_end"] > 5.3 + 1e-6 and to["t_end"] == pytest.approx(DURATION)
    return folder / "out", summary


def _same_as(out, summary, reference):
    ref_out, ref = reference
    assert summary["status"] == "complete"
    got, attrs = series(out)
    want, _ = series(ref_out)
    assert attrs["complete"] == True  # noqa: E712 - a numpy bool: `is` would not match
    assert set(got) == set(want)
    for k in want:
        assert got[k].shape == want[k].shape, k
        assert np.array_equal(got[k], want[k]), k  # bit-identical
    assert summary["timeline"] == ref["timeline"]
    assert summary["final_outputs"] == ref["final_outputs"]
    assert summary["component_steps"] == ref["component_steps"]
    assert summary.get("events") == ref.get("events")


@pytest.mark.parametrize("t_signal", [3.0, 5.15, 5.45])  # in the coupled rest, in the TM and TO it shortened
def test_interrupted_after_a_time_event_resumes_bit_identically(tmp_path, event_reference, sigint_at, t_signal):
    """Interrupted inside the coupled rest of a held interval an event cut (no checkpoint before it: it was
    refused, 'no checkpoint.pkl'), or inside an interval that rest shortened (resumed at the timeline's duration,
    other steps), the run resumes where it was and gives the uninterrupted run's bits."""
    out = tmp_path / "run"
    fired = sigint_at(t_signal)
    with pytest.raises(checkpoint.RunInterrupted):
        execute(toy_event(tmp_path), out, duration=DURATION, figures=False)
    assert fired
    s = json.loads((out / "summary.json").read_text())
    assert s["status"] == "interrupted" and s["checkpoint"] == "checkpoint.pkl"
    summary = execute(toy_event(tmp_path), out, duration=DURATION, figures=False, resume=True)
    assert summary["resumed_from_t_s"] is not None and summary["resumed_from_t_s"] <= s["t_end_s"] + 1e-12
    _same_as(out, summary, event_reference)


@pytest.mark.parametrize("last", [2, 3])  # the end of the coupled rest (of interval 1), of the TM it shortened
def test_a_checkpoint_at_the_end_of_a_shortened_interval_resumes_bit_identically(tmp_path, event_reference,
                                                                                monkeypatch, sigint_at, last):
    """The checkpoint an interval end writes (the one a hard kill leaves) after the coupled rest or after an
    interval it shortened: the next interval is shortened in the resumed run as in the uninterrupted one."""
    original = checkpoint.Checkpointer.save

    def interval_ends_only(self, sim, k, next_interval=False, write=True):
        if next_interval and sim.interval_index + 1 <= last:
            original(self, sim, k, next_interval, write)

    monkeypatch.setattr(checkpoint.Checkpointer, "save", interval_ends_only)
    out = tmp_path / "run"
    sigint_at(5.45)
    with pytest.raises(checkpoint.RunInterrupted):
        execute(toy_event(tmp_path), out, duration=DURATION, figures=False, checkpoint_every=1e-9)
    monkeypatch.setattr(checkpoint.Checkpointer, "save", original)
    summary = execute(toy_event(tmp_path), out, duration=DURATION, figures=False, resume=True)
    assert summary["resumed_from_t_s"] == pytest.approx(5.0012 if last == 2 else 5.3012, abs=1e-9)
    _same_as(out, summary, event_reference)
