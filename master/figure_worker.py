"""``python -m rotorcosim.master.figure_worker``: draws figures for a run in another process (figure_pool.py).

Imports matplotlib at once (the slow part of a first figure, done while the run goes), then reads one request
from stdin, a JSON line ``{"module", "jobs", "series", "out", "context"}``, draws each job with
``module.draw(job, SeriesFile(series), out, Context(**context))`` and prints ``{"names": {job: [file, ...]}}``.
End of input without a request: exits 0 having drawn nothing.
"""
from __future__ import annotations

import importlib
import json
import sys
from pathlib import Path


def main() -> int:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot  # noqa: F401

    from .series import SeriesFile

    line = sys.stdin.readline()
    if not line.strip():
        return 0
    req = json.loads(line)
    module = importlib.import_module(req["module"])
    ctx = module.Context(**req["context"])
    series = SeriesFile(req["series"])
    names = {job: module.draw(job, series, Path(req["out"]), ctx) for job in req["jobs"]}
    print(json.dumps({"names": names}))
    return 0


if __name__ == "__main__":
    sys.exit(main())
