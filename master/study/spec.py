"""The SPEC files of ``rotorcosim calibrate`` and ``rotorcosim uq`` (TOML), read and checked before anything runs.

A calibration SPEC (paths relative to the SPEC's folder)::

    [calibrate]
    scenario = "my_engine.toml"           # a shipped name or a path
    duration = 2.0                        # optional: the runs' duration in s (default: the scenario's)
    targets = "targets.csv"               # columns: case, result, value[, weight][, uncertainty][, holdout]
    residual = "log"                      # optional: "log" (log of ours / target) or "linear" ((ours - target) w)
    max_evaluations = 40                  # optional: points of the least-squares search (each: every fit case)
    diff_step = 0.02                      # optional: finite-difference step, a fraction of each parameter's range
    tolerance = 1e-4                      # optional: stop when the cost changes by less than this fraction
    [calibrate.cases.low]                 # optional named cases: --set style overrides; case "" = the scenario as is
    "rotor.F_load" = 700.0
    [[calibrate.parameter]]
    name = "damperA.k_spring"             # comp.param, as --set takes it
    lower = 3.0e6
    upper = 1.0e7
    start = 5.254e6                       # optional: default the scenario's value
    scale = "log"                         # or "linear"

A UQ SPEC::

    [uq]
    scenario = "my_engine.toml"
    duration = 2.0
    samples = 64
    sampler = "lhs"                       # "mc", "lhs" or "sobol" (Saltelli's scheme: samples x (D + 2) runs)
    seed = 1
    results = ["bearings.A.whirl_amplitude_mm"]
    [[uq.parameter]]
    name = "damperA.k_spring"
    distribution = "normal"               # "uniform" (lower, upper), "normal" / "lognormal" (mean, std),
    mean = 5.254e6                        # "truncnormal" (mean, std, lower, upper)
    std = 2.6e5

Every mistake is a :class:`SpecError` (a ValueError) of one line naming the file and the key.

>>> import tempfile, pathlib
>>> d = pathlib.Path(tempfile.mkdtemp())
>>> _ = (d / "t.csv").write_text("case,result,value\\n,final_outputs.node.T,310\\n")
>>> _ = (d / "s.toml").write_text('''[calibrate]
... scenario = "toy_thermomechanical"
... targets = "t.csv"
... [[calibrate.parameter]]
... name = "node.R"
... lower = 0.5
... upper = 2.0
... ''')
>>> spec = read_calibration(d / "s.toml")
>>> spec.parameters[0].name, spec.parameters[0].start, spec.parameters[0].scale
('node.R', 1.0, 'linear')
"""
from __future__ import annotations

import hashlib
import json
import math
import numbers
import sys
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

from rotorcosim import scenarios
from rotorcosim.components import toml_text
from rotorcosim.components.bounded_read import read_bytes, read_text
from rotorcosim.master.api import load_scenario
from rotorcosim.master.scenario.build import Scenario

SCALES = ("linear", "log")
RESIDUALS = ("log", "linear")
SAMPLERS = ("mc", "lhs", "sobol")
#: each distribution's keys (all required)
DISTRIBUTIONS = {"uniform": ("lower", "upper"), "normal": ("mean", "std"), "lognormal": ("mean", "std"),
                 "truncnormal": ("mean", "std", "lower", "upper")}
#: defaults of the optional calibration keys: least-squares points, finite-difference step (fraction of a range)
MAX_EVALUATIONS = 40
#: the largest design a UQ draws [bytes]: its runs x parameters as float64, drawn whole before its wall time is
#: priced and its first run starts. Far above a study that can finish (a million runs of six parameters: 46 MiB),
#: below a size that would end the command out of memory instead of refusing it
MAX_DESIGN_BYTES = 512 * 2**20
DIFF_STEP = 0.02
#: default relative change of the cost (and of the parameters, in their unit scale) at which the search stops: the
#: runs' own numerical scatter (a nonlinear transient) makes smaller changes meaningless
TOLERANCE = 1e-4


