"""The Python API: everything the command line does, as functions returning results in memory.

::

    import rotorcosim
    sc = rotorcosim.load_scenario("toy_thermomechanical")     # shipped name or path (TOML or .ssp)
    sc = sc.set({"osc.F0": 20.0})                              # returns a new scenario
    sc = sc.swap("node", "mypkg.thermal:Node")                 # registry name, "module:Class", or a .fmu path
    res = rotorcosim.simulate(sc, duration=0.05)               # schedule=..., out=DIR writes the CLI's files
    res.time, res.phase, res["node.T"], res.summary            # numpy arrays; summary as in summary.json
    df = res.to_dataframe()                                    # labelled columns with units (needs pandas)

``rotorcosim run`` is :func:`simulate` with ``out=DIR``. Without ``out`` (or with the CSV format) the run is
recorded in memory; with ``out`` and HDF5, the result's arrays are read from ``timeseries.h5`` when first used
(a monolithic 2-minute run records ~0.5 GB, which need not sit in memory twice).
"""
from __future__ import annotations

import numbers
import os
import sys
from pathlib import Path
from typing import Mapping, Sequence

import numpy as np

from rotorcosim import scenarios
from rotorcosim.components.bounded_read import read_json
from rotorcosim.master import case
from rotorcosim.master.core.algorithm import SimulationDiverged  # noqa: F401 - re-exported: rotorcosim.SimulationDiverged
from rotorcosim.master.core.phases import Phases
from rotorcosim.master.core.threads import one_thread
from rotorcosim.master.observer.recorder_csv import column_names
from rotorcosim.master.observer.series import SeriesFile
from rotorcosim.master.run import checkpoint
from rotorcosim.master.run import summary as summaries
from rotorcosim.master.run.figure_pool import FigurePool
from rotorcosim.master.run.options import RunOptions
from rotorcosim.master.run.outputs import check_dpi, write_json
from rotorcosim.master.run.session import RunSession
from rotorcosim.master.scenario.build import Scenario, build_simulation, load_scenario as _load_file, schedule_of
from rotorcosim.master.scenario.cycle import cycle_of
from rotorcosim.master.schedule import budget
from rotorcosim.master.schedule.timeline import Schedule

#: the scenario run when none is named (declared with the shipped scenarios, ``scenarios.DEFAULT``)
DEFAULT_SCENARIO = scenarios.DEFAULT
#: ``schedule=`` names: the scenario's own schedule (its timeline), automatic, one TM interval
SCHEDULES = {"scenario": None, "auto": "auto", "monolithic": "monolithic"}


def load_scenario(name_or_path: str | Path | None = None) -> Scenario:
    """A scenario: a shipped name (see ``rotorcosim scenarios``), a TOML file, or an SSP archive (``.ssp``). None
    gives the default, :data:`DEFAULT_SCENARIO`. Its ``[results]`` keys are checked (the schema's, then its
    case's, master/case.py)."""
    sc = _load(name_or_path)
    case.check_results(sc)
    return sc


def _load(name_or_path: str | Path | None) -> Scenario:
    if name_or_path is None:
        return _load_file(scenarios.path(scenarios.DEFAULT))
    if isinstance(name_or_path, str) and not name_or_path.strip():  # Path("") is the current folder
        raise ValueError("load_scenario: an empty name: give a shipped scenario's name or a file")
    p = Path(name_or_path)
    if p.suffix.lower() == ".ssp":
        from rotorcosim.master.scenario.ssp import read_ssp

        return read_ssp(p)
    if p.is_dir() and not p.suffix and (scenarios.FOLDER / f"{p.name}.toml").is_file() and len(p.parts) == 1:
        # a shipped name that is also a folder here, typically the results of `run NAME --out NAME`: the folder is
        # no scenario ("is a folder, not a TOML file" refused the second run of that same command)
        return _load_file(scenarios.path(str(name_or_path)))
    if p.exists() or p.suffix:
        return _load_file(p)
    return _load_file(scenarios.path(str(name_or_path)))


def _postprocessor(sc: Scenario):
    """The module that turns a run into the scenario's results (its case's, ``[results] kind``), or None."""
    kind = sc.extra.get("results", {}).get("kind")
    if not kind:
        return None
    try:
        return case.results_of(kind)
    except case.CaseError as exc:
        raise ValueError(f"[results] kind {kind!r}: no such result extraction ({exc})") from None


