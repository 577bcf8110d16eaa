"""The ``rotorcosim`` command line.

Each sub-command lives in the module that owns its subject and offers ``add_arguments(parser)`` and
``run(args) -> int``; this table only names them, so a component's command is imported only when used.
"""
from __future__ import annotations

import argparse
import atexit
import gc
import importlib
import re
import shutil
import sys
import textwrap
import traceback

#: the master's own commands; each case adds its own (rotorcosim.master.case, ``COMMANDS``): see :func:`commands`
COMMANDS: dict[str, tuple[str, str]] = {
    "scenarios": ("rotorcosim.master.cli.scenarios", "list the shipped scenarios, one line each"),
    "run": ("rotorcosim.master.cli.run", "run a scenario (TOML or SSP; by default the shipped case's main job)"),
    "sweep": ("rotorcosim.master.cli.sweep", "run a scenario at several levels or parameter values in parallel on "
                                             "Dask, with its case's tables"),
    "calibrate": ("rotorcosim.master.cli.calibrate", "fit a few parameters to measured results (bounded least "
                                                     "squares, runs on Dask, resumable)"),
    "uq": ("rotorcosim.master.cli.uq", "uncertainty of the results over parameter distributions (Monte Carlo, "
                                       "Latin hypercube, Sobol' indices; runs on Dask, resumable)"),
    "bearing-static": ("rotorcosim.components.bearing.cli", "static load distribution of a ball bearing"),
    "damper-force": ("rotorcosim.components.damper.cli", "squeeze film damper force at a journal position and velocity"),
    "thermal-steady": ("rotorcosim.components.thermal.cli", "steady state of a bearing's thermal network"),
    "export-fmus": ("rotorcosim.master.cli.export_fmus", "export components as FMI 2.0 co-simulation FMUs"),
    "export-ssp": ("rotorcosim.master.cli.export_ssp", "export a scenario's system as an SSP 1.0 archive"),
    "import-ross": ("rotorcosim.interop.cli", "a rotor saved by ROSS (Rotor.save TOML) as an engine file"),
    "parameters": ("rotorcosim.master.cli.parameters", "every parameter of a scenario's components (or of one "
                                                       "component or implementation): unit, default, value, source"),
}


def commands() -> dict[str, tuple[str, str]]:
    """Every command of the program: the master's own, then the cases' (a case cannot replace one of the
    master's)."""
    from rotorcosim.master import case

    out = dict(COMMANDS)
    for name, entry in case.commands().items():
        out.setdefault(name, entry)
    return out


#: the top-level ``--help``: what the program does (plain text, one paragraph)
DESCRIPTION = ("Co-simulation of a dual-rotor gas turbine engine through a transient and long after it: a rotor, "
               "ball bearings, squeeze film dampers, rub rings and the bearings' thermal networks coupled by a "
               "master that alternates thermo-mechanical and thermal-only intervals. Run a scenario (a shipped "
               "name, a TOML file or an SSP archive) and get its results, time series and figures in an output "
               "folder; sweep parameters in parallel; export components as FMUs or a whole system as SSP.")
#: the top-level ``--help``'s closing paragraphs: where to read on, and the exit statuses
EPILOG = ("A command's options: rotorcosim COMMAND --help. A command that takes a scenario takes it as its "
          "positional SCENARIO (or --scenario SCENARIO) and writes into --out DIR (export-ssp: --out FILE.ssp). "
          "Documentation: README.md and docs/ in the source repository.",
          "Errors: one line and exit status 2 for a mistake in the input, 1 for a run that failed, 130 for an "
          "interrupted run; --debug (anywhere on the line) shows the traceback.")

#: what the command line takes for a negative number rather than an option: argparse's own pattern knows only -5
#: and -.5, so ``--position -1e-5 0`` failed with "expected 2 arguments" and ``--duration -inf`` with "expected
#: one argument" (no option of rotorcosim starts with a digit, "inf" or "nan")
NEGATIVE_NUMBER = re.compile(r"^-(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$|^-(inf|infinity|nan)$", re.IGNORECASE)
#: what a negative number is shielded with from argparse: a word that does not start with "-" is a value, and
#: float() and int() ignore the leading space (removed again from the values kept as text: :func:`_unshield`)
_SHIELD = " "


def _shield(argv: list[str]) -> list[str]:
    return [_SHIELD + a if NEGATIVE_NUMBER.match(a) else a for a in argv]


def _unshield_value(v):
    if isinstance(v, str) and v.startswith(_SHIELD) and NEGATIVE_NUMBER.match(v[len(_SHIELD):]):
        return v[len(_SHIELD):]
    if isinstance(v, list):
        return [_unshield_value(x) for x in v]
    return v


def _unshield(args: argparse.Namespace) -> argparse.Namespace:
    for key, value in vars(args).items():
        setattr(args, key, _unshield_value(value))
    return args


class _Parser(argparse.ArgumentParser):
    """An option mistake is one line, as every other error (argparse prints the whole usage first); the
    sub-commands' parsers are of this class too (add_subparsers takes the parser's own class)."""

    def error(self, message):
        self.exit(2, f"{self.prog}: error: {' '.join(message.split())} (see: {self.prog} --help)\n")


