"""``rotorcosim compare blade_loss_rundown [--duration D] --out DIR``: the staggered scheme against the monolithic
run on a rundown: the check of the scheme in non-stationary operation.

The rundown scenario runs twice over the same ``duration``: staggered (the scenario's own automatic schedule:
coupled intervals through the rundown, thermal-only ones once the response is steady) and monolithic (one
thermo-mechanical interval all the way), each into its own folder (``staggered/``, ``monolithic/``, with its
summary, time series and figures). ``DIR/rundown_compare.json`` holds:

- ``results``: per bearing (``"0"``, ``"5"``) and Table 4 result at the end of the run (the case's
  ``RESULT_KEYS``, cases/blade_loss/results.py) ``{staggered, monolithic, rel_error_pct}``;
- ``crossings``: per critical-speed crossing of the monolithic run (matched by spool and critical speed) its
  ``spool``, ``critical_speed_rpm``, ``t_s`` and ``peak_speed_rpm`` of each run (the speed with its relative
  error) and per bearing each peak (``peak_whirl_mm``, ``peak_contact_load_N``, ``peak_contact_stress_MPa``,
  ``peak_transmitted_force_N``) ``{staggered, monolithic, rel_error_pct}``, and ``peak_found`` of each run; a
  crossing one run has (or finds a peak at) and the other not is listed with ``null`` for the missing values and
  is not within; one where neither run finds a resonance peak has a ``note`` and is not judged;
- ``speeds``: per spool its speed at the end ``end_rpm`` of each run and their relative error (not judged);
- ``wall_time_s``, ``cpu_time_s`` of each run (as ``rotorcosim run`` times a run: the simulation whole, no
  figures), ``speedup`` = monolithic / staggered wall time and ``speedup_cpu`` the same in CPU time (the
  staggered run costs ``1 / speedup_cpu`` of the monolithic one), ``load_average`` around each run;
- ``largest_error_pct`` and ``within_2pct`` (the acceptance bound, :data:`TOLERANCE_PCT`) for ``results``,
  ``crossing_peaks`` (the peak values), ``crossing_speeds`` (the peak speeds) and ``all``; a result whose
  relative error cannot be formed (the monolithic value 0, the staggered one not; a missing crossing) counts as
  not within;
- ``duration_s``, ``duration_rule`` (how the duration was chosen), ``t_fuel_cut_s``, ``staggered_phases``
  (simulated time, intervals and steps of each phase of the staggered run) and its ``hold`` report;
- ``estimated_error``: the staggered run's estimated error of every Table 4 result beside its true error in the
  same terms (temperatures as rises above the initial temperature; cases/blade_loss/error_check.py);
- ``fatigue``: the damage-equivalent load of every counted load element (cases/rundown/fatigue.py: the mounts'
  loads on an airframe, else the dampers' transmitted forces) over the windmilling, from the fuel cut +
  :data:`RUNDOWN_S` to the end, in each run (the staggered run's held intervals counted from the hold's window
  times the revolutions they span, master/observer/held_cycles.py): ``t_from_s``, ``woehler_exponent``,
  ``reference_cycles``, per element ``del_N`` ``{staggered, monolithic, rel_error_pct}``, ``largest_error_pct``
  and ``within_2pct``; None when the run ends before the windmilling or has no time series.

The relative error is ``100 |staggered - monolithic| / |monolithic|`` (temperatures in degrees C, as Table 4 and
``rotorcosim compare``'s Table 6 give them; 0 when both are 0).

The default duration is the rundown plus :data:`WINDMILLING_S` (10 minutes) of windmilling: the fuel
cut of the spool whose crossings are reported plus :data:`RUNDOWN_S`, the time the shipped rundown takes from the
fuel cut to windmilling (see its comment), plus :data:`WINDMILLING_S`; for ``blade_loss_rundown`` 15.01 + 45 +
600 = 660.01 s. A scenario without a fuel cut needs ``--duration``.

Under faults it behaves as every comparison (:func:`rotorcosim.master.compare.compare_schemes`): one
comparison at a time writes into DIR (a lock); a failed run says what happened and keeps what it recorded in its folder; Ctrl-C
stops the run going on (its folder says ``interrupted``), keeps the complete ones and says which;
``--resume`` runs only the runs that are not complete (the complete ones checked to be this comparison's: the
scenario, its level, the duration and every ``--set`` / ``--swap``).
"""
from __future__ import annotations

import math
from pathlib import Path