def check_run(sc: Scenario, schedule=None, duration: float | None = None, force: bool = False,
              engine: str = "auto") -> dict:
    """The checks :func:`simulate` makes before it starts (the schedule, the duration, the budget), without
    running: a sweep makes them for every case before the first one runs. Returns the estimate (budget.py).

    >>> est = check_run(load_scenario("toy_thermomechanical"), "monolithic", duration=1.0)
    >>> est["steps"], est["engine"]
    (1000, 'python')
    """
    sch, _ = _schedule(sc, schedule, duration)
    return budget.check(sc, sch, force, engine)


def _schedule(sc: Scenario, schedule, duration: float | None):
    if duration is not None and (not isinstance(duration, numbers.Real) or isinstance(duration, bool)):
        raise TypeError(f"duration must be a number of seconds, got {type(duration).__name__} {duration!r}")
    if duration is not None and not (duration > 0 and duration < float("inf")):
        raise ValueError(f"duration must be a positive number of seconds, got {duration}")
    if isinstance(schedule, Schedule):
        if duration is not None:
            raise ValueError("give duration or a schedule object, not both")
        return schedule, None
    aliases = case.schedule_aliases()
    schedule = aliases.get(schedule, schedule) if isinstance(schedule, str) else schedule
    if schedule is not None and schedule not in SCHEDULES:
        raise ValueError(f"schedule {schedule!r}: use one of {sorted(SCHEDULES)} or a Timeline/AutoSchedule")
    kind = SCHEDULES.get(schedule) if schedule is not None else None
    return schedule_of(sc, kind, duration), kind


class Result:
    """A run: ``time`` [s], ``phase`` (per sample, the name of its phase: "TM" / "TO" unless the scenario names
    them otherwise), ``res["comp.port"]`` (a 1-D array for a
    scalar port, (n, size) for a vector one; SI units, see :meth:`unit` / :meth:`columns`), ``summary`` (the dict
    written to summary.json), ``files`` (the files written, with ``out=``). The arrays are in memory, or read
    from the run's time series file when first used (a run with ``out=`` and HDF5).

    Made by :func:`simulate`; its parameters: ``data`` (``"time"``, ``"phase"`` (0 coupled, 1 held) and one
    (n, size) array per recorded ``"comp.port"``), ``variables`` (``"comp.port"`` -> the port's declaration: unit,
    element labels), ``summary``, ``files`` and ``phases`` (the scenario's phase names,
    :class:`~rotorcosim.master.core.phases.Phases`; default "TM" / "TO").

    >>> import rotorcosim
    >>> res = rotorcosim.simulate("toy_thermomechanical", duration=0.05)
    >>> res
    <Result 'toy_thermomechanical': 51 samples to t = 0.05 s, 3 signals>
    >>> res.signals, res.unit("node.T")
    (['osc.x', 'osc.P', 'node.T'], 'K')
    >>> float(res.time[-1]), str(res.phase[-1]), res["node.T"].shape      # [s], phase, one value per sample
    (0.05, 'TM', (51,))
    """

    def __init__(self, data: Mapping[str, np.ndarray], variables: dict, summary: dict, files: Sequence[Path] = (),
                 phases: Phases | None = None):
        self._data = data
        self._phase_names = np.array((phases or Phases()).names)
        self._vars = variables
        self.summary = summary
        self.files = [Path(f) for f in files]

    @property
    def time(self) -> np.ndarray:
        """The sample times [s]."""
        return self._data["time"]

    @property
    def phase(self) -> np.ndarray:
        """The phase of each sample, by the scenario's names ("TM" thermo-mechanical / "TO" thermal-only by
        default)."""
        return self._phase_names[self._data["phase"].astype(int)]

    @property
    def signals(self) -> list[str]:
        """The recorded ports, ``component.port``."""
        return list(self._vars)

    def __contains__(self, ref: str) -> bool:
        return ref in self._vars

    def __getitem__(self, ref: str) -> np.ndarray:
        if ref not in self._vars:
            raise KeyError(f"{ref!r} was not recorded; recorded: {', '.join(self._vars) or 'nothing'} "
                           f"(choose with simulate(..., record=[...]) or the scenario's [outputs] record)")
        x = self._data[ref]
        return x[:, 0] if x.shape[1] == 1 else x

    def unit(self, ref: str) -> str:
        """The unit of the recorded port ``ref`` (``"comp.port"``), e.g. ``"m"``, ``"W"``, ``"K"``."""
        self[ref]
        return self._vars[ref].unit

    def columns(self, ref: str) -> list[str]:
        """Names of a port's vector elements (``["x", "y", "z"]``, ``["inner", "outer"]``...)."""
        self[ref]
        return self._vars[ref].column_labels()

    def to_dataframe(self):
        """A pandas DataFrame: ``time (s)``, ``phase`` and one column per recorded element, labelled with its
        unit (``osc.x[0] (m)``, ``node.T (K)``). pandas is not a dependency of rotorcosim (the
        arrays need none); install it to use this."""
        try:
            import pandas as pd
        except ImportError:
            raise ImportError("Result.to_dataframe() needs pandas, which rotorcosim does not install: "
                              "pip install pandas (or use res.time, res.phase and res['comp.port'])") from None
        names = column_names(self.signals, self._vars)
        blocks = [self._data[r] for r in self.signals]
        values = np.hstack(blocks) if blocks else np.zeros((len(self.time), 0))
        df = pd.DataFrame(values, columns=names)
        df.insert(0, "phase", self.phase)
        df.insert(0, "time (s)", self.time)
        return df

    def __repr__(self) -> str:
        return (f"<Result {self.summary.get('scenario')!r}: {len(self.time)} samples to t = "
                f"{self.summary.get('t_end_s', float('nan')):.4g} s, {len(self._vars)} signals>")


