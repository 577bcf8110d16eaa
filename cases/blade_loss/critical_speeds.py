"""``rotorcosim critical-speeds``: synchronous critical speeds (and Campbell diagram) of the rotor model.

The gas generator turns at the scenario's speed ratio (15 000 / 16 000) of the power turbine; the co-simulated
bearings (#0 and #5 of the paper's engine, every [attach] bearing<ID> of another) are the system linearised (rotorcosim.cases.blade_loss.linear_engine: ball contacts at the preloaded rest, the
outer race + journal body of eq. 5, O-ring, film at the stated oil temperature), the one engine model the
calibration uses. ``--json`` reports it under ``support_model``. (A master command: the system's linearisation
takes the bearing and damper components, which the rotor package, bundled alone into its FMU, may not import.)
"""
from __future__ import annotations

import itertools

import json
import os
from pathlib import Path

import numpy as np

from rotorcosim.components.airframe.installed import installed_model
from rotorcosim.components.rotor import attach, critical, engine_check
from rotorcosim.components.rotor import model as fem
from rotorcosim.components.rotor.engine_shape import refuse
from rotorcosim.cases.blade_loss import linear_engine, response_peaks


def add_arguments(parser):
    """The options of ``rotorcosim critical-speeds`` on ``parser``."""
    parser.add_argument("--model", "--model-file", dest="model_file", default="", metavar="FILE",
                        help="engine file (TOML, docs/reference/engine-format.md); default: the engine of "
                             "--scenario, else the paper's engine")
    parser.add_argument("--scenario", default=None, metavar="SCENARIO",
                        help="the scenario whose bearing and damper components linearise the attached bearings "
                             "(default: the shipped blade-loss scenario)")
    parser.add_argument("--count", type=int, default=6, metavar="N", help="how many of each kind to list (default 6)")
    parser.add_argument("--json", action="store_true", help="print a JSON object")
    parser.add_argument("--campbell", metavar="FILE.png", help="also draw the Campbell diagram into this file")
    parser.add_argument("--max-rpm", type=float, default=30000.0, metavar="RPM",
                        help="highest power-turbine speed of the Campbell diagram and the list (default 30000)")
    parser.add_argument("--oil-temperature", type=float, default=None, metavar="C",
                        help="oil temperature of the linearised film (default: the engine file's "
                             "[attach] oil_temperature_C); the undamped critical speeds do not depend on it")
    add_windmill_argument(parser)


def add_windmill_argument(parser):
    """``--windmill-rpm LO,HI``: the windmilling speeds to mark on the Campbell diagram."""
    parser.add_argument("--windmill-rpm", type=windmill_range, default=None, metavar="LO,HI",
                        help="mark this range of first-spool speeds [rev/min] on the Campbell diagram: the "
                             "windmilling speeds of a diversion (e.g. 3000,4900)")


def windmill_range(text: str) -> tuple[float, float]:
    """``"LO,HI"`` [rev/min] as a pair, 0 <= LO <= HI; else a ValueError naming the option."""
    try:
        lo, hi = (float(v) for v in str(text).split(","))
    except ValueError:
        raise ValueError(f"--windmill-rpm {text!r}: must be two speeds LO,HI in rev/min (e.g. 3000,4900)") from None
    if not (np.isfinite(lo) and np.isfinite(hi) and 0.0 <= lo <= hi):
        raise ValueError(f"--windmill-rpm {text!r}: must be 0 <= LO <= HI, finite")
    return lo, hi


#: the label of each fuse stage in the reports and on the Campbell diagram
FUSE_STAGES = ("fuse intact", "fuse broken", "fuse broken, second stage")
#: the Campbell diagram's colours of the engine after the breaks, one per combination of the fuses' stages (in turn)
FUSE_COLOURS = ("tab:purple", "tab:brown", "tab:olive", "tab:cyan", "tab:pink", "tab:gray")