class SpecError(ValueError):
    """A mistake in a SPEC file: one line naming the file and the key."""


@dataclass
class Parameter:
    """A parameter to update: ``name`` (``comp.param``), bounds, start and scale (``"linear"`` or ``"log"``)."""
    name: str
    lower: float
    upper: float
    start: float
    scale: str = "linear"

    def to_unit(self, value: float) -> float:
        """``value`` as a fraction of the range in the parameter's scale (0 at ``lower``, 1 at ``upper``)."""
        if self.scale == "log":
            return math.log(value / self.lower) / math.log(self.upper / self.lower)
        return (value - self.lower) / (self.upper - self.lower)

    def from_unit(self, u: float) -> float:
        """The inverse of :meth:`to_unit`."""
        if self.scale == "log":
            return self.lower * (self.upper / self.lower) ** u
        return self.lower + u * (self.upper - self.lower)

    def d_value_d_unit(self, value: float) -> float:
        """d value / d u at ``value`` (a standard error in u times this is one in the parameter's unit)."""
        if self.scale == "log":
            return value * math.log(self.upper / self.lower)
        return self.upper - self.lower


@dataclass
class Distribution:
    """An uncertain parameter: ``name`` (``comp.param``), ``distribution`` and its values (:data:`DISTRIBUTIONS`)."""
    name: str
    distribution: str
    values: dict[str, float] = field(default_factory=dict)


@dataclass
class CalibrationSpec:
    """A read calibration SPEC (see the module's docstring); ``source`` the SPEC file."""
    source: Path
    scenario: str
    duration: float | None
    targets: Path
    parameters: list[Parameter]
    cases: dict[str, dict[str, Any]]
    residual: str = "log"
    max_evaluations: int = MAX_EVALUATIONS
    diff_step: float = DIFF_STEP
    tolerance: float = TOLERANCE

    def definition(self) -> dict:
        """Everything the SPEC says, as JSON values: a folder holding a calibration of another definition is
        refused, naming the keys that differ (the targets by their file's digest)."""
        digest = (hashlib.sha256(read_bytes(self.targets, "targets file")).hexdigest()[:16]
                  if self.targets.is_file() else None)
        return {"scenario": self.scenario, "duration": self.duration, "cases": self.cases,
                "parameters": [asdict(p) for p in self.parameters], "targets": digest, "residual": self.residual,
                "max_evaluations": self.max_evaluations, "diff_step": self.diff_step, "tolerance": self.tolerance}

    def fingerprint(self) -> str:
        """The digest of :meth:`definition`: evaluations stored under another fingerprint are not reused."""
        return _digest(self.definition())


@dataclass
class UQSpec:
    """A read UQ SPEC (see the module's docstring); ``source`` the SPEC file."""
    source: Path
    scenario: str
    duration: float | None
    samples: int
    sampler: str
    seed: int
    results: list[str]
    parameters: list[Distribution]
    overrides: dict[str, Any] = field(default_factory=dict)

    def definition(self) -> dict:
        """Everything the SPEC says, as JSON values: a folder holding a UQ of another definition is refused,
        naming the keys that differ."""
        return {"scenario": self.scenario, "duration": self.duration, "samples": self.samples,
                "sampler": self.sampler, "seed": self.seed, "overrides": self.overrides, "results": self.results,
                "parameters": [asdict(p) for p in self.parameters]}

    def fingerprint(self) -> str:
        """The digest of :meth:`definition`: samples stored under another fingerprint are not reused."""
        return _digest(self.definition())


def _digest(obj) -> str:
    return hashlib.sha256(json.dumps(obj, sort_keys=True, default=str).encode()).hexdigest()[:16]