def simulate(sc: Scenario | str | Path, duration: float | None = None, schedule=None, out: str | Path | None = None,
             record: Sequence[str] | None = None, figures: bool = True, progress: bool = False, *,
             overwrite: bool = False, resume: bool = False, force: bool = False,
             checkpoint_every: float | None = checkpoint.EVERY_S, step_timeout: float = 0.0, engine: str = "auto",
             dpi: float | None = None) -> Result:
    """Run scenario ``sc`` (a :class:`Scenario`, or a name or path for :func:`load_scenario`).

    ``duration`` [s] cuts the schedule; ``schedule`` is ``"scenario"`` (the scenario's own; also an alias a case
    declares, ``SCHEDULE_ALIASES``), ``"auto"``, ``"monolithic"`` or a :class:`~rotorcosim.master.schedule.timeline.Timeline` / ``AutoSchedule``;
    ``record`` the ports to record (default: the scenario's ``[outputs] record``); ``progress`` shows a progress bar.

    ``out``: a folder that receives what ``rotorcosim run`` writes (summary.json, the time series, the figures
    unless ``figures=False``). It must be empty, or hold a previous run's results and ``overwrite``, or an
    interrupted run and ``resume`` (rundir.py); runs with a folder are checkpointed every ``checkpoint_every``
    wall seconds, at interval ends at least ``min(checkpoint_every, checkpoint.END_GAP_S)`` after the last
    checkpoint, and where an interrupt (SIGINT/SIGTERM) stops them. Any run is refused before it starts if it is
    estimated above budget.LIMIT_S of wall time, unless ``force``. ``step_timeout`` [s] (0: none) ends a run whose component
    step hangs (watchdog.py), writing a failed summary first. ``engine``: ``"auto"`` runs each thermo-mechanical
    interval through the compiled loop when every component offers a compiled kernel (master/compiled/runner.py),
    ``"python"`` through the generic loop, ``"compiled"`` through the compiled loop or not at all (an error); the
    summary's ``engine`` says which ran (``engine_note`` why the generic loop did under auto). ``dpi``: the
    resolution of the figures (None: :data:`~rotorcosim.master.run.outputs.FIGURE_DPI`).

    The summary's ``status`` says how the run ended: ``complete``, ``stopped`` (a component asked to stop),
    ``interrupted`` (SIGINT/SIGTERM) or ``failed``; on ``interrupted`` and ``failed`` the error is raised after
    the summary and the time series are written, carrying the partial :class:`Result` as ``.result``. Results
    or figures that fail once the steps have ended fail the run too: :class:`ResultsFailed`.

    The whole run uses one BLAS thread whatever the calling program set up (threads.py): the same numbers as the
    command line's, bit for bit."""
    import scipy.linalg  # noqa: F401  (loads scipy's own BLAS now, so that the limit below covers it too)

    with one_thread():
        if not isinstance(sc, (Scenario, str, os.PathLike)):
            raise TypeError(f"simulate: give a Scenario, a shipped scenario's name or a file, got {type(sc).__name__}")
        if not isinstance(sc, Scenario):
            sc = load_scenario(sc)
        opts = RunOptions(out=out, record=record, figures=figures, progress=progress, overwrite=overwrite,
                          resume=resume, force=force, checkpoint_every=checkpoint_every, step_timeout=step_timeout,
                          engine=engine, dpi=dpi)
        return _run(sc, schedule, duration, opts)


