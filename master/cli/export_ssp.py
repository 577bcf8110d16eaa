"""``rotorcosim export-ssp [SCENARIO] --out FILE.ssp``: a scenario's whole system as an SSP 1.0 archive.

The archive holds SystemStructure.ssd and one FMU per component (master/scenario/ssp.py); ``rotorcosim run FILE.ssp``
runs it again in our master, and other SSP engines (Ecos) run it too. The older form
``rotorcosim export-ssp FILE.ssp [SCENARIO]`` keeps working.
"""
from __future__ import annotations

from pathlib import Path

from rotorcosim.master import case
from rotorcosim.master.cli.options import add_out, add_scenario


def add_arguments(parser):
    """The command's options on ``parser``. The archive names its system after the scenario, so the default is
    the base file a case declares for its levels (:func:`rotorcosim.master.case.default_scenario`)."""
    add_scenario(parser, case.default_scenario(), output_first=True,
                 note="the base file of the levels a case declares; the archive carries its name")
    add_out(parser, "the SSP archive to write (FILE.ssp)", positional_alias="FILE.ssp")


def run(args) -> int:
    """Write the archive of ``args.scenario`` to ``args.out``; prints one line; returns 0."""
    from rotorcosim.master.cli.run import resolve
    from rotorcosim.master.scenario.ssp import write_ssp

    if not str(args.out).strip():   # Path("") is ".", which the archive check named instead
        raise ValueError("--out is empty: give the SSP archive to write (FILE.ssp)")
    sc = resolve(args.scenario)
    path = write_ssp(sc, Path(args.out))
    print(f"{sc.name}: {len(sc.components)} components, {len(sc.connections)} connections -> {path}")
    return 0
