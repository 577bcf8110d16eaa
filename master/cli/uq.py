"""``rotorcosim uq SPEC.toml --out DIR [--scheduler ADDRESS] [--workers N] [--serial] [--quiet]``.

A thin layer over :func:`rotorcosim.uq` (``master/study/uncertainty.py``): samples the SPEC's uncertain
parameters, runs the samples on Dask and writes ``DIR/samples.csv``, ``DIR/uq.json``, ``DIR/uq_histograms.png``
and ``DIR/uq_tornado.png``. Run again with the same SPEC and ``--out`` after an interruption, it resumes without
rerunning a stored sample.
"""
from __future__ import annotations

import sys

from rotorcosim.master.cli.calibrate import add_study_options


def add_arguments(p):
    """The options of ``rotorcosim uq`` on the parser ``p``."""
    add_study_options(p, "UQ")


def run(args) -> int:
    """Run the command ``args`` (parsed); returns the exit status (1 when a sample failed)."""
    from rotorcosim.master.study.statistics import RBD_FAST_MIN_SAMPLES
    from rotorcosim.master.study.uncertainty import uq

    rep = uq(args.spec, args.out, scheduler=args.scheduler, workers=args.workers, serial=args.serial,
             quiet=args.quiet, force=args.force, resume=args.resume)
    print(f"uq: {rep['samples']} samples ({rep['samples_this_session']} run this time) in "
          f"{rep['wall_time_s']:.4g} s; {args.out}/uq.json, samples.csv, uq_histograms.png, uq_tornado.png")
    for name, r in rep["results"].items():
        if "mean" not in r:
            print(f"  {name}: no successful sample")
            continue
        lo, hi = r["mean_ci"]
        line = f"  {name}: mean {r['mean']:.5g} (95 % {lo:.5g}..{hi:.5g}), std {r['std']:.3g}, p5 {r['p5']:.5g}, " \
               f"p95 {r['p95']:.5g}"
        idx = (r.get("sobol") or {}).get("indices")
        if idx:
            key = "ST" if "ST" in next(iter(idx.values())) else "S1"
            top = max(idx, key=lambda n: idx[n][key])
            line += f"; largest {key}: {top} {idx[top][key]:.2f}"
        elif (r.get("sobol") or {}).get("note"):
            line += f"; no sensitivity indices (fewer than {RBD_FAST_MIN_SAMPLES} successful samples)"
        print(line)
    failed = rep["failed"]
    for s in failed["samples"]:
        print(f"  sample {s['sample']} failed: {s['error']}", file=sys.stderr)
    if failed["count"]:
        print(f"{failed['count']} of {rep['samples']} samples failed (named in uq.json 'failed')", file=sys.stderr)
    return 1 if failed["count"] else 0
