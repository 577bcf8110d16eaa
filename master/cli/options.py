"""The options every command spells the same way, defined once.

- The scenario is the optional positional ``SCENARIO`` (a shipped name, a TOML file or an ``.ssp`` archive) of
  every command that takes one; ``--scenario SCENARIO`` says the same (an error when both are given and differ).
- The output is ``--out``. The export commands also take it as their first positional, their older form
  (``export-fmus DIR``, ``export-ssp FILE.ssp [SCENARIO]``); giving it both ways is an error.
- ``--schedule`` has one help text (:data:`SCHEDULE_HELP`).

:func:`finish` turns the parsed spellings into ``args.scenario`` and ``args.out``; the ``rotorcosim`` program
(:func:`rotorcosim.master.cli.program.main`) calls it before a command runs, so a command reads only those two.

Example (the export command's older form and its current one give the same ``args``):

>>> p = argparse.ArgumentParser(prog="rotorcosim export-fmus")
>>> add_scenario(p, "toy_thermomechanical", output_first=True)
>>> add_out(p, "output folder", positional_alias="DIR")
>>> argvs = (["fmus_out"], ["toy_thermomechanical", "--out", "fmus_out"])
>>> old, new = (finish(p.parse_args(argv)) for argv in argvs)
>>> (old.scenario, old.out) == (new.scenario, new.out) == ("toy_thermomechanical", "fmus_out")
True
"""
from __future__ import annotations

import argparse
from pathlib import Path

#: ``--schedule`` of every command that runs a scenario
SCHEDULE_HELP = ("scenario: the scenario's own schedule (a case may add aliases of it, master/case.py); auto: "
                 "switch TM/TO automatically; monolithic: one TM interval")

#: what a SCENARIO may be
SCENARIO_KINDS = 'scenario TOML file, shipped scenario name or .ssp archive ("rotorcosim scenarios" lists them)'


def add_scenario(p: argparse.ArgumentParser, default: str | None, *, shown: str | None = None,
                 note: str = "", output_first: bool = False) -> None:
    """The positional ``SCENARIO`` and its alias ``--scenario``.

    Parameters: ``p`` the command's parser; ``default`` the scenario when neither is given (None: the API's
    default, :func:`rotorcosim.load_scenario`); ``shown`` the default's name in the help when ``default`` is None;
    ``note`` a sentence appended to the help (why this command's default is what it is); ``output_first``:
    the command's older form ``OUTPUT [SCENARIO]`` (with :func:`add_out`'s ``positional_alias``) is accepted.
    """
    name = default if default is not None else shown
    text = f"{SCENARIO_KINDS}; default: {name}" + (f" ({note})" if note else "")
    p.add_argument("scenario", nargs="?", default=None, metavar="SCENARIO", help=text)
    if output_first:  # the older form's second positional (OUTPUT SCENARIO)
        p.add_argument("scenario_second", nargs="?", default=None, help=argparse.SUPPRESS)
    p.add_argument("--scenario", dest="scenario_option", default=None, metavar="SCENARIO",
                   help="the same as the positional SCENARIO (an error when both are given and differ)")
    p.set_defaults(scenario_default=default)


def add_out(p: argparse.ArgumentParser, what: str, *, positional_alias: str | None = None) -> None:
    """``--out`` (required), described as ``what``. ``positional_alias``: the command's older form named the
    output as its first positional (metavar given here, e.g. ``DIR``); it keeps working."""
    if positional_alias is None:
        p.add_argument("--out", required=True, metavar="DIR", help=what)
        return
    p.add_argument("--out", default=None, metavar=positional_alias,
                   help=f"{what}; required (the older form gives it as the first positional: "
                        f"{p.prog} {positional_alias} [SCENARIO])")
    p.set_defaults(out_positional=positional_alias)


def _is_scenario(word: str) -> bool:
    """True when ``word`` names a shipped scenario or an existing TOML file: not an output's name."""
    from rotorcosim import scenarios

    if len(Path(word).parts) == 1 and (scenarios.FOLDER / f"{word}.toml").is_file():
        return True
    return word.lower().endswith(".toml") and Path(word).is_file()


