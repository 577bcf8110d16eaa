"""Cost of the FMI boundary: a component step behind its exported FMU against the same component native.

    python bench/bench_fmu.py [--steps N] [--only NAME ...] [--blade-loss]

For every registered component whose implementation imports (the engine's, as they land, and the test
components), in this one process: export it (fmus/export.py), load the FMU back (fmus/importer.py), set both up
the same way, and time ``set_inputs`` + ``do_step`` (what the master does per communication step) over N steps.
Prints microseconds per step native and through the FMU, their ratio, and the added cost per step; then the
whole toy thermo-mechanical scenario run natively and with every component swapped for its FMU; then the largest
difference of the exported toy SSP run in Ecos against our master (Jacobi and Gauss-Seidel, same fixed step);
with ``--blade-loss``, the same two comparisons on the paper's whole system over 200 TM steps; with ``--setup``,
the set-up time of the nine blade-loss FMUs (SSP read, FMUs extracted, loaded, instantiated, initialised) in a
fresh process with an empty cache and again in another fresh process with the cache the first one left
(fmus/extraction_cache.py).
"""
from __future__ import annotations

import checkout  # noqa: F401  (this checkout's rotorcosim, not an installed one: bench/checkout.py)
import argparse
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from rotorcosim.components import registry
from rotorcosim.fmus.export import export_component
from rotorcosim.master.scenario.export import export_scenario
from rotorcosim.fmus.importer import load_fmu_component
from rotorcosim.master.core.threads import one_thread

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))  # the tests' builders: tests.helpers.fmus

#: inputs held at typical non-zero values (others at their declared start values)
TYPICAL = {"damper.fast": {"X_journal": [1e-4, 0.0], "V_journal": [0.0, 0.05]},
           "damper.fe": {"X_journal": [1e-4, 0.0], "V_journal": [0.0, 0.05]},
           "testing.mass": {"F": [1.0]}, "testing.thermal_node": {"P": [100.0]}}
#: the paper's bearing #0 records (a component takes no record unless asked: its engine file gives them); the FE
#: damper solves the Reynolds equation at every call: a coarser mesh keeps the bench short
PARAMS = {**{name: {"bearing": 0} for name in ("bearing.hertz", "bearing.hertz_spinning", "rubring.contact",
                                                "rubring.contact_spinning", "thermal.network",
                                                "thermal.network_spinning")},
          "damper.fast": {"damper": 0}, "damper.fe": {"damper": 0, "n_theta": 32, "n_z": 8}}


def time_steps(comp, inputs: dict, h: float, n: int) -> float:
    """Seconds per (set_inputs + do_step), after 20 warm-up steps (JIT compilation, caches)."""
    t = 0.0
    for _ in range(20):
        comp.set_inputs(inputs)
        comp.do_step(t, h)
        t += h
    t0 = time.perf_counter()
    for _ in range(n):
        comp.set_inputs(inputs)
        comp.do_step(t, h)
        t += h
    return (time.perf_counter() - t0) / n


