"""The options of the commands that evaluate one part of an engine (``bearing-static``, ``damper-force``,
``thermal-steady``): which part, and the engine file or scenario it comes from (the command line resolves them
into the part's parameters: master/cli/options.py, ``finish_part``)."""
from __future__ import annotations


def add_part_arguments(parser, component: str, selector: str, part: str, engine_help: str) -> None:
    """``--SELECTOR ID`` (the part's id), ``--engine FILE`` (``engine_help``) and ``--scenario SCENARIO`` (whose
    component ``COMPONENT<ID>`` gives the ``part``)."""
    parser.add_argument(f"--{selector}", required=True, metavar="ID",
                        help=f"the {selector}'s id in the engine (--engine or --scenario); alone, 0 or 5: the "
                             f"paper's Table 3 {selector}")
    parser.add_argument("--engine", metavar="FILE", help=engine_help)
    parser.add_argument("--scenario", dest="part_scenario", metavar="SCENARIO",
                        help=f"a scenario whose component {component}<ID> gives the {part}")
    parser.set_defaults(part=(component, selector))


def part_id(text: str):
    """A part's id: an integer when it is one (the paper's 0 and 5), else the text."""
    return int(text) if text.isdigit() else text