def linearised_supports(m, oil_temperature, scenario=None, fuse_stage: int = 0):
    """The co-simulated bearings linearised where the engine attaches them (every [attach] bearing<ID>), or None
    for an engine that attaches none (its [[support]] entries are all its supports, e.g. a ROSS rotor); every
    fused bearing's fuse at ``fuse_stage`` (0 intact, 1 broken, 2 broken in its second stage)."""
    if not attach.layout(m.data.get("attach", {})).bearings:
        return None
    return linear_engine.supports(scenario, oil_temperature_C=oil_temperature, data=m.data, fuse_stage=fuse_stage)


def fuse_states(m, count: int, max_rpm: float, oil_temperature=None, scenario=None) -> list[dict]:
    """The synchronous critical speeds of an engine with fused bearings after the breaks: each combination of its
    fuses' stages but the all-intact one (linear_engine.fuse_combinations; one fuse: its stages in turn), as
    ``[{"stage" (the furthest fuse's), "stages" ({fuse id: stage}), "label", "forward_synchronous_rpm",
    "backward_synchronous_rpm", "fuse_stiffness_N_per_m"}]``; empty for an engine without a fuse. The intact
    engine is the report's own."""
    out = []
    combos = linear_engine.fuse_combinations(m.data)
    for stages in combos:
        sup = linearised_supports(m, oil_temperature, scenario, stages)
        stiffness = {k[1:]: v["fuse"]["k"] for k, v in sup.items() if "fuse" in v}
        stage = max(stages.values())
        label = FUSE_STAGES[stage] if len(stages) == 1 else ", ".join(
            f"{FUSE_STAGES[s].replace('fuse', f'fuse {k}', 1)}" for k, s in stages.items())
        free = [k for k, v in stiffness.items() if v == 0.0]
        try:
            crit = critical.synchronous_critical_speeds(m, sup, n=count, max_rpm=max_rpm)
            note = None
        except ValueError as exc:
            if not free or "singular" not in str(exc):
                raise
            # a soft path of stiffness 0 (k_broken's default): nothing holds the housing radially but a bumper,
            # the engine after this break has a rigid-body motion and no critical speed to list
            crit = {"forward_synchronous_rpm": [], "backward_synchronous_rpm": []}
            note = (f"not computed: fuse {', '.join('#' + k for k in free)} has stiffness 0 after this break "
                    "(nothing but a bumper holds its housing radially): the linearised engine moves freely")
        entry = {"stage": stage, "stages": dict(stages), "label": label,
                 "forward_synchronous_rpm": crit["forward_synchronous_rpm"],
                 "backward_synchronous_rpm": crit["backward_synchronous_rpm"],
                 "fuse_stiffness_N_per_m": stiffness}
        if note:
            entry["note"] = note
        out.append(entry)
    return out


def refuse_problems(data: dict, model_file: str = "") -> None:
    """A ValueError naming the engine file and the first of its problems that check-engine lists
    (components/rotor/engine_check.problems: a typo'd key of a part table, a fuse of three stages...), so that the
    critical speeds are never those of a file check-engine refuses; a shaft model file (``[shaft]``) has its own
    reader."""
    if "shaft" not in data:
        refuse(engine_check.problems(data), f"engine file {model_file or fem.DEFAULT_FILE}")


