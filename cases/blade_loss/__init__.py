"""The reference paper's blade-loss case: its Table 4 results, Figs. 9-14, the Table 5 / Table 6 comparisons.

- :mod:`.results`: the paper's 11 result categories for bearings #0 and #5 (``summary.json`` -> ``bearings``);
- :mod:`.figures`: figures like the paper's Figs. 9-14, drawn from a run's time series;
- :mod:`.table5`, :mod:`.paper_comparison`: a sweep's results in the paper's Table 5 format, and scored against it;
- :mod:`.compare`: ``rotorcosim compare``, the paper's Table 6 (staggered against monolithic);
- :mod:`.linear_engine`, :mod:`.critical_speeds`: the engine linearised about its bearings' state, its critical
  speeds and Campbell diagram (``rotorcosim critical-speeds``);
- ``reference_table5.csv``, ``reference_table6.csv``: the paper's tables.

The generic master runs the case as any other; what its parts measured on this system:

- The cycle: ``[schedule] speed_rpm = 16000`` (blade_loss.toml), the speed the unbalance turns at (checked
  against ``[results] speed_parameter`` before every run, :func:`.results.check`); the master turns it into the
  period 60 / 16000 s of the hold's windows, the restart ramp and the steady windows of the results.
- The hold's statistic: ``mean`` (the paper holds the RMS, ``hold = "rms"``, which overstates a fluctuating
  power). The TO law's elasticity in the rubbing cases: e ~ 0.25-0.3 (the journal orbit grows as the SFD oil
  thins); docs/table6_levels.md.
- The group driver: with the stiff rub ring bearing #0's drag follows the SFD oil through the orbit and the
  loads (2 055 -> 1 215 W while the SFD oil warms 47 -> 80 C at 8 551 N, the bearing's own oil barely moving).
  Keeping a driver only where it beats the producer's own TO law: the 2-minute run at 2 850 N is 0.27 % off the
  monolithic run (1.41 % with the producers' own temperatures as drivers); 5 700-14 252 N 0.68-0.97 % with a
  driver, 3.4-4.7 % without. The driver's bound (a factor 3) is not reached in the seven Table 6 levels (largest
  |b dT| 0.81: the SFD oil, 14 252 N).
- The restart: stepping the thermal growths into the frozen mechanics at once rings the rotor's axial mode
  (~480 Hz; at 712 N +-3 um at bearing #0 and the ball loads +-10 %, decaying 4 % in 10 cycles); the default
  ramp of 2 rotor cycles (3.6 periods of that mode) keeps ~2 % of it; ``restart_cycles = 0`` is the paper's step.
- The error estimate takes temperatures relative to their rise above the run's initial temperature
  (results.estimated_errors), not to their degrees C values as Table 6's relative errors do.
"""

from rotorcosim.master.scenario import checkers

#: the result extraction of the scenarios whose ``[results] kind`` is ``"blade_loss"`` (rotorcosim.master.case)
RESULTS = "rotorcosim.cases.blade_loss.results"
#: the case's own commands of the ``rotorcosim`` program
COMMANDS = {
    "compare": ("rotorcosim.cases.blade_loss.compare",
                "staggered against monolithic: the paper's Table 6, or a rundown's"),
    "critical-speeds": ("rotorcosim.cases.blade_loss.critical_speeds",
                        "synchronous critical speeds and Campbell diagram of the rotor"),
    "new-engine": ("rotorcosim.cases.blade_loss.new_engine",
                   "write a small engine of your own and its blade-loss and rundown scenarios into a folder"),
    "check-engine": ("rotorcosim.cases.blade_loss.check_engine",
                     "an engine file's problems, or its nodes, masses, inertias, critical speeds with their "
                     "amplification factors and separation margins (API 684), warnings and Campbell diagram"),
}
#: the level the case sweeps (master/case.py ``Level``): the blade-loss force, held by the component parameter its
#: scenarios name in ``[results] unbalance_parameter``; ``--unbalance`` on ``run`` and ``sweep``, ``unbalance_N``
#: in a run's summary, ``levels_N`` in sweep.json, one sweep case folder ``F_<level>`` per level
LEVEL = {"results_key": "unbalance_parameter", "name": "unbalance", "option": "--unbalance", "unit": "N",
         "label": "blade-loss unbalance force", "summary_key": "unbalance_N", "sweep_key": "levels_N",
         "folder_prefix": "F_"}
#: ``rotorcosim sweep --unbalance paper``: the seven levels of the paper's Table 5 [N]
LEVELS = {"paper": (712.0, 1425.0, 2850.0, 5700.0, 8551.0, 11401.0, 14252.0)}
#: the scenario ``sweep`` and ``export-ssp`` start from: the levels' base file (F_u = 2850 N as in blade_loss_2850)
DEFAULT_SCENARIO = "blade_loss"
#: ``--schedule paper`` (and ``simulate(schedule="paper")``): the scenario's own timeline, the paper's
SCHEDULE_ALIASES = {"paper": "scenario"}
#: the case's own ``[results]`` keys (master/case.py checks them when a scenario of the case is loaded)
RESULTS_KEYS = {"unbalance_parameter": checkers.port_ref}
#: the key of sweep.json the score of SWEEP_TABLES is written under
SCORE_KEY = "paper_score"
#: what a sweep with one case per level writes besides its own files (Table 5, the paper comparison)
SWEEP_TABLES = "rotorcosim.cases.blade_loss.paper_comparison:sweep_tables"
#: the files SWEEP_TABLES writes (``sweep --overwrite`` may clear them)
SWEEP_FILES = ("table5.csv", "table5.md", "paper_comparison.csv", "paper_comparison.png")
#: the line ``rotorcosim sweep`` prints for the score SWEEP_TABLES returns
SWEEP_SCORE = "rotorcosim.cases.blade_loss.paper_comparison:score_line"
