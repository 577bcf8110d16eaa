"""``rotorcosim export-fmus DIR [--component NAME] [--scenario SCENARIO]``: components as FMI 2.0 CS FMUs.

Each component of the scenario (default: the blade-loss scenario) is written to ``DIR/<component>.fmu`` with the
scenario's parameters baked in as the parameters' start values (fmus/export.py). The FMUs pass
``fmpy.validation.validate_fmu`` (checked after writing; a problem is an error, not a warning).
"""
from __future__ import annotations

from pathlib import Path

DEFAULT_SCENARIO = "blade_loss"


def add_arguments(parser):
    parser.add_argument("dir", help="output folder (created if missing)")
    parser.add_argument("--component", default=None, metavar="NAME",
                        help="export only this component of the scenario (default: all)")
    parser.add_argument("--scenario", default=DEFAULT_SCENARIO,
                        help=f"scenario TOML file, shipped scenario name or .ssp archive (default: {DEFAULT_SCENARIO})")


def run(args) -> int:
    from fmpy.validation import validate_fmu

    from rotorcosim.master.cli.run import resolve

    from rotorcosim.master.scenario.export import export_scenario

    from rotorcosim.master.run.rundir import check_folder

    check_folder(args.dir, "output folder")   # "" would become Path("."): the FMUs were written where it ran
    sc = resolve(args.scenario)
    written = export_scenario(sc, Path(args.dir), args.component)
    for name, path in written.items():
        problems = validate_fmu(str(path))
        if problems:
            path.unlink()   # an FMU other tools may reject is not left behind as if it were good
            raise ValueError(f"{path} does not pass fmpy's validation (removed): " + "; ".join(problems))
        print(f"{name}: {path}")
    return 0
