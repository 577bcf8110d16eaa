"""Memory over a run ten times longer: ``python bench/bench_memory.py [SHORT_S] [OUT]``.

A run that writes its time series to a file holds no series in memory, so its peak must not grow with its
length. For ``run``, ``sweep`` (per worker: each case's worker process) and ``compare`` (the process that runs
both runs), each command is run over SHORT_S (default 0.05 s) and ten times that, each in fresh processes, on the
blade-loss scenario, without figures; the peak is each run's ``peak_memory_MB`` (summary.json: the process's
high-water mark at the run's end). Prints the peaks and their ratio long / short for each command;
tests/reliability/test_memory.py holds the ratio below 1.10.

Measured on the shared 2-core VM (loaded by other work), peak MB short / long (ratio):

    0.05 s vs 0.5 s:  run 240.1 / 243.2 (1.013), sweep 281.3 / 280.1 (0.996), compare 263.5 / 269.7 (1.023)
    0.2 s vs 2 s:     run 239.5 / 239.6 (1.000), sweep 278.5 / 280.1 (1.006), compare 263.1 / 265.5 (1.009)

Before the recorder opened its HDF5 file without a chunk cache (recorder_hdf5.py), compare's 2 s monolithic run
peaked at 285.7 MB (ratio 1.074): h5py's 1 MiB cache per dataset filled with the last chunks written, ~10 MB per
simulated second of one thermo-mechanical interval.
"""
from __future__ import annotations

import json
import subprocess
import sys
import tempfile
from pathlib import Path

#: the commands measured and the options that make each run over a given duration
COMMANDS = {
    "run": ["run", "blade_loss_2850", "--no-figures", "--quiet"],
    "sweep": ["sweep", "blade_loss", "--unbalance", "712,1425", "--workers", "2", "--quiet"],
    "compare": ["compare", "--revolutions", "2", "--timing-runs", "1", "--no-figures", "--quiet"],
}


def peak_mb(command: str, duration: float, out: Path) -> float:
    """The largest ``peak_memory_MB`` of the runs ``rotorcosim COMMAND`` makes over ``duration`` [s] into
    ``out`` (run: its one run; sweep: each case, in its worker; compare: both runs, in one process)."""
    argv = [sys.executable, "-m", "rotorcosim.master.cli", *COMMANDS[command], "--duration", f"{duration:g}",
            "--out", str(out)]
    r = subprocess.run(argv, capture_output=True, text=True, timeout=1800)
    if r.returncode != 0:
        raise RuntimeError(f"{' '.join(argv[2:])}: exit status {r.returncode}: {r.stderr[-1000:]}")
    peaks = [json.loads(f.read_text())["peak_memory_MB"] for f in sorted(out.rglob("summary.json"))]
    if not peaks or None in peaks:
        raise RuntimeError(f"{out}: no peak_memory_MB in the runs' summaries")
    return max(peaks)


def measure(short: float, root: Path, commands=tuple(COMMANDS)) -> dict[str, dict[str, float]]:
    """``{command: {"short_MB", "long_MB", "ratio"}}`` for runs over ``short`` and ``10 * short`` seconds."""
    out = {}
    for c in commands:
        a = peak_mb(c, short, root / f"{c}_short")
        b = peak_mb(c, 10 * short, root / f"{c}_long")
        out[c] = {"short_MB": a, "long_MB": b, "ratio": b / a}
    return out


def main(argv: list[str]) -> int:
    short = float(argv[0]) if argv else 0.05
    with tempfile.TemporaryDirectory() as tmp:
        root = Path(argv[1]) if len(argv) > 1 else Path(tmp)
        figures = measure(short, root)
    print(f"peak resident memory, {short:g} s against {10 * short:g} s (blade-loss scenario, no figures):")
    for c, f in figures.items():
        print(f"  {c:8s} {f['short_MB']:8.1f} MB  {f['long_MB']:8.1f} MB  ratio {f['ratio']:.3f}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
