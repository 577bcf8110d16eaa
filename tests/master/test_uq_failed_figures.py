"""A UQ whose samples failed says so in its figures instead of drawing empty axes (master/study/figures.py)."""
from __future__ import annotations

from rotorcosim.master.study import figures


def test_the_titles_count_the_failed_samples():
    assert figures._failed_note({"count": 0, "samples": []}, 64) == ""
    note = figures._failed_note({"count": 64, "samples": []}, 64)
    assert "64 of 64 samples failed" in note and "uq.json" in note


def test_figures_of_a_uq_without_a_successful_sample_are_drawn(tmp_path):
    failed = {"count": 2, "samples": [{"sample": 0, "error": "x"}, {"sample": 1, "error": "y"}]}
    figures.histograms(tmp_path / "h.png", ["a", "b"], {"a": [None, None], "b": [None, None]}, {}, failed, 2)
    figures.tornado(tmp_path / "t.png", ["a"], ["p"], {"a": None}, {"a": 0.0}, failed, 2)
    assert (tmp_path / "h.png").stat().st_size > 0 and (tmp_path / "t.png").stat().st_size > 0
