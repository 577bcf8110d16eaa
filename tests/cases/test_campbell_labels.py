"""The Campbell diagram's critical-speed labels: speeds nearer than a share of the speed axis share one label, so
that no text is printed over another (an installed engine's 4 355 and 4 410 rev/min were)."""
from __future__ import annotations

from rotorcosim.cases.blade_loss.critical_speeds import LABEL_MERGE, speed_labels


def test_near_speeds_share_one_label_far_ones_keep_their_own():
    assert speed_labels([4355.2, 4410.0], 30000.0) == [(4355.2, "4 355 / 4 410")]
    # the paper's engine: 8 500 and 10 200 rev/min on a 30 000 rev/min axis, apart
    assert speed_labels([8500.0, 10200.0], 30000.0) == [(8500.0, "8 500"), (10200.0, "10 200")]
    edge = LABEL_MERGE * 30000.0
    assert len(speed_labels([1000.0, 1000.0 + 0.99 * edge], 30000.0)) == 1
    assert len(speed_labels([1000.0, 1000.0 + 1.01 * edge], 30000.0)) == 2
    assert speed_labels([], 30000.0) == []