def critical_speeds(model_file: str = "", count: int = 6, max_rpm: float = 30000.0,
                    oil_temperature: float | None = None, scenario=None) -> dict:
    """The ``count`` lowest synchronous critical speeds [rev/min] of the first spool up to ``max_rpm``, of the
    engine in ``model_file`` ("": the paper's) on the linearised supports with the film at ``oil_temperature``
    [degrees C] (None: the file's), with the speed ratio, the paper's targets and the support model. The
    co-simulated bearings the file attaches are linearised from the components of ``scenario`` (a
    :class:`~rotorcosim.master.api.Scenario`; None: the shipped blade-loss scenario's); an engine that attaches
    none stands on its [[support]] entries alone. With co-simulated bearings, ``damped_critical_speeds_rpm``: per
    bearing id the speeds from half the lowest critical speed to ``max_rpm`` where the linear engine's unbalance
    response peaks there (:mod:`.response_peaks`), where a run's response peaks.

    Example: ``critical_speeds("engine.toml", count=3)["forward_synchronous_rpm"]``."""
    if count < 1:
        raise ValueError(f"--count must be >= 1, got {count}")
    if not (np.isfinite(max_rpm) and max_rpm > 0):
        raise ValueError(f"--max-rpm must be > 0, got {max_rpm}")
    m = installed_model(model_file)
    refuse_problems(m.data, model_file)
    sup = linearised_supports(m, oil_temperature, scenario)
    out = critical.synchronous_critical_speeds(m, sup, n=count, max_rpm=max_rpm)
    out["speed_ratio_gg_pt"] = critical.speed_ratio(m)
    out["spools"] = list(m.info["spools"])
    out["target_rpm"] = list(m.data.get("calibration", {}).get("target_rpm", []))
    out["model_file"] = str(model_file or fem.DEFAULT_FILE)
    out["support_model"] = linear_engine.describe(sup) if sup is not None else {
        "kind": "linear", "description": "the engine file's linear supports only (no co-simulated bearing attached)"}
    if sup is not None and out["forward_synchronous_rpm"]:
        # the speeds a run sees its response peak at (response_peaks): from half the lowest undamped critical
        # speed, below which the films' damping cannot move a peak, to max_rpm
        ref = m.omega_pt * 30.0 / np.pi
        out["damped_critical_speeds_rpm"] = response_peaks.damped_critical_speeds(
            m, sup, 0.5 * out["forward_synchronous_rpm"][0], max_rpm, ref)
    if sup is not None and fem.fuse_ids(m.data):
        out["fuse_states"] = fuse_states(m, count, max_rpm, oil_temperature, scenario)
    return out