def component_costs(names, steps: int, folder: Path):
    rows = []
    for name in names:
        try:
            registry.lookup(name)
        except ImportError as exc:
            print(f"  {name:28s} skipped: implementation not importable yet ({exc})")
            continue
        params = PARAMS.get(name, {})
        try:
            native = registry.create(name, name, params)
            path = export_component(name, folder / f"{name.replace('.', '_')}.fmu", parameters=params)
        except (ValueError, OSError) as exc:   # a component that needs an engine of its kind (an airframe)
            print(f"  {name:28s} skipped: {str(exc).splitlines()[0]}")
            continue
        inputs = {v.name: v.start_array() for v in native.variables if v.causality == "input"}
        inputs.update({k: np.asarray(v, dtype=float) for k, v in TYPICAL.get(name, {}).items()})
        fmu = load_fmu_component(path, name)
        h = native.preferred_step
        n = steps if "fe" not in name else max(50, steps // 50)
        try:
            for c in (native, fmu):
                c.set_inputs(inputs)
                c.setup(0.0)
        except (ValueError, RuntimeError) as exc:   # a component that needs its system (a spool, a rotor file)
            print(f"  {name:28s} skipped: {str(exc).splitlines()[0]}")
            fmu.terminate()
            continue
        t_nat = time_steps(native, inputs, h, n)
        t_fmu = time_steps(fmu, inputs, h, n)
        same = all(np.array_equal(native.y[k], fmu.y[k]) for k in native.y)
        fmu.terminate()
        rows.append((name, t_nat, t_fmu, same))
        print(f"  {name:28s} native {t_nat * 1e6:9.2f} us   FMU {t_fmu * 1e6:9.2f} us   ratio {t_fmu / t_nat:6.2f}"
              f"   added {(t_fmu - t_nat) * 1e6:7.2f} us/step   same outputs: {same}")
    return rows


def toy_scenario(folder: Path):
    from tests.helpers.fmus import TOY, run_intervals

    from rotorcosim.master.scenario.build import load_scenario

    sc = load_scenario(TOY)
    fmus = export_scenario(sc, folder / "toy")
    swapped = sc.copy()
    for name, path in fmus.items():
        spec = swapped.components[name]
        spec.implementation, spec.fmu, spec.parameters = None, str(path), {}
    intervals = [("TM", 0.3, 1e-3), ("TO", 4.7, 0.05)] * 3
    t0 = time.perf_counter()
    run_intervals(sc, intervals)
    t_nat = time.perf_counter() - t0
    t0 = time.perf_counter()
    run_intervals(swapped, intervals)
    t_fmu = time.perf_counter() - t0
    print(f"  toy scenario, 3 x (TM 0.3 s + TO 4.7 s): native {t_nat:.3f} s, all FMUs {t_fmu:.3f} s, "
          f"ratio {t_fmu / t_nat:.2f}")


def ecos_vs_master(folder: Path):
    try:
        from tests.fmus.test_ssp import ecos_run
    except Exception as exc:  # pragma: no cover
        print(f"  Ecos: cannot import the helper ({exc})")
        return
    try:
        import ecospy  # noqa: F401 - only whether it imports
    except (ImportError, OSError) as exc:
        print(f"  Ecos: not available ({exc})")
        return
    from tests.helpers.fmus import TOY, run_intervals

    from rotorcosim.master.scenario.ssp import read_ssp, write_ssp
    from rotorcosim.master.scenario.build import load_scenario

    ssp = write_ssp(load_scenario(TOY), folder / "toy.ssp")
    step, n = 1e-3, 300
    signals = ["osc.x", "osc.v", "osc.P", "node.T"]
    ecos = ecos_run(ssp, step, n, signals)
    for kind in ("jacobi", "gauss-seidel"):
        sc = read_ssp(ssp)
        sc.algorithm = {"kind": kind, "order": ["osc", "node"]}
        ours = run_intervals(sc, [("TM", n * step, step)])
        worst = {s: float(np.max(np.abs(ours.series(s).reshape(n) - ecos[s])) / np.max(np.abs(ours.series(s))))
                 for s in signals}
        print(f"  Ecos vs our master ({kind}, TM 0.3 s at 1 ms), max |diff| / max |ours|: "
              + ", ".join(f"{s} {v:.2e}" for s, v in worst.items()))


def blade_loss(folder: Path, n: int = 200):
    """The paper's whole system: native vs every component an FMU (our master), and the SSP in Ecos."""
    from tests.helpers.fmus import max_rel_diff, run_intervals

    from rotorcosim import scenarios
    from rotorcosim.master.scenario.ssp import read_ssp, write_ssp
    from rotorcosim.master.scenario.build import load_scenario

    sc = load_scenario(scenarios.path("blade_loss"))
    h = float(sc.schedule.get("step", 1e-5))
    t0 = time.perf_counter()
    ssp = write_ssp(sc, folder / "blade_loss.ssp")
    print(f"  export-ssp blade_loss: {time.perf_counter() - t0:.1f} s, {ssp.stat().st_size / 1e6:.1f} MB")
    iv = [("TM", n * h, h)]
    t0 = time.perf_counter()
    native = run_intervals(sc, iv)
    t_nat = time.perf_counter() - t0
    t0 = time.perf_counter()
    fmu = run_intervals(read_ssp(ssp), iv)
    t_fmu = time.perf_counter() - t0
    print(f"  blade_loss TM {n} steps of {h:g} s: native {t_nat:.1f} s, SSP of FMUs in our master {t_fmu:.1f} s "
          f"(both with set-up); max relative difference {max_rel_diff(native, fmu, list(native.rows[0])):.3g}")
    try:
        from tests.fmus.test_ssp import ecos_run
    except (ImportError, OSError) as exc:
        print(f"  Ecos: not available ({exc})")
        return
    signals = [f"{s}{k}{i}" for k in (0, 5) for s, i in (("rotor.X_brg", "[1]"), ("bearing", ".F_rotor[1]"),
                                                          ("damper", ".F_journal[1]"), ("rubring", ".P_rub"),
                                                          ("thermal", ".T_oil"))]
    signals = [s for s in signals if s.partition("[")[0] in native.rows[0]]
    ecos = ecos_run(ssp, h, n, signals)
    # Ecos holds every value over a step; the scenario extrapolates the bearing forces to the step's end
    # (extrapolation = "linear-end"), which SSP 1.0 cannot say: compared as the archive says, then all held
    for label, held in (("as the scenario couples", False), ("every connection held, as Ecos", True)):
        jac = read_ssp(ssp)
        jac.algorithm = {"kind": "jacobi", "order": jac.algorithm.get("order")}
        if held:
            for c in jac.connections:
                c.extrapolation = "hold"
        ours = run_intervals(jac, iv)
        diffs = []
        for s in signals:
            port, _, idx = s.partition("[")
            mine = ours.series(port)[:, int(idx[:-1]) - 1 if idx else 0]
            scale = np.max(np.abs(mine))
            diffs.append(f"{s} {np.max(np.abs(mine - ecos[s])) / scale if scale else 0.0:.2e}")
        print(f"  Ecos vs our master (jacobi, {label}), blade_loss TM {n} steps, max |diff| / max |ours|: "
              + ", ".join(diffs))


_SETUP = """
import sys, time
t0 = time.perf_counter()
from rotorcosim.master.scenario.ssp import read_ssp
from rotorcosim.master.scenario.build import build_simulation
sim = build_simulation(read_ssp(sys.argv[1]), [])
sim.initialise()
print(time.perf_counter() - t0)
"""


def setup_time(folder: Path) -> None:
    """Set-up of the blade-loss SSP's nine FMUs in a fresh process: empty cache, then the cache left behind."""
    from rotorcosim import scenarios
    from rotorcosim.master.scenario.ssp import write_ssp
    from rotorcosim.master.scenario.build import load_scenario

    ssp = write_ssp(load_scenario(scenarios.path("blade_loss")), folder / "blade_loss_setup.ssp")
    env = {**os.environ, "ROTORCOSIM_CACHE": str(folder / "cache")}
    times = []
    for label in ("empty cache", "warm cache"):
        out = subprocess.run([sys.executable, "-c", _SETUP, str(ssp)], env=env, capture_output=True, text=True)
        if out.returncode:
            print(f"  set-up failed: {out.stderr.strip().splitlines()[-1:]}")
            return
        times.append(float(out.stdout.strip().splitlines()[-1]))
        print(f"  nine blade-loss FMUs set up ({label}, fresh process, imports included): {times[-1]:.2f} s")
    print(f"  ratio empty/warm: {times[0] / times[1]:.1f}")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--steps", type=int, default=5000, help="timed steps per component (default 5000)")
    ap.add_argument("--only", nargs="*", default=None, help="component implementation names (default: all)")
    ap.add_argument("--blade-loss", action="store_true",
                    help="also the whole blade-loss system: native vs FMUs, and in Ecos (a few minutes)")
    ap.add_argument("--setup", action="store_true",
                    help="only the set-up time of the nine blade-loss FMUs, empty cache then warm cache")
    args = ap.parse_args(argv)
    if args.setup:
        with tempfile.TemporaryDirectory(prefix="bench_fmu_") as tmp:
            print("FMU set-up:")
            setup_time(Path(tmp))
        return 0
    names = args.only or registry.available()
    with tempfile.TemporaryDirectory(prefix="bench_fmu_") as tmp:
        folder = Path(tmp)
        print("cost of one communication step (set_inputs + do_step), native vs behind the FMU boundary:")
        with one_thread():   # as a run steps them (BLAS's threads sum in another order: other last bits)
            component_costs(names, args.steps, folder)
        print("whole scenario:")
        toy_scenario(folder)
        print("another engine:")
        ecos_vs_master(folder)
        if args.blade_loss:
            print("the blade-loss system:")
            blade_loss(folder)
    return 0


if __name__ == "__main__":
    sys.exit(main())