def _read(path: Path, table: str) -> dict:
    path = Path(path)
    if not path.is_file():
        raise FileNotFoundError(f"SPEC {path}: no such file")
    try:
        data = toml_text.loads(read_text(path, "SPEC"))
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as exc:
        raise SpecError(f"SPEC {path}: not valid TOML: {exc}") from None
    if table not in data:
        raise SpecError(f"SPEC {path}: no [{table}] table")
    if not isinstance(data[table], dict):
        raise SpecError(f"SPEC {path}: [{table}] must be a table, got {_shape(data[table])}")
    other = sorted(set(data) - {table})
    if other:
        # a misspelt sub-table ([uq.parmeter]) sits inside [uq], named by its unknown keys; this is what is outside
        raise SpecError(f"SPEC {path}: unknown table(s) or key(s) {', '.join(other)} (a {table} SPEC holds [{table}] "
                        "only)")
    return data[table]


def _shape(value) -> str:
    """What a TOML value is, in a refusal's words: "a list ([1])", "a table", "int (5)"."""
    if isinstance(value, dict):
        return "a table"
    if isinstance(value, list):
        return f"a list ({value!r:.40})"
    return f"{type(value).__name__} ({value!r:.40})"


def _number(where: str, value, *, positive: bool = False) -> float:
    if isinstance(value, (dict, list)):
        raise SpecError(f"{where}: must be a number, got {_shape(value)}")
    if isinstance(value, bool) or not isinstance(value, numbers.Real) or not math.isfinite(value):
        raise SpecError(f"{where}: {value!r} is not a finite number")
    if positive and value <= 0:
        raise SpecError(f"{where}: {value!r} must be > 0")
    return float(value)


def _unknown_keys(where: str, table: dict, known) -> None:
    extra = sorted(set(table) - set(known))
    if extra:
        raise SpecError(f"{where}: unknown key(s) {', '.join(extra)} (known: {', '.join(sorted(known))})")


def resolve_scenario(name: str, folder: Path, where: str) -> str:
    """The scenario ``name`` of a SPEC in ``folder``: a file relative to the SPEC's folder if there is one,
    else a shipped name; returned as a string a worker can load (an absolute path or the shipped name)."""
    if not isinstance(name, str) or not name.strip():
        raise SpecError(f"{where}: scenario must be a shipped name or a file")
    p = Path(name).expanduser()
    p = p if p.is_absolute() else folder / p
    if p.is_file():
        return str(p.resolve())
    if name in scenarios.names():
        return name
    raise SpecError(f"{where}: scenario {name!r} is neither a file beside the SPEC nor a shipped scenario "
                    f"({', '.join(scenarios.names())})")


def _duration(where: str, table: dict) -> float | None:
    if table.get("duration") is None:
        return None
    return _number(f"{where} duration", table["duration"], positive=True)


def _default_value(sc: Scenario, ref: str, where: str):
    """The scenario's value of ``comp.param`` (or its implementation's declared default)."""
    from rotorcosim.master.scenario.overrides import declared_parameters

    comp, _, param = ref.partition(".")
    spec = sc.components[comp]
    if param in spec.parameters:
        return spec.parameters[param]
    declared = declared_parameters(spec) or {}
    if param in declared:
        return declared[param].start
    raise SpecError(f"{where}: no start given and {ref} has no value in the scenario (give start)")


def check_parameters(sc: Scenario, values: dict[str, Any], where: str) -> None:
    """``values`` (``comp.param`` -> value) applied to ``sc``: an unknown component or parameter, or a value
    the parameter does not take, is an error naming it."""
    try:
        sc.set(values)
    except (ValueError, TypeError) as exc:
        raise SpecError(f"{where}: {' '.join(str(exc).split())}") from None


