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
or "TM,TO" preferredStep=... package=... slaveModule=.../>`` tells our importer the phases it takes part in (other
FMUs default to ``{"TM"}``: mechanical, frozen in thermal-only intervals).
"""