def _run(sc: Scenario, schedule, duration: float | None, opts: RunOptions) -> Result:
    """The run :func:`simulate` makes once its options are checked: the scenario's own checks, then the run in a
    :class:`~rotorcosim.master.run.session.RunSession`, then the case's results and figures."""
    sch, kind = _schedule(sc, schedule, duration)
    estimate = budget.check(sc, sch, opts.force, opts.engine)
    if estimate["wall_s"] > budget.WARN_S:
        # from Python as from the command line: a long run does not start silently
        # the automatic schedule is priced as if every step were coupled: an upper bound, often far above
        # (it holds most of a long run), and said so
        said = "at most" if estimate.get("upper_bound") else "estimated"
        print(f"{sc.name}: {estimate['steps']:,} steps, {said} {estimate['wall']} of wall time "
              f"({estimate['engine']} engine)", file=sys.stderr)
    post = _postprocessor(sc)
    signals = opts.signals(sc.outputs)
    fmt = sc.outputs.get("format", "h5")
    if fmt not in ("h5", "csv"):
        raise ValueError(f"[outputs] format {fmt!r} not in ('h5', 'csv')")
    cycle = cycle_of(sc.schedule)
    if post is not None and cycle is None:
        raise ValueError(f"scenario {sc.name!r}: [results] needs a cycle, [schedule] speed_rpm or cycle (steady "
                         "windows in cycles)")
    with RunSession(sc, sch, signals, fmt, opts) as run:
        post_obs = post.observers(sc, cycle) if post is not None else []
        sim = build_simulation(sc, run.observers(post_obs, estimate))
        run.built(sim)
        if post is not None and hasattr(post, "check"):
            post.check(sc, sim)  # the scenario's own consistency checks before anything runs
        sim.engine_choice = opts.engine
        pool = None
        if opts.figures and run.out is not None and post is not None and not run.keep:
            # its workers start now, one after the other, and import matplotlib and the figures while the run goes
            pool = FigurePool(preload=[m for m in [getattr(post, "FIGURES_MODULE", None)] if m],
                              after=sim.first_compiled)
            run.on_exit(pool.close)
        run.start(summaries.head(sc, kind, sch.duration, estimate, run.provenance))
        run.execute()
        if run.refused():
            raise run.error
        summary = run.summary()
        data, files = run.recorded()
        try:
            files += _results(run, post, post_obs, summary, data, pool)
        except ResultsFailed as exc:
            if run.error is not None:   # the run's own error is the one that ended it
                summary["results_error"] = f"{type(exc.__cause__).__name__}: {exc.__cause__}"
            else:
                # the steps' record is whole and stays; the summary must not say "complete" over results that
                # were never made (_results has taken back a half-made extraction, _draw its figures)
                run.post_failed(exc)
                summary.update(status=run.status, error=f"{type(exc).__name__}: {exc}")
        run.finish(summary, files)
        result = Result(data, dict(run.recorder.variables), summaries.as_written(summary), files, sim.phases)
        if run.error is not None:
            try:
                run.error.result = result
            except AttributeError:  # an exception type without a __dict__
                pass
            raise run.error
    return result


class ResultsFailed(RuntimeError):
    """A run whose steps ended but whose results could not be made after them: ``step`` says which (extracting
    the results, drawing the figures); the error that stopped it is its ``__cause__``. Its time series is kept,
    summary.json says ``failed`` with this error, and no figure of the step is left (:func:`_draw`). Raised
    carrying the partial :class:`Result` as ``.result``, like a failed run's error."""

    def __init__(self, step: str, cause: BaseException):
        self.step = step
        super().__init__(f"{step} failed after the simulation ended: {type(cause).__name__}: {cause}")


#: the steps after the simulation, as :class:`ResultsFailed` names them
EXTRACTING, DRAWING = "extracting the results", "drawing the figures"


