"""``rotorcosim export-ssp [SCENARIO] --out FILE.ssp``: a scenario's whole system as an SSP 1.0 archive.

The archive holds SystemStructure.ssd and one FMU per component (master/scenario/ssp.py); ``rotorcosim run FILE.ssp``
runs it again in our master, and other SSP engines (Ecos) run it too. The older form
``rotorcosim export-ssp FILE.ssp [SCENARIO]`` keeps working.
"""
from __future__ import annotations

from pathlib import Path

from rotorcosim.master.cli.options import add_out, add_scenario

#: the archive names its system after the scenario, so the default stays the levels' base file
DEFAULT_SCENARIO = "blade_loss"


def add_arguments(parser):
    """The command's options on ``parser``."""
    add_scenario(parser, DEFAULT_SCENARIO, output_first=True,
                 note="the levels' base file, F_u = 2850 N as in blade_loss_2850 that run uses; the archive "
                      "carries its name")
    add_out(parser, "the SSP archive to write (FILE.ssp)", positional_alias="FILE.ssp")


def run(args) -> int:
    """Write the archive of ``args.scenario`` to ``args.out``; prints one line; returns 0."""
    from rotorcosim.master.cli.run import resolve
    from rotorcosim.master.scenario.ssp import write_ssp

    sc = resolve(args.scenario)
    path = write_ssp(sc, Path(args.out))
    print(f"{sc.name}: {len(sc.components)} components, {len(sc.connections)} connections -> {path}")
    return 0