def check_values(sc: Scenario, name: str, values, where: str) -> None:
    """Each of ``values`` of the parameter ``name`` (``comp.param``) is one its component takes: its declared range
    (:func:`check_parameters`), and the component built and set up alone with it, where it sets up alone with the
    scenario's own values (an FMU's parameters are checked by its runs). A SpecError naming the first that is
    not."""
    from rotorcosim.master.scenario.build import create_component

    comp = name.partition(".")[0]
    for v in values:
        check_parameters(sc, {name: v}, where)
    if sc.components[comp].fmu is not None or _sets_up(create_component, sc.components[comp]) is not None:
        return
    for v in values:
        why = _sets_up(create_component, sc.set({name: v}).components[comp])
        if why is not None:
            raise SpecError(f"{where}: {' '.join(why.split())}")


def _sets_up(create, component_spec) -> str | None:
    """Why the component of ``component_spec`` cannot be built and set up alone, or None when it can."""
    try:
        create(component_spec).setup(0.0)
    except (ValueError, TypeError, ArithmeticError, RuntimeError, LookupError) as exc:
        return str(exc)
    return None


def read_calibration(path: str | Path) -> CalibrationSpec:
    """Read and check the calibration SPEC ``path`` (see the module's docstring): the scenario loads, every
    parameter exists with bounds lower < start < upper (log: all > 0), every case's overrides apply. The targets
    file is read by :func:`rotorcosim.master.study.targets.read_targets`."""
    path = Path(path)
    t = _read(path, "calibrate")
    w = f"SPEC {path} [calibrate]"
    _unknown_keys(w, t, ("scenario", "duration", "targets", "cases", "parameter", "residual", "max_evaluations",
                         "diff_step", "tolerance"))
    scenario = resolve_scenario(t.get("scenario", ""), path.parent, w)
    sc = load_scenario(scenario)
    if "targets" not in t or not isinstance(t["targets"], str):
        raise SpecError(f"{w}: targets must name a CSV file (case, result, value[, weight][, holdout])")
    targets = (path.parent / t["targets"]).resolve()
    cases = t.get("cases", {})
    if not isinstance(cases, dict) or not all(isinstance(v, dict) for v in cases.values()):
        raise SpecError(f"{w}: cases must be tables of overrides, [calibrate.cases.NAME] \"comp.param\" = value")
    for name, over in cases.items():
        check_parameters(sc, over, f"{w} cases.{name}")
    out = []
    for pw, name, p in _parameter_tables(w, t, "calibrate", taken=(), sc=sc):
        _unknown_keys(pw, p, ("name", "lower", "upper", "start", "scale"))
        for c, over in cases.items():
            if name in over:
                raise SpecError(f"{pw}: case {c!r} sets it too (a parameter to update cannot be a case's setting)")
        scale = p.get("scale", "linear")
        if not isinstance(scale, str) or scale not in SCALES:
            raise SpecError(f"{pw}: scale {scale!r} not in {SCALES}")
        for key in ("lower", "upper"):
            if key not in p:
                raise SpecError(f"{pw}: {key} is missing")
        lower, upper = _number(f"{pw} lower", p["lower"]), _number(f"{pw} upper", p["upper"])
        if not lower < upper:
            raise SpecError(f"{pw}: lower {lower:g} must be below upper {upper:g}")
        if scale == "log" and lower <= 0:
            raise SpecError(f"{pw}: a log scale needs lower > 0, got {lower:g}")
        check_values(sc, name, (lower, upper), pw)   # every point of the search lies between them
        start = p["start"] if "start" in p else _default_value(sc, name, pw)
        start = _number(f"{pw} start", start)
        if not lower <= start <= upper:
            raise SpecError(f"{pw}: start {start:g} is outside the bounds [{lower:g}, {upper:g}]")
        out.append(Parameter(name, lower, upper, start, scale))
    residual = t.get("residual", "log")
    if not isinstance(residual, str) or residual not in RESIDUALS:
        raise SpecError(f"{w}: residual {residual!r} not in {RESIDUALS}")
    nmax = t.get("max_evaluations", MAX_EVALUATIONS)
    if isinstance(nmax, bool) or not isinstance(nmax, int) or nmax < 1:
        raise SpecError(f"{w}: max_evaluations must be an integer >= 1, got {nmax!r}")
    step = _number(f"{w} diff_step", t.get("diff_step", DIFF_STEP), positive=True)
    if step >= 0.5:
        raise SpecError(f"{w}: diff_step {step:g} must be below 0.5 (a fraction of each parameter's range)")
    tol = _number(f"{w} tolerance", t.get("tolerance", TOLERANCE), positive=True)
    if tol >= 1:
        raise SpecError(f"{w}: tolerance {tol:g} must be below 1 (a relative change)")
    return CalibrationSpec(path, scenario, _duration(w, t), targets, out, {str(k): v for k, v in cases.items()},
                           residual, nmax, step, tol)