def _results(run: RunSession, post, post_obs: list, summary: dict, data, pool: FigurePool | None) -> list[Path]:
    """The case's results (``post``, its observers ``post_obs``) added to ``summary``, or the components' final
    outputs for a scenario without a case or a run that computed nothing; the estimated error; the case's figures
    of a run that ended by itself, drawn from ``data`` (in ``pool``). Returns the figure files; a step that fails
    raises :class:`ResultsFailed`."""
    before = dict(summary)
    try:
        return _extract(run, post, post_obs, summary, data, pool)
    except ResultsFailed:   # the figures: the results made before them are whole
        raise
    except Exception as exc:
        # some results added, the located events taken out to be merged: the summary as the run left it
        summary.clear()
        summary.update(before)
        raise ResultsFailed(EXTRACTING, exc) from exc


def _extract(run: RunSession, post, post_obs: list, summary: dict, data, pool: FigurePool | None) -> list[Path]:
    sc, sim = run.sc, run.sim
    hold = sim.report.hold
    if post is None or (run.error is not None and not sim.computed):
        summary["final_outputs"] = summaries.final_outputs(sim.system)
        summaries.add_estimated_error(summary, sc, hold)
        return []
    located = summary.pop("events", None)
    summary.update(post.extract(sc, sim, post_obs, sim.report))
    # what the case found at some time of the run that its end values do not show: one line each; the events
    # the master located (master/core/events.py) come first in the one list
    for event in summary.get("events") or []:
        print(f"{sc.name}: warning: {event['message']}", file=sys.stderr)
    for event in located or []:
        print(f"{sc.name}: event: {event['message']}", file=sys.stderr)
    if located is not None:
        summary["events"] = located + (summary.get("events") or [])
    summaries.add_estimated_error(summary, sc, hold)
    if not (run.opts.figures and run.out is not None and run.status in summaries.ENDED):
        return []
    names = _draw(post, sc, data, run.out, pool, run.opts.dpi)
    summary["figures"] = names
    return [run.out / n for n in names]


def _draw(post, sc: Scenario, data, out: Path, pool: FigurePool | None, dpi) -> list[str]:
    """``post.figures`` into ``out``, whole or not at all: a drawing that fails leaves none of the files it made
    (a figure's ``.part``, the figures already drawn: a set of figures with some missing reads as a run that drew
    no more) and raises :class:`ResultsFailed`."""
    present = {f.name for f in out.iterdir()}
    try:
        return post.figures(sc, data, out, pool=pool, dpi=dpi)
    except Exception as exc:
        for f in out.iterdir():
            if f.name not in present and f.is_file():
                f.unlink(missing_ok=True)
        raise ResultsFailed(DRAWING, exc) from exc


def draw_figures(sc: Scenario | str | Path, out: str | Path, pool: FigurePool | None = None,
                 dpi: float | None = None) -> list[str]:
    """Draw the figures of the finished run in folder ``out`` (a run of ``sc`` with ``out=`` and the HDF5 format,
    e.g. one run with ``figures=False``) from its ``timeseries.h5``, with the same drawing code as a run; adds
    their names to its summary.json (``figures``) and returns them. ``pool``: a
    :class:`~rotorcosim.master.run.figure_pool.FigurePool` to draw them in, or None (drawn in this process);
    ``dpi``: their resolution (None: :data:`~rotorcosim.master.run.outputs.FIGURE_DPI`).

    ``rotorcosim compare`` uses it to draw its two runs' figures after both timed runs, so that no figure worker
    competes with a timed simulation."""
    if not isinstance(sc, Scenario):
        sc = load_scenario(sc)
    out = Path(out)
    post = _postprocessor(sc)
    if post is None:
        raise ValueError(f"scenario {sc.name!r} has no [results] kind: it draws no figures")
    f = out / "summary.json"
    try:
        summary = read_json(f, "summary")
    except (OSError, ValueError) as exc:
        raise ValueError(f"{out}: no readable summary.json of a finished run ({exc})") from None
    if summary.get("status") not in ("complete", "stopped"):
        raise ValueError(f"{f}: the run's status is {summary.get('status')!r}: figures are drawn of a complete "
                         "or stopped run only")
    name = summary.get("timeseries")
    if not name or not name.endswith(".h5") or not (out / name).exists():
        raise ValueError(f"{f}: the run has no HDF5 time series in {out} (timeseries: {name!r}): the figures "
                         "are drawn from timeseries.h5 ([outputs] format = \"h5\")")
    with one_thread():  # the figures' linear analyses give the run's numbers (core/threads.py)
        # a failure leaves the complete run as it was (its summary without figures: drawn again later)
        names = _draw(post, sc, SeriesFile(out / name), out, pool, check_dpi(dpi))
    write_json(f, {**summary, "figures": names})
    return names
