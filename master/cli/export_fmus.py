"""``rotorcosim export-fmus [SCENARIO] --out DIR [--component NAME]``: components as FMI 2.0 CS FMUs.

Each component of the scenario (default: `run`'s) is written to ``DIR/<component>.fmu`` with the
scenario's parameters baked in as the parameters' start values (fmus/export.py). The FMUs pass
``fmpy.validation.validate_fmu`` (checked after writing; a problem is an error, not a warning). The older form
``rotorcosim export-fmus DIR [--scenario SCENARIO]`` keeps working.
"""
from __future__ import annotations

from pathlib import Path

from rotorcosim.master.api import DEFAULT_SCENARIO
from rotorcosim.master.cli.options import add_out, add_scenario


def add_arguments(parser):
    """The command's options on ``parser``."""
    # the default as `run`'s: a level's scenario and its base file give the same FMU bytes (same parameters)
    add_scenario(parser, None, shown=DEFAULT_SCENARIO, output_first=True)
    add_out(parser, "output folder (created if missing)", positional_alias="DIR")
    parser.add_argument("--component", default=None, metavar="NAME",
                        help="export only this component of the scenario (default: all)")


def run(args) -> int:
    """Export the FMUs of ``args.scenario`` into ``args.out``; prints one line per FMU; returns 0."""
    from fmpy.validation import validate_fmu

    from rotorcosim.master.cli.run import resolve
    from rotorcosim.master.run.rundir import check_folder
    from rotorcosim.master.scenario.export import export_scenario

    check_folder(args.out, "output folder")   # "" would become Path("."): the FMUs were written where it ran
    sc = resolve(args.scenario)
    written = export_scenario(sc, Path(args.out), args.component)
    for name, path in written.items():
        problems = validate_fmu(str(path))
        if problems:
            path.unlink()   # an FMU other tools may reject is not left behind as if it were good
            raise ValueError(f"{path} does not pass fmpy's validation (removed): " + "; ".join(problems))
        print(f"{name}: {path}")
    return 0