def _parameter_tables(w: str, t: dict, section: str, taken, sc: Scenario):
    """The ``[[SECTION.parameter]]`` tables of a spec as (where, name, table), each a table with a ``name``
    written 'component.parameter' that no earlier table, nor ``taken``, gives, of a parameter that takes a real
    number (:func:`check_real`)."""
    params = t.get("parameter", [])
    if not isinstance(params, list) or not params:
        raise SpecError(f"{w}: no [[{section}.parameter]] given")
    seen = set(taken)
    for i, p in enumerate(params):
        pw = f"{w} parameter {i + 1}"
        if not isinstance(p, dict):
            raise SpecError(f"{pw}: must be a table")
        name = p.get("name")
        if not isinstance(name, str) or "." not in name:
            raise SpecError(f"{pw}: name must be written 'component.parameter'")
        pw = f"{w} parameter {name}"
        if name in seen:
            raise SpecError(f"{pw}: given twice")
        seen.add(name)
        check_real(sc, name, pw, section)
        yield pw, name, p


#: where a study fixes a parameter it cannot vary, by the SPEC's section
FIXED_IN = {"calibrate": "give each value a case of its own, [calibrate.cases.NAME]",
            "uq": "fix its value in [uq.set], or run one study per value"}


def check_real(sc: Scenario, name: str, where: str, section: str) -> None:
    """The parameter ``name`` (``comp.param``) takes one real number, as a study's search or sampling gives it: an
    integer, Boolean, string or vector parameter (a bearing's ball count, a switch) is a SpecError naming it (its
    runs would all be refused but the start's). A component or parameter the scenario lacks is left to
    :func:`check_parameters` to name; an FMU's parameters are checked by its runs."""
    from rotorcosim.components.contract import ContractError
    from rotorcosim.master.scenario.overrides import declared_parameters

    comp, _, param = name.partition(".")
    if comp not in sc.components:
        return
    try:
        var = (declared_parameters(sc.components[comp]) or {}).get(param)
    except (ContractError, ImportError, AttributeError):
        return
    if var is None or (var.type == "Real" and var.size == 1):
        return
    kind = f"{var.size} values" if var.size != 1 else {"Integer": "an integer", "Boolean": "a Boolean (true/false)",
                                                      "String": "a string"}.get(var.type, f"a {var.type} value")
    raise SpecError(f"{where}: {name} takes {kind}, not a real number: a {section} study varies real numbers only "
                    f"({FIXED_IN[section]})")


