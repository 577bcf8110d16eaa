"""Scenarios: a system, its parameters and its schedule as data (TOML or SSP), checked before anything runs.

- :mod:`.build`: :class:`Scenario`, :func:`load_scenario`, and the system / simulation built from a scenario;
- :mod:`.schema`: the checks of a scenario file, each error naming the file, table and key; its tables and keys
  (:mod:`.tables`), value checkers (:mod:`.checkers`), the line of a key (:mod:`.key_lines`) and the checks of
  ``[schedule]`` (:mod:`.schedule_check`);
- :mod:`.compose`: ``[scenario] extends = ...`` (a scenario stating only what it changes);
- :mod:`.overrides`: ``--set comp.param=value`` and ``--swap comp=IMPL`` (and their API forms);
- :mod:`.ssp`: SSP 1.0 archives written from a scenario and read into one.

::

    from rotorcosim.master.scenario import load_scenario
    sc = load_scenario("scenarios/toy_thermomechanical.toml").set({"osc.F0": 20.0})
"""
from rotorcosim.master.scenario.build import (ComponentSpec, Scenario, ScenarioError, build_simulation,
                                              build_system, create_component, load_scenario, schedule_of)

__all__ = ["ComponentSpec", "Scenario", "ScenarioError", "build_simulation", "build_system",
           "create_component", "load_scenario", "schedule_of"]