def build_parser() -> argparse.ArgumentParser:
    """The program's parser: the top-level options and one sub-parser per command; only the command named first
    on ``sys.argv`` gets its options (its module is imported then)."""
    from rotorcosim import __version__

    width = max(40, min(100, shutil.get_terminal_size().columns - 2))
    parser = _Parser(prog="rotorcosim", description=textwrap.fill(DESCRIPTION, width),
                     epilog="\n\n".join(textwrap.fill(par, width) for par in EPILOG),
                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--debug", action="store_true", help="show the traceback of an error")
    parser.add_argument("--version", action="version", version=f"rotorcosim {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    argv = sys.argv[1:]
    table = commands()
    for name, (module, help_text) in table.items():
        p = sub.add_parser(name, help=help_text, description=help_text)
        # import a command's module only when it is the one asked for (keeps start-up fast)
        if argv and argv[0] == name:
            importlib.import_module(module).add_arguments(p)
    return parser


#: the collector's first threshold in a command's own process (Python's default: 700 allocations). Start-up
#: (numba's registries, the components' models) allocates millions of long-lived objects, on which the default
#: ran 2 full collections that found nothing to free (0.18-0.28 s of the main job at load 4); the run itself makes
#: little cyclic garbage, so collecting less often costs no memory that matters
GC_THRESHOLD0 = 50_000


def _command_process() -> None:
    """Settings for a process that runs one command (the ``rotorcosim`` program, ``python -m``), not for a
    program that calls :func:`main` among other work: fewer collections, and every object frozen at exit, so
    that the interpreter's final collections skip them (every file is closed by then; Python does not promise
    finalizers of objects alive at exit anyway). Measured on the main job at load ~4: the exit took 1.4-1.7 s
    after the results were written, 0.15-0.2 s with the freeze."""
    gc.set_threshold(GC_THRESHOLD0, *gc.get_threshold()[1:])
    atexit.register(gc.freeze)  # registered first, so it runs after the handlers of what the command imports


#: errors caused by what the user gave (input files, options, folders): exit status 2
USER_ERRORS = (ValueError, LookupError, FileNotFoundError, IsADirectoryError, NotADirectoryError, FileExistsError)


def describe_error(exc: BaseException) -> tuple[int, str]:
    """(exit status, one-line message) for an error that ended a command."""
    if isinstance(exc, USER_ERRORS):
        return 2, str(exc) or type(exc).__name__
    if isinstance(exc, OSError):  # the environment: disk full, permissions, I/O
        where = f" ({exc.filename})" if exc.filename else ""
        return 1, f"{exc.strerror or exc}{where}"
    if isinstance(exc, MemoryError):
        return 1, "out of memory"
    if isinstance(exc, RuntimeError) and type(exc).__module__.startswith("rotorcosim"):
        # a run's failure says first what happened (algorithm.SimulationFailed.line: diverged, timed out...)
        line = getattr(exc, "line", None)
        return 1, line() if callable(line) else str(exc)
    return 1, f"unexpected {type(exc).__name__}: {exc} (rerun with --debug for the traceback; it may be a bug)"


def main(argv: list[str] | None = None) -> int:
    """Run the command line ``argv``; None: this process's own (``sys.argv``), the process being the command's."""
    if argv is None:
        _command_process()
    argv = list(sys.argv[1:] if argv is None else argv)
    # --debug may stand anywhere on the line
    debug = "--debug" in argv
    argv = [a for a in argv if a != "--debug"]
    sys.argv = [sys.argv[0], *argv]
    parser = build_parser()
    args = _unshield(parser.parse_args(_shield(argv)))
    if not args.command:
        parser.print_help()
        return 2
    try:
        from rotorcosim.master.cli.options import finish, finish_part

        finish(args)   # SCENARIO / --scenario and the output's spellings (cli/options.py)
        finish_part(args)   # an engine part's parameters: --engine FILE or --scenario with --bearing ID
        module = importlib.import_module(commands()[args.command][0])
        from rotorcosim.master.core.threads import one_thread

        with one_thread():  # the same numbers whatever the calling program imported first (threads.py)
            return int(module.run(args) or 0)
    except KeyboardInterrupt as exc:
        if debug:
            traceback.print_exc()
        # a command that says what its interruption kept (a sweep: its cases) raises its own subclass; the sweep's
        # module is looked up, not imported (a command that ran no sweep does not load Dask to say so)
        sweep = sys.modules.get("rotorcosim.master.sweep.engine")
        said = str(exc) if sweep is not None and isinstance(exc, sweep.SweepInterrupted) else ""
        print(f"rotorcosim {args.command}: {said or 'interrupted'}", file=sys.stderr)
        return 130
    except Exception as exc:
        status, text = describe_error(exc)
        if debug:
            traceback.print_exc()
        print(f"rotorcosim {args.command}: error: {' '.join(text.split())}", file=sys.stderr)
        return status


if __name__ == "__main__":
    sys.exit(main())