from rotorcosim.master.api import load_scenario
from rotorcosim.master.run.outputs import check_dpi
from rotorcosim.master.compare import KINDS, LevelValue, compare_schemes, pair
from rotorcosim.master.compare import within as within_tolerance
from rotorcosim.master.scenario.build import Scenario, schedule_of

from rotorcosim.cases.blade_loss import error_check
from rotorcosim.cases.rundown import fatigue
from rotorcosim.cases.blade_loss.results import RESULT_KEYS, unbalance_force

#: the acceptance: every Table 4 result at the end and every crossing's peaks within 2 %
TOLERANCE_PCT = 2.0
#: windmilling after the rundown in the default duration [s]: the rundown plus 10 minutes
WINDMILLING_S = 600.0
#: the rundown's length from the fuel cut to windmilling [s]. Measured on blade_loss_rundown (2850 N, the shipped
#: torque law, its automatic schedule over 120 s): the power turbine passes both critical speeds within 3 s of the
#: cut, its 4 900 rev/min no-load windmill speed ~16 s after it, and settles at ~3 430 rev/min (the airflow's
#: torque balancing the bearings' drag; 3 430 at 80, 100 and 120 s): within 5 % of that 32 s after the cut, within
#: 1 % 45 s after it. Another torque law or level moves it (--set spool_pt.aero_torque=...): give --duration then
RUNDOWN_S = 45.0
#: the file this comparison writes
TABLE = "rundown_compare.json"
#: the crossing peaks judged, per bearing
PEAKS = ("peak_whirl_mm", "peak_contact_load_N", "peak_contact_stress_MPa", "peak_transmitted_force_N")


def fuel_cut(sc: Scenario) -> float | None:
    """The fuel cut [s] of the spool whose crossings ``sc`` reports (the first of ``[results] spools``): None when
    that spool is not torque-driven (``spool.speed`` with profile ``torque``) or is never cut."""
    spools = sc.extra.get("results", {}).get("spools") or [n for n, c in sc.components.items()
                                                           if c.implementation == "spool.speed"]
    c = sc.components.get(spools[0]) if spools else None
    if c is None or c.parameters.get("profile") != "torque":
        return None
    cut = float(c.parameters.get("t_fuel_cut", -1.0))
    return cut if 0.0 <= cut < math.inf else None


def default_duration(sc: Scenario) -> float:
    """The rundown plus 10 minutes of windmilling: fuel cut + :data:`RUNDOWN_S` + :data:`WINDMILLING_S` [s]."""
    cut = fuel_cut(sc)
    if cut is None:
        raise ValueError(f"compare: scenario {sc.name!r} has no fuel cut (its first [results] spool is not a "
                         "spool.speed of profile 'torque' with t_fuel_cut >= 0): give --duration")
    return cut + RUNDOWN_S + WINDMILLING_S


def table(st: dict, mono: dict) -> dict:
    """The comparison of the staggered summary ``st`` with the monolithic ``mono`` (the module's keys
    ``results``, ``crossings``, ``speeds``, ``largest_error_pct``, ``within_2pct``)."""
    results = {}
    for k in sorted(set(st.get("bearings") or {}) | set(mono.get("bearings") or {})):
        a, b = (st.get("bearings") or {}).get(k, {}), (mono.get("bearings") or {}).get(k, {})
        results[k] = {key: pair(a.get(key), b.get(key)) for key in RESULT_KEYS}
    crossings = []
    by_key = {(c["spool"], c["critical_speed_rpm"]): c for c in st.get("crossings") or []}
    keys = [(c["spool"], c["critical_speed_rpm"]) for c in mono.get("crossings") or []]
    keys += [k for k in by_key if k not in keys]
    mono_by_key = {(c["spool"], c["critical_speed_rpm"]): c for c in mono.get("crossings") or []}
    for key in keys:
        a, b = by_key.get(key), mono_by_key.get(key)
        found = {k: c is not None and c.get("peak_found", True) for k, c in zip(KINDS, (a, b))}
        entry = {"spool": key[0], "critical_speed_rpm": key[1], "peak_found": found,
                 "t_s": {"staggered": a and a["t_s"], "monolithic": b and b["t_s"]},
                 "peak_speed_rpm": pair(a and a["peak_speed_rpm"], b and b["peak_speed_rpm"]), "bearings": {}}
        for loc in sorted(set((a or {}).get("bearings", {})) | set((b or {}).get("bearings", {}))):
            ra, rb = (a or {}).get("bearings", {}).get(loc, {}), (b or {}).get("bearings", {}).get(loc, {})
            entry["bearings"][loc] = {p: pair(ra.get(p), rb.get(p)) for p in PEAKS if p in ra or p in rb}
        if not any(found.values()):  # both runs agree that the response has no peak there: nothing to compare
            entry["note"] = "no resonance peak in either run"
        crossings.append(entry)
    judged = [c for c in crossings if any(c["peak_found"].values())]
    speeds = {sp: {"end_rpm": pair((st.get("speeds") or {}).get(sp, {}).get("end_rpm"), v.get("end_rpm"))}
              for sp, v in (mono.get("speeds") or {}).items()}
    groups = {
        "results": [e for r in results.values() for e in r.values()],
        "crossing_peaks": [e for c in judged for r in c["bearings"].values() for e in r.values()],
        "crossing_speeds": [c["peak_speed_rpm"] for c in judged],
    }
    largest, within = {}, {}
    for name, entries in groups.items():
        largest[name], within[name] = within_tolerance(entries, TOLERANCE_PCT)
    # no result at all to judge (no bearings, no crossing) is not a pass
    within["all"] = all(within.values()) and bool(groups["results"]) and bool(judged)
    return {"results": results, "crossings": crossings, "speeds": speeds, "largest_error_pct": largest,
            "within_2pct": within}


