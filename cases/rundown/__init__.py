"""The rundown case: a rotor whose spools change speed (components/spool), read as an engine-dynamics engineer
reads a rundown: the speed of each spool against time, each critical-speed crossing (the time, the speed where
the response peaks, the peak whirl, contact load, contact stress and transmitted force at each location), the
spools' energy balance, and for the blade-loss engine the Table 4 results at the end (cases/blade_loss).

- :mod:`.results`: ``summary.json`` keys ``speeds``, ``crossings``, ``energy`` (and ``bearings`` for the engine);
- :mod:`.modes`: the critical speeds a crossing is labelled with (the linearised engine's, per film temperature);
- :mod:`.energy`: the spools' energy balance from the torques the components report;
- :mod:`.fatigue`: the fatigue content of named loads (damage-equivalent loads, Miner damage; held intervals
  counted from the hold's window);
- :mod:`.figures`: speed against time with the thermal-only intervals shaded, whirl and transmitted force against
  speed, the Campbell diagram with the run's trajectory, the temperatures;
- :mod:`.compare`: ``rotorcosim compare blade_loss_rundown``, the staggered scheme against the monolithic run
  over the rundown and 10 minutes of windmilling (``compare_rundown``).

Scenarios: ``jeffcott_rundown`` (the check case against an independent integration) and ``blade_loss_rundown``.
"""

from rotorcosim.cases import blade_loss
from rotorcosim.master.scenario import checkers

from . import fuse_comparison

#: the result extraction of the scenarios whose ``[results] kind`` is ``"rundown"`` (rotorcosim.master.case)
RESULTS = "rotorcosim.cases.rundown.results"
#: ``rotorcosim compare`` for the scenarios of this case (master/case.py ``COMPARE``)
COMPARE = "rotorcosim.cases.rundown.compare:run"
#: the level: the blade-loss engine's unbalance force (``[results] unbalance_parameter``, ``--unbalance``), as the
#: blade-loss case's; a rundown of a scenario without that key (a test rotor) has no level to set
LEVEL = blade_loss.LEVEL
#: the steepest S-N curve accepted (``[results] woehler_exponent``): slopes are 3 to 5 for steel details (EN 1993-1-9)
#: and up to ~20 for some materials; the damage-equivalent load sums S^m, which overflows a float beyond ~100 for
#: loads of kN (its value came out null, with numpy's overflow warning)
MAX_WOEHLER_EXPONENT = 50.0


def woehler_exponent(v) -> str | None:
    """A finite S-N slope m in (0, :data:`MAX_WOEHLER_EXPONENT`]."""
    err = checkers.positive(v)
    if err is None and v > MAX_WOEHLER_EXPONENT:
        return (f"must be at most {MAX_WOEHLER_EXPONENT:g} (the S-N curve's slope m: 3 to 5 for steel details, "
                f"EN 1993-1-9; the loads' S^m overflows beyond), got {v!r}")
    return err


#: the case's own ``[results]`` keys: the spool components whose speeds and crossings it reports, the critical
#: speeds whose crossings it reports [rev/min]; the blade-loss engine's level when it runs that engine; the loads
#: whose fatigue content it reports and the S-N settings
RESULTS_KEYS = {"spools": checkers.list_of(checkers.text), "critical_speeds_rpm": checkers.list_of(checkers.positive),
                "unbalance_parameter": checkers.port_ref,
                # the fatigue content of loads (cases/rundown/fatigue.py: defaults and sources)
                "fatigue_loads": checkers.list_of(checkers.port_ref), "woehler_exponent": woehler_exponent,
                "reference_cycles": checkers.positive, "sn_range_N": checkers.positive,
                "sn_cycles": checkers.positive,
                # the airframe component whose interface loads summary.json reports (cases/interface/results.py;
                # default: the component named "airframe", else the scenario's one airframe.modal)
                "airframe": checkers.text,
                # a run with a support fuse beside the same scenario without it (cases/rundown/fuse_comparison.py)
                "casing_force_peak": checkers.boolean, "without_fuse": checkers.text,
                "without_fuse_set": fuse_comparison.settings}
