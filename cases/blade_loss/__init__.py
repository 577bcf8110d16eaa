"""The reference paper's blade-loss case: its Table 4 results, Figs. 9-14, the Table 5 / Table 6 comparisons.

- :mod:`.results`: the paper's 11 result categories for bearings #0 and #5 (``summary.json`` -> ``bearings``);
- :mod:`.figures`: figures like the paper's Figs. 9-14, drawn from a run's time series;
- :mod:`.table5`, :mod:`.paper_comparison`: a sweep's results in the paper's Table 5 format, and scored against it;
- :mod:`.compare`: ``rotorcosim compare``, the paper's Table 6 (staggered against monolithic);
- :mod:`.linear_engine`, :mod:`.critical_speeds`: the engine linearised about its bearings' state, its critical
  speeds and Campbell diagram (``rotorcosim critical-speeds``);
- ``reference_table5.csv``, ``reference_table6.csv``: the paper's tables.
"""

#: the result extraction of the scenarios whose ``[results] kind`` is ``"blade_loss"`` (rotorcosim.master.case)
RESULTS = "rotorcosim.cases.blade_loss.results"
#: the case's own commands of the ``rotorcosim`` program
COMMANDS = {
    "compare": ("rotorcosim.cases.blade_loss.compare", "the paper's Table 6: staggered against monolithic"),
    "critical-speeds": ("rotorcosim.cases.blade_loss.critical_speeds",
                        "synchronous critical speeds and Campbell diagram of the rotor"),
}
#: ``rotorcosim sweep --unbalance paper``: the seven levels of the paper's Table 5 [N]
LEVELS = {"paper": (712.0, 1425.0, 2850.0, 5700.0, 8551.0, 11401.0, 14252.0)}
#: what a sweep with one case per level writes besides its own files (Table 5, the paper comparison)
SWEEP_TABLES = "rotorcosim.cases.blade_loss.paper_comparison:sweep_tables"