def fatigue_table(sc: Scenario, out: Path, duration: float) -> dict | None:
    """The damage-equivalent loads over the windmilling of both runs in ``out`` (the module's ``fatigue``)."""
    cut = fuel_cut(sc)
    t_from = (cut or 0.0) + RUNDOWN_S
    folders = {k: out / k for k in KINDS}
    if cut is None or duration <= t_from or not all((f / "timeseries.h5").is_file() for f in folders.values()):
        return None
    s = fatigue.settings(sc)
    counts = {k: fatigue.recorded_counts(f, sc, t_from) for k, f in folders.items()}
    loads = {key: {"del_N": pair(fatigue.content(counts["staggered"][key], s)["del_N"],
                                 fatigue.content(c, s)["del_N"])}
             for key, c in counts["monolithic"].items() if key in counts["staggered"]}
    largest, within = within_tolerance([v["del_N"] for v in loads.values()], TOLERANCE_PCT)
    return {"t_from_s": t_from, "woehler_exponent": s["woehler_exponent"],
            "reference_cycles": s["reference_cycles"], "loads": loads, "largest_error_pct": largest,
            "within_2pct": within and bool(loads)}


def phase_totals(summary: dict) -> dict:
    """Simulated time [s], intervals and steps of each phase of a run's timeline."""
    out = {}
    for iv in summary.get("timeline") or []:
        d = out.setdefault(iv["phase"], {"simulated_s": 0.0, "intervals": 0, "steps": 0})
        d["simulated_s"] += iv["t_end"] - iv["t_start"]
        d["intervals"] += 1
        d["steps"] += iv["steps"]
    return out


