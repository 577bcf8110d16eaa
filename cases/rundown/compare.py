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
  (simulated time, intervals and steps of each phase of the staggered run) and its ``hold`` report.

The relative error is ``100 |staggered - monolithic| / |monolithic|`` (temperatures in degrees C, as Table 4 and
``rotorcosim compare``'s Table 6 give them; 0 when both are 0).

The default duration is the rundown plus :data:`WINDMILLING_S` (10 minutes) of windmilling: the fuel
cut of the spool whose crossings are reported plus :data:`RUNDOWN_S`, the time the shipped rundown takes from the
fuel cut to windmilling (see its comment), plus :data:`WINDMILLING_S`; for ``blade_loss_rundown`` 15.01 + 45 +
600 = 660.01 s. A scenario without a fuel cut needs ``--duration``.

Under faults it behaves as ``rotorcosim compare`` (cases/blade_loss/compare.py): one comparison at a time
writes into DIR (a lock); a failed run says what happened and keeps what it recorded in its folder; Ctrl-C
stops the run going on (its folder says ``interrupted``), keeps the complete ones and says which;
``--resume`` runs only the runs that are not complete (the complete ones checked to be this comparison's: the
scenario, its level, the duration and every ``--set`` / ``--swap``).
"""
from __future__ import annotations

import copy
import json
import math
import sys
import tempfile
from pathlib import Path

from rotorcosim.master.api import check_run, load_scenario
from rotorcosim.master.cli.run import execute
from rotorcosim.master.run.outputs import check_dpi, write_json
from rotorcosim.master.run.rundir import LOCK, check_folder, ensure_folder
from rotorcosim.master.scenario.build import Scenario, schedule_of
from rotorcosim.master.schedule import Interval, Timeline, budget
from rotorcosim.master.sweep import SweepInterrupted
from rotorcosim.master.sweep.folder import named_os_error
from rotorcosim.master.sweep.lock import FolderLock

from rotorcosim.cases.blade_loss.compare import _draw, _kept, _load, _quantum
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
#: the two runs, in the order they run, and their folders
KINDS = ("staggered", "monolithic")
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


def rel_error_pct(a, b) -> float | None:
    """``100 |a - b| / |b|`` (0 when both are 0; None when it cannot be formed: a missing value, b = 0 alone)."""
    if not isinstance(a, (int, float)) or not isinstance(b, (int, float)) or not (math.isfinite(a)
                                                                                  and math.isfinite(b)):
        return None
    if b == 0.0:
        return 0.0 if a == 0.0 else None
    return 100.0 * abs(a - b) / abs(b)


def _pair(a, b) -> dict:
    return {"staggered": a, "monolithic": b, "rel_error_pct": rel_error_pct(a, b)}


def _within(entries) -> tuple[float | None, bool]:
    """(largest relative error, all within TOLERANCE_PCT) of ``entries`` (None errors: not within)."""
    errs = [e["rel_error_pct"] for e in entries]
    known = [e for e in errs if e is not None]
    return (max(known) if known else None), (None not in errs and all(e <= TOLERANCE_PCT for e in errs))


def table(st: dict, mono: dict) -> dict:
    """The comparison of the staggered summary ``st`` with the monolithic ``mono`` (the module's keys
    ``results``, ``crossings``, ``speeds``, ``largest_error_pct``, ``within_2pct``)."""
    results = {}
    for k in sorted(set(st.get("bearings") or {}) | set(mono.get("bearings") or {})):
        a, b = (st.get("bearings") or {}).get(k, {}), (mono.get("bearings") or {}).get(k, {})
        results[k] = {key: _pair(a.get(key), b.get(key)) for key in RESULT_KEYS}
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
                 "peak_speed_rpm": _pair(a and a["peak_speed_rpm"], b and b["peak_speed_rpm"]), "bearings": {}}
        for loc in sorted(set((a or {}).get("bearings", {})) | set((b or {}).get("bearings", {}))):
            ra, rb = (a or {}).get("bearings", {}).get(loc, {}), (b or {}).get("bearings", {}).get(loc, {})
            entry["bearings"][loc] = {p: _pair(ra.get(p), rb.get(p)) for p in PEAKS if p in ra or p in rb}
        if not any(found.values()):  # both runs agree that the response has no peak there: nothing to compare
            entry["note"] = "no resonance peak in either run"
        crossings.append(entry)
    judged = [c for c in crossings if any(c["peak_found"].values())]
    speeds = {sp: {"end_rpm": _pair((st.get("speeds") or {}).get(sp, {}).get("end_rpm"), v.get("end_rpm"))}
              for sp, v in (mono.get("speeds") or {}).items()}
    groups = {
        "results": [e for r in results.values() for e in r.values()],
        "crossing_peaks": [e for c in judged for r in c["bearings"].values() for e in r.values()],
        "crossing_speeds": [c["peak_speed_rpm"] for c in judged],
    }
    largest, within = {}, {}
    for name, entries in groups.items():
        largest[name], within[name] = _within(entries)
    # no result at all to judge (no bearings, no crossing) is not a pass
    within["all"] = all(within.values()) and bool(groups["results"]) and bool(judged)
    return {"results": results, "crossings": crossings, "speeds": speeds, "largest_error_pct": largest,
            "within_2pct": within}


def phase_totals(summary: dict) -> dict:
    """Simulated time [s], intervals and steps of each phase of a run's timeline."""
    out = {}
    for iv in summary.get("timeline") or []:
        d = out.setdefault(iv["phase"], {"simulated_s": 0.0, "intervals": 0, "steps": 0})
        d["simulated_s"] += iv["t_end"] - iv["t_start"]
        d["intervals"] += 1
        d["steps"] += iv["steps"]
    return out


def _changes(edits) -> list | None:
    """A scenario's edits (provenance.py) without where they came from (the command line, Python), as JSON."""
    if not isinstance(edits, list):
        return None
    return json.loads(json.dumps([{k: v for k, v in dict(e).items() if k != "origin"} for e in edits]))


def _plans(sc: Scenario, duration: float) -> dict:
    """(scenario, schedule) of each run: the scenario's own (automatic) schedule, and one coupled interval."""
    plans = {}
    for kind, sched in zip(KINDS, (None, "monolithic")):
        s = copy.deepcopy(sc)
        s.name = f"{sc.name}_{kind}"
        plans[kind] = (s, schedule_of(s, sched, duration))
    return plans


def _warm_up(sc: Scenario, out: Path) -> None:
    """A few milliseconds of the system through a coupled interval, a thermal-only one and a restart, untimed,
    so that neither timed run pays the process's one-off costs (kernels loaded, model matrices built, first
    calls): a few seconds that would weigh on a short comparison's ratio."""
    s = copy.deepcopy(sc)
    h = float(s.schedule.get("step", 1e-5))
    tm = 2 * _quantum(s)
    with tempfile.TemporaryDirectory(dir=out) as tmp:
        execute(s, Path(tmp), figures=False, checkpoint_every=None,
                schedule=Timeline([Interval("TM", tm, h), Interval("TO", 0.1, 0.05), Interval("TM", tm, h)]))


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
    out = check_folder(out)
    held = [k for k in KINDS if (out / k).is_dir() and any(p.name != LOCK for p in (out / k).iterdir())]
    if held and not overwrite and not resume:
        raise ValueError(f"--out {out} already holds a comparison ({', '.join(held)}): results are never mixed; "
                         "give --overwrite to replace it, --resume to continue it, or another folder")
    if resume and not held:
        raise ValueError(f"--resume: {out} holds no comparison to continue")
    plans = _plans(sc, duration)
    # each run's own checks (schedule, budget) before anything runs; then the two together
    ests = {kind: check_run(s, sch) for kind, (s, sch) in plans.items()}
    total = sum(e["wall_s"] for e in ests.values())
    if total > budget.LIMIT_S:
        raise budget.BudgetError(f"this comparison would take about {budget.hms(total)} of wall time, above the "
                                 f"{budget.hms(budget.LIMIT_S)} limit: give a shorter --duration")
    unbalance = unbalance_force(sc)
    # --resume: the complete runs of this comparison are kept (another scenario, level or duration is an error)
    kept = {kind: _kept(out / kind, plans[kind][0].name, unbalance, duration) for kind in held} if resume else {}
    kept = {k: v for k, v in kept.items() if v is not None}
    for kind, s in kept.items():  # the same --set / --swap / --unbalance too (a fuel cut moved, a part swapped)
        if _changes((s.get("provenance") or {}).get("edits")) != _changes(sc.edits):
            raise ValueError(f"--resume: {out / kind} holds a run made with other --set/--swap/--unbalance "
                             f"({(s.get('provenance') or {}).get('edits')}): give the same command, or another folder")
    made = not out.exists()
    ensure_folder(out)
    try:
        with FolderLock(out, "comparison"):
            try:
                return _compare(out, duration, rule, sc, plans, kept, quiet, figures, overwrite or resume, dpi,
                                warm_up, unbalance)
            except KeyboardInterrupt:
                said = [f"{k} complete (kept in {out / k})" if _kept(out / k, None, None, None) is not None
                        else f"{k} not complete" for k in KINDS]
                raise SweepInterrupted(f"interrupted: {', '.join(said)}; continue with --resume") from None
    except BaseException:
        # refused at set-up (a bad --set value: the warm-up's components say so first): a folder made here for
        # nothing goes again, as a run's does (rundir.py)
        if made and out.is_dir() and not any(out.iterdir()):
            out.rmdir()
        raise


def _compare(out, duration, rule, sc, plans, kept, quiet, figures, overwrite, dpi, warm_up, unbalance) -> dict:
    """The two runs and the table, in the locked folder (:func:`compare_rundown` has checked every input)."""
    (out / TABLE).unlink(missing_ok=True)  # never left beside runs it does not describe
    if warm_up and len(kept) < len(KINDS):
        _warm_up(sc, out)
    runs, loads, later = {}, {}, {}
    for i, kind in enumerate(KINDS, 1):
        s, sch = plans[kind]
        if kind in kept:
            runs[kind], loads[kind] = kept[kind], [None, None]
            if not quiet:
                print(f"[{i}/2] {kind}: complete in {out / kind}, kept", file=sys.stderr, flush=True)
            continue
        # figures from the time series after both runs (no figure worker beside a timed run)
        draw_later = figures and s.outputs.get("format", "h5") == "h5" and bool(s.outputs.get("record"))
        if draw_later:
            later[kind] = s
        if not quiet:
            print(f"[{i}/2] {kind}: {duration:g} s simulated", file=sys.stderr, flush=True)
        load = _load()
        runs[kind] = execute(s, out / kind, figures=figures and not draw_later, quiet=quiet, schedule=sch,
                             overwrite=overwrite, checkpoint_every=None, dpi=dpi)
        loads[kind] = [load, _load()]
        if not quiet:
            print(f"[{i}/2] {kind}: done in {runs[kind]['wall_time_s']:.3g} s", file=sys.stderr, flush=True)
    if later:
        _draw(out, later, quiet, dpi)
    st, mono = runs["staggered"], runs["monolithic"]
    wall = {k: runs[k].get("wall_time_s") for k in KINDS}
    cpu = {k: runs[k].get("cpu_time_s") for k in KINDS}
    result = {"scenario": sc.name, "unbalance_N": unbalance, "duration_s": duration, "duration_rule": rule,
              "t_fuel_cut_s": fuel_cut(sc), "tolerance_pct": TOLERANCE_PCT,
              **table(st, mono),
              "wall_time_s": wall, "cpu_time_s": cpu,
              "speedup": wall["monolithic"] / wall["staggered"] if wall["staggered"] else None,
              "speedup_cpu": cpu["monolithic"] / cpu["staggered"] if cpu["monolithic"] and cpu["staggered"] else None,
              # the machine's 1-minute load average before and after each run (a shared machine's wall times)
              "load_average": loads,
              "staggered_phases": phase_totals(st), "hold": st.get("hold")}
    try:
        write_json(out / TABLE, result)
    except OSError as exc:  # the runs are complete and kept: a --resume writes the table
        (out / (TABLE + ".part")).unlink(missing_ok=True)
        raise named_os_error(exc, out, f"writing {TABLE}") from None
    return result


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

    def pct(x):
        return "n/a" if x is None else f"{x:.2f} %"

    print(f"rundown comparison ({t['duration_s']:g} s): speed-up {t['speedup']:.1f} (CPU time "
          f"{t['speedup_cpu']:.1f}); largest error: Table 4 results at the end {pct(e['results'])}, crossing peaks "
          f"{pct(e['crossing_peaks'])}, peak speeds {pct(e['crossing_speeds'])}; "
          f"{'all within' if w['all'] else 'NOT all within'} {TOLERANCE_PCT:g} %; {Path(args.out) / TABLE}")
    return 0
