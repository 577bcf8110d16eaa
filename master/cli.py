"""The ``rotorcosim`` command line.

Each sub-command lives in the module that owns its subject and offers ``add_arguments(parser)`` and
``run(args) -> int``; this table only names them, so a component's command is imported only when used.
"""
from __future__ import annotations

import argparse
import importlib
import sys

COMMANDS: dict[str, tuple[str, str]] = {
    "run": ("rotorcosim.master.commands.run", "run a scenario (TOML or SSP), the 2850 N blade-loss case by default"),
    "sweep": ("rotorcosim.master.commands.sweep", "run several unbalance levels in parallel on Dask, write table5.csv"),
    "compare": ("rotorcosim.master.commands.compare", "the paper's Table 6: staggered against monolithic"),
    "critical-speeds": ("rotorcosim.components.rotor.cli", "synchronous critical speeds and Campbell diagram of the rotor"),
    "bearing-static": ("rotorcosim.components.bearing.cli", "static load distribution of bearing #0 or #5"),
    "damper-force": ("rotorcosim.components.damper.cli", "squeeze film damper force at a journal position and velocity"),
    "thermal-steady": ("rotorcosim.components.thermal.cli", "steady state of a bearing's thermal network"),
    "export-fmus": ("rotorcosim.fmus.cli_export", "export components as FMI 2.0 co-simulation FMUs"),
    "export-ssp": ("rotorcosim.fmus.cli_ssp", "export a scenario's system as an SSP 1.0 archive"),
}


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="rotorcosim", description=__doc__.splitlines()[0])
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    argv = sys.argv[1:]
    for name, (module, help_text) in COMMANDS.items():
        p = sub.add_parser(name, help=help_text, description=help_text)
        # import a command's module only when it is the one asked for (keeps start-up fast)
        if argv and argv[0] == name:
            importlib.import_module(module).add_arguments(p)
    return parser


def main(argv: list[str] | None = None) -> int:
    if argv is not None:
        sys.argv = [sys.argv[0], *argv]
    parser = build_parser()
    args = parser.parse_args()
    if not args.command:
        parser.print_help()
        return 2
    module = importlib.import_module(COMMANDS[args.command][0])
    try:
        return int(module.run(args) or 0)
    except (ValueError, FileNotFoundError, KeyError) as exc:
        # bad input: one clear line, no traceback
        print(f"rotorcosim {args.command}: error: {exc}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
