"""``rotorcosim calibrate SPEC.toml --out DIR [--scheduler ADDRESS] [--workers N] [--serial] [--quiet]``.

A thin layer over :func:`rotorcosim.calibrate` (``master/study/calibration.py``): fits the SPEC's parameters to
its targets by bounded nonlinear least squares, each point of the search a batch of runs on Dask, and writes
``DIR/calibration.json``, ``DIR/evaluations.csv`` and ``DIR/calibration.png``. Run again with the same SPEC and
``--out`` after an interruption, it resumes without rerunning a stored run.
"""
from __future__ import annotations

import sys


def add_study_options(p, what: str) -> None:
    """The options ``calibrate`` and ``uq`` share (SPEC, ``--out``, where the runs go, ``--quiet``)."""
    p.add_argument("spec", metavar="SPEC.toml", help=f"the {what} SPEC (TOML; see docs/how-to/calibrate-and-uq.md)")
    p.add_argument("--out", required=True, metavar="DIR",
                   help="output folder: new, empty, or holding this SPEC's interrupted study (which then resumes)")
    p.add_argument("--scheduler", default=None, metavar="ADDRESS",
                   help="address of a running Dask scheduler, e.g. tcp://10.0.0.5:8786 (default: a local cluster)")
    p.add_argument("--workers", type=int, default=None, help="local cluster size (default: number of cores)")
    p.add_argument("--serial", action="store_true", help="run in this process, one run after another, without Dask")
    p.add_argument("--quiet", action="store_true", help="no progress lines")
    p.add_argument("--force", action="store_true", help="run a study estimated above 24 h of wall time")
    p.add_argument("--resume", action="store_true",
                   help="continue the study in --out (it must hold this SPEC's study; without --resume such a "
                        "folder is continued too)")


def add_arguments(p):
    """The options of ``rotorcosim calibrate`` on the parser ``p``."""
    add_study_options(p, "calibration")


def run(args) -> int:
    """Run the command ``args`` (parsed); returns the exit status (1 when the search failed)."""
    from rotorcosim.master.study.calibration import calibrate

    rep = calibrate(args.spec, args.out, scheduler=args.scheduler, workers=args.workers, serial=args.serial,
                    quiet=args.quiet, force=args.force, resume=args.resume)
    print(f"calibration {rep['status']} after {rep['evaluations']} runs ({rep['evaluations_this_session']} this "
          f"time) in {rep['wall_time_s']:.4g} s; {args.out}/calibration.json, evaluations.csv, calibration.png")
    for name, p in rep["parameters"].items():
        se = p["std_error"]
        print(f"  {name} = {p['value']:.6g}" + (f" +- {se:.3g}" if se is not None else " (no standard error)")
              + f"  (start {p['start']:.6g}, bounds [{p['lower']:.4g}, {p['upper']:.4g}])")
    for key in ("fit", "holdout"):
        a, b = rep[f"{key}_score_start"], rep[f"{key}_score"]
        if b["targets"]:
            print(f"  {key}: within +-30 % {a['within_30pct']} -> {b['within_30pct']}, within x2 {a['within_x2']} -> "
                  f"{b['within_x2']} of {b['targets']} targets")
    for w in rep["warnings"]:
        print(f"warning: {w}", file=sys.stderr)
    return 0 if rep["status"] in ("converged", "max_evaluations") else 1
