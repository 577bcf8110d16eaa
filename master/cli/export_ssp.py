"""``rotorcosim export-ssp FILE.ssp [SCENARIO]``: a scenario's whole system as an SSP 1.0 archive.

The archive holds SystemStructure.ssd and one FMU per component (master/scenario/ssp.py); ``rotorcosim run FILE.ssp``
runs it again in our master, and other SSP engines (Ecos) run it too.
"""
from __future__ import annotations

from pathlib import Path

DEFAULT_SCENARIO = "blade_loss"


def add_arguments(parser):
    parser.add_argument("file", help="the SSP archive to write (FILE.ssp)")
    parser.add_argument("scenario", nargs="?", default=DEFAULT_SCENARIO,
                        help=f"scenario TOML file or shipped scenario name (default: {DEFAULT_SCENARIO})")


def run(args) -> int:
    from rotorcosim.master.cli.run import resolve

    from rotorcosim.master.scenario.ssp import write_ssp

    sc = resolve(args.scenario)
    path = write_ssp(sc, Path(args.file))
    print(f"{sc.name}: {len(sc.components)} components, {len(sc.connections)} connections -> {path}")
    return 0
