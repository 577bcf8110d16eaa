"""Write targets.csv of the paper calibration from the paper's Table 5 (cases/blade_loss/reference_table5.csv).

The cells of the levels FIT are fitted, those of HOLDOUT are held out (``holdout`` 1). A cell whose printed value
is 0 is left out: a log ratio has no value there (the paper comparison scores those cells itself: the rub-power
zeros are met when ours is below 1 W). Run: ``python docs/examples/paper_study/make_targets.py``.
"""
import csv
from pathlib import Path

from rotorcosim.cases.blade_loss.table5 import paper_table5

FIT = (712.0, 2850.0, 8551.0)
HOLDOUT = (1425.0, 5700.0, 11401.0, 14252.0)


def case_name(level: float) -> str:
    """The SPEC's case of an unbalance level: ``F712``."""
    return f"F{level:g}"


def main(path: Path = Path(__file__).with_name("targets.csv")) -> None:
    rows = []
    for (key, k), by_level in paper_table5().items():
        for level in (*FIT, *HOLDOUT):
            v = by_level[level]
            if v != 0.0:
                rows.append([case_name(level), f"bearings.{k}.{key}", repr(v), int(level in HOLDOUT)])
    with open(path, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["case", "result", "value", "holdout"])
        w.writerows(rows)
    print(f"{len(rows)} targets ({sum(r[3] == 0 for r in rows)} fitted) written to {path}")


if __name__ == "__main__":
    main()