def _may_be_scenario(word: str) -> bool:
    """True when ``word`` could be a scenario: :func:`_is_scenario`, a TOML or SSP name, or an existing file."""
    return _is_scenario(word) or Path(word).suffix.lower() in (".toml", ".ssp") or Path(word).is_file()


def finish(args: argparse.Namespace) -> argparse.Namespace:
    """``args.scenario`` and ``args.out`` from the spellings :func:`add_scenario` and :func:`add_out` define;
    a ValueError (exit status 2) names a contradiction. A namespace without them is returned as it is."""
    if not hasattr(args, "scenario_option"):
        return args
    first, second, option = args.scenario, getattr(args, "scenario_second", None), args.scenario_option
    alias = getattr(args, "out_positional", None)
    if alias is not None and args.out is None:
        # the older form: OUTPUT [SCENARIO]
        if first is None:
            raise ValueError(f"give the output: --out {alias}")
        if second is None and option is None and _is_scenario(first):
            raise ValueError(f"{first!r} is a scenario; give the output with --out {alias} "
                             f"(or name it first: {alias} {first})")
        args.out, first, second = first, second, None
    elif alias is not None and first is not None and (second is not None or not _may_be_scenario(first)):
        raise ValueError(f"the output is given twice (--out {args.out} and {first!r}); with --out, "
                         f"the one positional is the SCENARIO")
    if second is not None:
        raise ValueError(f"unexpected {second!r} after the SCENARIO {first!r}")
    if first is not None and option is not None and first != option:
        raise ValueError(f"two scenarios, {first!r} and --scenario {option!r}: give one")
    args.scenario = first if first is not None else option if option is not None else args.scenario_default
    return args


def add_dpi(p: argparse.ArgumentParser) -> None:
    """``--dpi``: the resolution of the PNG figures a command writes."""
    from rotorcosim.master.run.outputs import DPI_RANGE, FIGURE_DPI

    p.add_argument("--dpi", type=float, default=None, metavar="N",
                   help=f"resolution of the PNG figures in dots per inch (default {FIGURE_DPI}; "
                        f"{DPI_RANGE[0]}-{DPI_RANGE[1]})")


def finish_part(args: argparse.Namespace) -> argparse.Namespace:
    """``args.parameters`` of the commands that evaluate one part of an engine (``bearing-static``,
    ``damper-force``, ``thermal-steady``): the parameters component ``<part><ID>`` takes from ``--engine FILE``
    or ``--scenario SCENARIO`` (master/scenario/engine.py), None when neither is given (the shipped engine's records by
    number). A namespace of another command is returned as it is."""
    part = getattr(args, "part", None)
    if part is None:
        return args
    kind, attr = part
    pid = str(getattr(args, attr))
    engine, scenario = getattr(args, "engine", None), getattr(args, "part_scenario", None)
    if engine and scenario:
        raise ValueError("give --engine FILE or --scenario SCENARIO, not both")
    from rotorcosim.master.scenario.engine import part_parameters

    if scenario:
        from rotorcosim.master.api import load_scenario

        sc = load_scenario(scenario)
        args.parameters = part_parameters(f"{kind}{pid}", scenario=sc)
        impl = sc.components[f"{kind}{pid}"].implementation
        if impl is not None and not impl.startswith(f"{kind}."):
            # a plug-in's parameters given to the project's model of that part failed there, naming a variable
            raise ValueError(f"--scenario {scenario}: {kind}{pid} is {impl}, not one of rotorcosim's {kind} models "
                             f"({kind}.*), which this command evaluates")
    elif engine:
        if not Path(engine).is_file():
            raise FileNotFoundError(f"--engine {engine}: no such file")
        args.parameters = part_parameters(f"{kind}{pid}", engine=engine)
    else:
        args.parameters = None
    return args