def draw_campbell(path: str, model_file: str = "", max_rpm: float = 30000.0, crit: dict | None = None,
                  oil_temperature: float | None = None, scenario=None,
                  windmill_rpm: tuple[float, float] | None = None) -> None:
    """Draw the Campbell diagram (whirl frequencies against power-turbine speed up to ``max_rpm`` [rev/min]) into
    the PNG file ``path``; ``crit``: :func:`critical_speeds`' result, marked on it (None: none marked). An engine on
    an airframe is drawn installed (components/airframe/installed.py: the airframe's modes among the engine's);
    ``windmill_rpm``: (lo, hi) [rev/min], the windmilling speeds shaded."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    m = installed_model(model_file)
    rpm = np.linspace(0.0, max_rpm, 61)
    extra = m.info.get("airframe_modes", 0)
    f, kind = critical.campbell(m, rpm, linearised_supports(m, oil_temperature, scenario),
                                n_modes=min(80 + extra, m.n), n_show=24 + extra)
    ratio = critical.speed_ratio(m)
    fig, ax = plt.subplots(figsize=(10, 5))
    styles = ((1, "tab:blue", "forward whirl"), (-1, "tab:orange", "backward whirl"),
              (0, "0.75", "no rotor whirl (axial, torsion, casing" + (", airframe)" if extra else ")")))
    for code, colour, label in styles:
        sel = kind == code
        ax.scatter(np.broadcast_to(rpm[:, None], f.shape)[sel], f[sel], s=5, c=colour, label=label)
    ax.plot(rpm, rpm / 60.0, "k--", lw=1, label="1x first spool speed" if ratio != 1.0 else "1x spool speed")
    if ratio != 1.0:
        ax.plot(rpm, ratio * rpm / 60.0, ":", color="0.35", lw=1, label=f"1x second spool speed ({ratio:.4g} x)")
    states = (crit or {}).get("fuse_states", [])
    for st, colour in zip([st for st in states if "note" not in st], itertools.cycle(FUSE_COLOURS)):
        # the engine after the break: its whirl frequencies and critical speeds, drawn over the intact engine's
        sup = linearised_supports(m, oil_temperature, scenario, st["stages"])
        fb, kb = critical.campbell(m, rpm, sup, n_modes=min(80, m.n))
        sel = kb == 1
        ax.scatter(np.broadcast_to(rpm[:, None], fb.shape)[sel], fb[sel], s=3, c=colour, marker="x", alpha=0.6,
                   label=f"forward whirl, {st['label']}")
        r = np.asarray(st["forward_synchronous_rpm"], dtype=float)
        r = r[r <= max_rpm]
        ax.plot(r, r / 60.0, "s", mfc="none", mec=colour, ms=9, ls="none",
                label=f"forward synchronous critical speeds, {st['label']}")
        for v, text in speed_labels(r[:2], max_rpm):
            ax.annotate(text, (v, v / 60.0), textcoords="offset points", xytext=(8, 4), fontsize=8, color=colour)
    if crit:
        r = np.asarray(crit["forward_synchronous_rpm"], dtype=float)
        r = r[r <= max_rpm]
        ax.plot(r, r / 60.0, "o", mfc="none", mec="tab:red", ms=9, ls="none",
                label="forward synchronous critical speeds" + (f", {FUSE_STAGES[0]}" if crit.get("fuse_states")
                                                                else ""))
        for v, text in speed_labels(r[:2], max_rpm):
            ax.annotate(text, (v, v / 60.0), textcoords="offset points", xytext=(8, -12), fontsize=8,
                        color="tab:red")
    # the operating point: the power turbine at its spin speed, the gas generator at its own (model data)
    pt = m.omega_pt * 30.0 / np.pi
    gg = m.omega_gg * 30.0 / np.pi
    op = f"{pt:,.0f} / {gg:,.0f}" if ratio != 1.0 else f"{pt:,.0f}"
    ax.axvline(pt, color="tab:green", lw=1.2, label=f"operating speed: {op} rev/min".replace(",", " "))
    if windmill_rpm is not None:
        ax.axvspan(windmill_rpm[0], windmill_rpm[1], color="tab:cyan", alpha=0.25, lw=0,
                   label=f"windmilling: {windmill_rpm[0]:.0f}-{windmill_rpm[1]:.0f} rev/min")
    ax.set_xlabel(f"first spool speed [rev/min] (second spool at {ratio:.4g} x)" if ratio != 1.0
                  else "spool speed [rev/min]")
    ax.set_ylabel("whirl frequency [Hz]")
    ax.set_xlim(0, max_rpm)
    ax.set_ylim(0, 1.2 * max_rpm / 60.0)
    ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), fontsize=8, framealpha=0.9)
    ax.set_title("Campbell diagram (undamped; co-simulated bearings linearised: contacts, journal body, O-ring)"
                 + (f"\nthe engine on its airframe ({extra} airframe modes)" if extra else ""), fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


#: critical speeds nearer than this share of the diagram's speed axis share one label (one text over another
#: reads as neither: an installed engine's modes split a few per cent by its mounts)
LABEL_MERGE = 0.04


def speed_labels(rpm, max_rpm: float) -> list[tuple[float, str]]:
    """``[(speed, text)]``: one label per group of the increasing critical speeds ``rpm`` [rev/min] whose
    neighbours lie within :data:`LABEL_MERGE` of ``max_rpm``, at the group's first speed, its speeds joined
    ("4 355 / 4 410")."""
    groups: list[list[float]] = []
    for v in rpm:
        if groups and v - groups[-1][-1] < LABEL_MERGE * max_rpm:
            groups[-1].append(float(v))
        else:
            groups.append([float(v)])
    return [(g[0], " / ".join(f"{v:,.0f}".replace(",", " ") for v in g)) for g in groups]


def check_figure_path(path: str) -> None:
    """--campbell names a file we can write, checked before the (slow) eigenvalue scan."""
    p = Path(path)
    if p.is_dir():
        raise ValueError(f"--campbell {path}: is a folder; give a file name, e.g. {p / 'campbell.png'}")
    parent = p.parent if str(p.parent) else Path(".")
    if not parent.is_dir():
        raise ValueError(f"--campbell {path}: the folder {parent} does not exist")
    if not os.access(parent, os.W_OK | os.X_OK):
        raise ValueError(f"--campbell {path}: the folder {parent} is not writable")
    if p.suffix:
        from matplotlib.backends.backend_agg import FigureCanvasAgg
        from matplotlib.figure import Figure

        formats = FigureCanvasAgg(Figure()).get_supported_filetypes()
        if p.suffix[1:].lower() not in formats:
            raise ValueError(f"--campbell {path}: {p.suffix!r} is not an image format matplotlib writes "
                             f"({', '.join(sorted(formats))})")


def scenario_engine(sc) -> str:
    """The engine file scenario ``sc`` runs (its ``[scenario] engine``, else its rotor's ``model_file``; '' for
    none or no scenario: the paper's). Without it ``--scenario my_engine/blade_loss.toml`` listed the paper's
    engine's critical speeds, its bearings linearised with the scenario's."""
    if sc is None:
        return ""
    if getattr(sc, "engine", None) is not None:
        return str(sc.engine.file)
    rotor = sc.components.get("rotor")
    model = rotor.parameters.get("model_file") if rotor is not None else None
    return model if isinstance(model, str) else ""


def run(args) -> int:
    """Run the command ``args`` (parsed); returns the exit status."""
    if args.campbell:
        check_figure_path(args.campbell)
    elif args.windmill_rpm is not None:
        raise ValueError("--windmill-rpm marks the Campbell diagram: give --campbell FILE.png too")
    sc = None
    if args.scenario:
        from rotorcosim.master.api import load_scenario   # a shipped name too, as every command's --scenario

        sc = load_scenario(args.scenario)
    model_file = args.model_file or scenario_engine(sc)
    out = critical_speeds(model_file, args.count, args.max_rpm, args.oil_temperature, sc)
    if args.campbell:
        draw_campbell(args.campbell, model_file, args.max_rpm, out, args.oil_temperature, sc, args.windmill_rpm)
        out["campbell"] = args.campbell
    if args.json:
        print(json.dumps(out))
    else:
        spools = out["spools"]
        if len(spools) > 1:
            print(f"synchronous critical speeds of spool {spools[0]!r} (the other at "
                  f"{out['speed_ratio_gg_pt']:.4f} x), rev/min:")
        else:
            print("synchronous critical speeds, rev/min:")
        print("  forward :", ", ".join(f"{v:.0f}" for v in out["forward_synchronous_rpm"]))
        print("  backward:", ", ".join(f"{v:.0f}" for v in out["backward_synchronous_rpm"]))
        if "definition" in out:
            print(f"  (coefficients over speed: {out['definition']})")
        if out["target_rpm"]:
            print("  paper (lowest two forward):", ", ".join(f"{v:.0f}" for v in out["target_rpm"]))
        sm = out["support_model"]
        if sm["kind"] != "coupled":
            print(f"  supports: {sm['description']}")
        else:
            ids = "/".join(f"#{b}" for b in sm.get("bearings", {}))
            print(f"  supports {ids}: {sm['description']}; film at {sm['oil_temperature_C']:g} C")
        for b, v in sm.get("bearings", {}).items():
            print(f"    #{b}: contact {v['k_contact']:.3g} N/m, journal {v['m_journal']:.3g} kg, O-ring "
                  f"{v['k_spring']:.4g} N/m, film {v['c_film']:.4g} N s/m")
        for st in out.get("fuse_states", []):
            print(f"  {st['label']} (fuse stiffness " + ", ".join(f"#{b} {k:.3g} N/m" for b, k in
                                                        st["fuse_stiffness_N_per_m"].items()) + "), rev/min:")
            if "note" in st:
                print(f"    {st['note']}")
                continue
            print("    forward :", ", ".join(f"{v:.0f}" for v in st["forward_synchronous_rpm"]))
            print("    backward:", ", ".join(f"{v:.0f}" for v in st["backward_synchronous_rpm"]))
        if out.get("damped_critical_speeds_rpm"):
            print("  damped (where the unbalance response peaks), rev/min:")
            for b, v in out["damped_critical_speeds_rpm"].items():
                print(f"    #{b}: " + (", ".join(f"{w:.0f}" for w in v) or "no peak"))
        if args.campbell:
            print(f"Campbell diagram: {args.campbell}")
    return 0
