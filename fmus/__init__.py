"""The FMI boundary: components out as FMI 2.0 co-simulation FMUs, systems out as SSP 1.0, both back in.

Modules:

* ``export``: one registered component (with parameters) -> ``.fmu`` built by pythonfmu; a scenario's components;
* ``slave_template``: the generic pythonfmu slave copied into every FMU (it imports nothing from rotorcosim);
* ``bundle``: the component's code copied into the FMU under a private package name;
* ``model_description``: pythonfmu's modelDescription.xml finished (units, InitialUnknowns, vendor annotation,
  deterministic GUID) and our annotation read back;
* ``flatten`` / ``units``: vector ports <-> ``X[1]..X[n]`` scalars; SI unit strings -> FMI unit definitions;
* ``importer``: any FMI 2.0 co-simulation FMU -> a contract component (``load_fmu_component``);
* ``safezip``: archive extraction that cannot write outside a fresh temporary folder;
* ``ssp``: ``write_ssp`` / ``read_ssp`` (SystemStructure.ssd + FMUs);
* ``cli_export`` / ``cli_ssp``: ``rotorcosim export-fmus`` and ``rotorcosim export-ssp``.

What an exported FMU carries besides standard FMI: ``<DefaultExperiment stepSize>`` is the component's preferred
communication step, and ``<VendorAnnotations><Tool name="rotorcosim"><Component implementation=... phases="TM"
or "TM,TO" preferredStep=... package=... slaveModule=... phaseInput="_rcs_phase" phasesOutput="_rcs_phases"/>``
tells our importer the phases it takes part in and names two Integer variables that are not ports: the schedule
phase in (0 TM, 1 TO: the component's ``enter_phase``) and, after set-up, the phases the component chose (bits
1 TM, 2 TO, 4 ``holds_state_in_TO``). Other FMUs default to ``{"TM"}`` (mechanical: frozen in thermal-only
intervals); other tools leave the phase input at 0 (always thermo-mechanical).
"""