def compare_rundown(scenario: Scenario | str | Path = "blade_loss_rundown", duration: float | None = None,
                    out: str | Path = "rundown_compare", *, quiet: bool = True, figures: bool = True,
                    overwrite: bool = False, resume: bool = False, dpi: float | None = None,
                    warm_up: bool = True) -> dict:
    """Run a rundown scenario staggered and monolithic into ``out`` and return the table written to
    ``out/rundown_compare.json`` (the module's docstring says every key).

    ``scenario``: a :class:`Scenario` (e.g. ``load_scenario("blade_loss_rundown").set({...})``), a shipped name
    or a file; it must have rundown results (``[results] kind = "rundown"``) with the blade-loss engine's
    bearings. ``duration`` [s]: None for the rundown plus 10 minutes of windmilling (:func:`default_duration`).
    ``quiet``: no progress lines; ``figures``: draw each run's figures (after both runs, untimed); ``overwrite``:
    replace a previous comparison in ``out``; ``resume``: keep its complete runs and make the others; ``dpi``:
    the figures' resolution; ``warm_up``: a few untimed milliseconds first (the process's one-off costs).

    Raises ValueError for a bad input (before anything runs),
    :class:`~rotorcosim.master.sweep.SweepInterrupted` on Ctrl-C / SIGTERM (saying which runs are kept), and a
    run's own error when it fails (its folder keeps what it recorded)."""
    dpi = check_dpi(dpi)
    sc = scenario if isinstance(scenario, Scenario) else load_scenario(scenario)
    if sc.extra.get("results", {}).get("kind") != "rundown" or not all(f"bearing{k}" in sc.components
                                                                      for k in (0, 5)):
        raise ValueError(f"compare: scenario {sc.name!r} is not a rundown of the blade-loss engine ([results] kind "
                         "= \"rundown\" with bearings #0 and #5, as blade_loss_rundown)")
    rule = "given"
    if duration is None:
        duration = default_duration(sc)
        rule = (f"fuel cut {fuel_cut(sc):g} s + rundown {RUNDOWN_S:g} s + windmilling {WINDMILLING_S:g} s")
    if isinstance(duration, bool) or not isinstance(duration, (int, float)) or not (0 < duration < math.inf):
        raise ValueError(f"--duration must be a positive number of seconds, got {duration}")
    duration = float(duration)
    if resume and overwrite:
        raise ValueError("--resume continues the comparison in --out: it excludes --overwrite")
    unbalance = unbalance_force(sc)

    def tabulate(runs: dict, timing: dict) -> dict:
        st, mono = runs["staggered"], runs["monolithic"]
        return {"scenario": sc.name, "unbalance_N": unbalance, "duration_s": duration, "duration_rule": rule,
                "t_fuel_cut_s": fuel_cut(sc), "tolerance_pct": TOLERANCE_PCT,
                **table(st, mono),
                "wall_time_s": timing["wall_time_s"], "cpu_time_s": timing["cpu_time_s"],
                "speedup": timing["speedup"], "speedup_cpu": timing["speedup_cpu"],
                # the machine's 1-minute load average before and after each run (a shared machine's wall times)
                "load_average": timing["load_average"],
                "staggered_phases": phase_totals(st), "hold": st.get("hold"),
                # the staggered run's estimated error of every result beside its true one, in the same terms
                "estimated_error": error_check.table(st, mono) if st.get("bearings") and mono.get("bearings")
                else None,
                "fatigue": fatigue_table(sc, Path(out), duration)}

    return compare_schemes(sc, out, schedule_of(sc, None, duration), schedule_of(sc, "monolithic", duration),
                           tabulate=tabulate, table_name=TABLE, quiet=quiet, figures=figures, overwrite=overwrite,
                           resume=resume, dpi=dpi, level=LevelValue("unbalance_N", unbalance, "N"), warm_up=warm_up,
                           same=("bearings",))


#: options of ``rotorcosim compare`` that belong to the paper's Table 6 only (dest -> its spelling)
TABLE6_ONLY = {"revolutions": "--revolutions", "bearing": "--bearing", "schedule": "--schedule",
               "tolerance": "--tolerance", "timing_runs": "--timing-runs", "monolithic": "--monolithic"}


def run(args, sc: Scenario) -> int:
    """``rotorcosim compare`` for a rundown scenario ``sc`` (the command's ``--set`` / ``--swap`` /
    ``--unbalance`` applied): refuses Table 6's options, runs :func:`compare_rundown`, prints one line."""
    given = [flag for dest, flag in TABLE6_ONLY.items() if getattr(args, dest, None) is not None]
    if given:
        raise ValueError(f"compare {sc.loaded_name or sc.name}: {', '.join(given)} belong(s) to the paper's Table 6 "
                         "comparison, not to a rundown (options: --duration, --unbalance, --set, --swap, --out, "
                         "--overwrite, --resume, --no-figures, --dpi, --quiet)")
    t = compare_rundown(sc, args.duration, args.out, quiet=args.quiet, figures=not args.no_figures,
                        overwrite=args.overwrite, resume=args.resume, dpi=args.dpi)
    w, e = t["within_2pct"], t["largest_error_pct"]
    big = (t.get("estimated_error") or {}).get("largest")

    def pct(x):
        return "n/a" if x is None else f"{x:.2f} %"

    print(f"rundown comparison ({t['duration_s']:g} s): speed-up {t['speedup']:.1f} (CPU time "
          f"{t['speedup_cpu']:.1f}); largest error: Table 4 results at the end {pct(e['results'])}, crossing peaks "
          f"{pct(e['crossing_peaks'])}, peak speeds {pct(e['crossing_speeds'])}; "
          f"{'all within' if w['all'] else 'NOT all within'} {TOLERANCE_PCT:g} %"
          + (f"; estimated error of the staggered run {big['estimated_pct']:.2f} % against a true "
             f"{big['true_pct']:.2f} % (temperatures as rises: estimated_error)"
             if big is not None and big["estimated_pct"] is not None else "")
          + (f"; windmilling damage-equivalent loads within {pct(t['fatigue']['largest_error_pct'])}"
             if t.get("fatigue") else "")
          + f"; {Path(args.out) / TABLE}")
    return 0