def read_uq(path: str | Path) -> UQSpec:
    """Read and check the UQ SPEC ``path`` (see the module's docstring): the scenario loads, every parameter
    exists, every distribution has its keys with std > 0 and lower < upper, samples >= 2 (a spread needs two)."""
    path = Path(path)
    t = _read(path, "uq")
    w = f"SPEC {path} [uq]"
    _unknown_keys(w, t, ("scenario", "duration", "samples", "sampler", "seed", "results", "parameter", "set"))
    scenario = resolve_scenario(t.get("scenario", ""), path.parent, w)
    sc = load_scenario(scenario)
    n = t.get("samples")
    if isinstance(n, bool) or not isinstance(n, int) or n < 2:
        # one sample has no spread (no standard deviation, no interval, no sensitivity): a run, not a study
        raise SpecError(f"{w}: samples must be an integer >= 2, got {n!r} (one sample has no spread: for one run "
                        "use rotorcosim run --set)")
    sampler = t.get("sampler", "lhs")
    if not isinstance(sampler, str) or sampler not in SAMPLERS:
        raise SpecError(f"{w}: sampler {sampler!r} not in {SAMPLERS}")
    seed = t.get("seed", 0)
    if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
        raise SpecError(f"{w}: seed must be an integer >= 0, got {seed!r}")
    results = t.get("results")
    if not isinstance(results, list) or not results or not all(isinstance(r, str) and r for r in results):
        raise SpecError(f"{w}: results must be a list of dotted paths into summary.json")
    if len(set(results)) != len(results):
        raise SpecError(f"{w}: a result is listed twice")
    overrides = t.get("set", {})
    if not isinstance(overrides, dict):
        raise SpecError(f"{w}: set must be a table of \"comp.param\" = value")
    check_parameters(sc, overrides, f"{w} set")
    out = []
    for pw, name, p in _parameter_tables(w, t, "uq", taken=overrides, sc=sc):
        kind = p.get("distribution")
        if not isinstance(kind, str) or kind not in DISTRIBUTIONS:
            raise SpecError(f"{pw}: distribution {kind!r} not in {tuple(DISTRIBUTIONS)}")
        vals = {}
        for key in DISTRIBUTIONS[kind]:
            if key not in p:
                raise SpecError(f"{pw}: a {kind} distribution needs {', '.join(DISTRIBUTIONS[kind])}; {key} is missing")
            vals[key] = _number(f"{pw} {key}", p[key])
        _unknown_keys(pw, p, ("name", "distribution", *DISTRIBUTIONS[kind]))
        if "std" in vals and vals["std"] <= 0:
            raise SpecError(f"{pw}: std must be > 0, got {vals['std']:g}")
        if "lower" in vals and not vals["lower"] < vals["upper"]:
            raise SpecError(f"{pw}: lower {vals['lower']:g} must be below upper {vals['upper']:g}")
        if kind == "truncnormal" and not vals["lower"] <= vals["mean"] <= vals["upper"]:
            # the study reports its mean as the parameter's and probes the parameter there: a truncated normal's
            # mean always lies within its bounds, so one outside is a slip (a bound or the mean in another unit)
            raise SpecError(f"{pw}: a truncnormal distribution's mean {vals['mean']:g} lies outside its bounds "
                            f"[{vals['lower']:g}, {vals['upper']:g}]: give a mean between lower and upper")
        if kind == "lognormal" and vals["mean"] <= 0:
            raise SpecError(f"{pw}: a lognormal distribution needs mean > 0, got {vals['mean']:g}")
        probe = vals.get("mean", (vals.get("lower", 0.0) + vals.get("upper", 0.0)) / 2)
        check_parameters(sc, {name: probe}, pw)
        out.append(Distribution(name, kind, vals))
    if sampler == "sobol" and len(out) < 2:
        raise SpecError(f"{w}: the sobol sampler (Sobol' indices) needs at least 2 parameters")
    runs = n * (len(out) + 2) if sampler == "sobol" else n
    if runs * len(out) * 8 > MAX_DESIGN_BYTES:
        raise SpecError(f"{w}: samples = {n}: a design of {runs} runs x {len(out)} parameters "
                        f"({runs * len(out) * 8 / 2**20:.0f} MiB) is above the {MAX_DESIGN_BYTES / 2**20:.0f} MiB a "
                        "study draws: give fewer samples")
    return UQSpec(path, scenario, _duration(w, t), n, sampler, seed, list(results), out, dict(overrides))
