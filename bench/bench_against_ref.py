"""The main job's speed against another version of the code, as a ratio.

    python bench/bench_against_ref.py REF [--rounds 5] [--scenario blade_loss_2850] [--duration S]

Checks out the git revision REF into a temporary worktree and runs ``rotorcosim run SCENARIO --no-figures``
from it and from this checkout in alternation (an untimed warm-up of each first: kernels compiled, caches
filled), ``--rounds`` times each. Two versions of one package cannot share an interpreter, so each run is a
child process of this one; alternating them gives both the same share of the machine's drift. Prints, per
version, the simulation's own wall time (``wall_time_s`` of summary.json) and the whole command's, and the
ratio this checkout / REF of their medians (below 1: this checkout is faster). It also says whether the two
versions' results are bit-identical (bench/same_results.py).
"""
from __future__ import annotations

import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(Path(__file__).resolve().parent))
from same_results import differences  # noqa: E402  (the bench folder is not a package)


def run_once(checkout: Path, out: Path, scenario: str, duration: float | None) -> tuple[float, float]:
    if out.exists():
        shutil.rmtree(out)
    cmd = [sys.executable, "-m", "rotorcosim.master.cli", "run", scenario, "--no-figures", "--out", str(out)]
    if duration is not None:
        cmd += ["--duration", str(duration)]
    t0 = time.perf_counter()
    subprocess.run(cmd, cwd=checkout, check=True, capture_output=True)
    whole = time.perf_counter() - t0
    return json.loads((out / "summary.json").read_text())["wall_time_s"], whole


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("ref", help="git revision to compare against (e.g. main~3, a commit)")
    p.add_argument("--rounds", type=int, default=5)
    p.add_argument("--scenario", default="blade_loss_2850")
    p.add_argument("--duration", type=float, default=None)
    a = p.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        ref = tmp / "ref"
        subprocess.run(["git", "worktree", "add", "--detach", str(ref), a.ref], cwd=HERE, check=True,
                       capture_output=True)
        try:
            versions = {"this checkout": HERE, a.ref: ref}
            for name, where in versions.items():  # warm-up
                run_once(where, tmp / f"warm_{len(name)}", a.scenario, a.duration)
            times = {name: [] for name in versions}
            for r in range(a.rounds):
                for name, where in (versions.items() if r % 2 == 0 else reversed(versions.items())):
                    times[name].append(run_once(where, tmp / name.replace(" ", "_").replace("/", "_"),
                                                a.scenario, a.duration))
                print(f"round {r + 1}/{a.rounds}: " + ", ".join(f"{n} {t[-1][0]:.3f} s" for n, t in times.items())
                      + f" (load {os.getloadavg()[0]:.2f})", flush=True)
            med = {n: (statistics.median(x[0] for x in t), statistics.median(x[1] for x in t))
                   for n, t in times.items()}
            for n, (sim, whole) in med.items():
                print(f"{n}: simulation {sim:.3f} s, whole command {whole:.3f} s (medians of {a.rounds})")
            new, old = med["this checkout"], med[a.ref]
            print(f"ratio this checkout / {a.ref}: simulation {new[0] / old[0]:.3f}, whole command "
                  f"{new[1] / old[1]:.3f}")
            diffs = differences(tmp / a.ref.replace(" ", "_").replace("/", "_"), tmp / "this_checkout")
            print("results: bit-identical" if not diffs else f"results: {len(diffs)} difference(s): {diffs[:3]}")
        finally:
            subprocess.run(["git", "worktree", "remove", "--force", str(ref)], cwd=HERE, capture_output=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
