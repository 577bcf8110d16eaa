"""``python -m rotorcosim.master.run.figure_worker [MODULE ...]``: draws figures for a run in another process
(figure_pool.py).

At once, while the run goes: imports matplotlib, h5py and the figure modules named on the command line, draws a
small figure into memory (a process's first figure loads the font and the PNG encoder) and says so on stdout
(``{"ready": true}``). Then reads one request from stdin, a JSON line ``{"module", "jobs", "series", "out",
"context"}``, draws each job with ``module.draw(job, SeriesFile(series), out, Context(**context))`` and prints
``{"names": {job: [file, ...]}}``.
End of input without a request: exits 0 having drawn nothing.
"""
from __future__ import annotations

import gc
import importlib
import json
import sys
from pathlib import Path


def main() -> int:
    """The worker's life (see the module's docstring); returns the exit status."""
    import matplotlib

    matplotlib.use("Agg")
    import h5py  # noqa: F401  (the series file is read with it)
    import matplotlib.pyplot  # noqa: F401  (imported ahead: the figures draw with it)

    from rotorcosim.master.observer.series import SeriesFile

    for name in sys.argv[1:]:
        importlib.import_module(name)
    _warm_up()
    print(json.dumps({"ready": True}), flush=True)  # the pool starts its next worker now (figure_pool.py)
    line = sys.stdin.readline()
    if not line.strip():
        return 0
    req = json.loads(line)
    module = importlib.import_module(req["module"])
    ctx = module.Context(**req["context"])
    series = SeriesFile(req["series"])
    names = {job: module.draw(job, series, Path(req["out"]), ctx) for job in req["jobs"]}
    print(json.dumps({"names": names}))
    # the run waits for this process to end: the interpreter's final collections over matplotlib's objects took
    # 0.5-0.6 s at load ~4, 0.05 s with every object frozen (the figures' files are closed)
    gc.freeze()
    return 0


def _warm_up() -> None:
    """A throwaway figure with a line, tick labels, a legend and titles, saved as PNG into memory: the font files,
    their glyph tables and the PNG encoder load here, not in the first figure of the request (measured: ~0.15 s
    of CPU less for the first figure). Nothing of it is kept that a figure's pixels depend on."""
    import io

    import matplotlib.pyplot as plt

    fig, ax = plt.subplots()
    ax.plot([0.0, 1.0], [0.0, 1.0], label="x")
    ax.set_xlabel("time [s]")
    ax.set_title("t", fontsize=10)
    ax.legend(fontsize=8)
    fig.suptitle("T")
    fig.savefig(io.BytesIO(), format="png")
    plt.close(fig)


if __name__ == "__main__":
    sys.exit(main())
