"""The reduced airframe and the mounts (components/airframe, components/rotor/mounts.py).

* the reduced airframe against the Euler-Bernoulli cantilever (an independent, analytic reference): a modal file
  of its clamped-free modes (Blevins, *Formulas for natural frequency and mode shape*, table 8-1: beta_n L roots
  of cos cosh = -1, tip deflection 2 of the shapes normalised to int phi^2 = L) has the static tip flexibility
  L^3 / (3 EI), and the airframe component stepping that beam on a mount spring k to a held engine point settles
  at the static deflection k / (k + 3 EI / L^3) of the engine's displacement and oscillates at the first root of
  the clamped beam's characteristic equation with a tip spring (EI w'''(L) = k w(L), w''(L) = 0), solved here;
* the shipped example airframe is its derivation's output (components/airframe/example.py);
* the paper's engine on the pylon (engine_on_pylon.toml) is, on a rigid airframe, the paper's engine: the same
  file but for the mounts' far ends, and the same assembled matrices bit for bit;
* bad input: a modal file with a negative modal mass or a frequency of zero, a mount on a node the engine does not
  have: one line naming the key, exit status 2.
"""
from __future__ import annotations

import math
import re

import numpy as np
import pytest
from scipy.optimize import brentq

from rotorcosim.components.airframe import example
from rotorcosim.components.contract import ContractError
from rotorcosim.components.airframe.modal import EXAMPLE, read, static_flexibility, to_toml
from rotorcosim.components.registry import create
from rotorcosim.components.rotor import model as fem
from rotorcosim.master.cli import main

L, EI, MU = 10.0, 1.0e7, 100.0          # m, N m^2, kg/m
N_MODES = 8
PYLON = fem.DEFAULT_FILE.with_name("engine_on_pylon.toml")


def _beta_roots(n: int) -> np.ndarray:
    """beta_n L of the clamped-free beam: roots of 1 + cos x cosh x = 0."""
    return np.array([brentq(lambda x: 1.0 + math.cos(x) * math.cosh(x), (k + 0.2) * math.pi, (k + 0.8) * math.pi)
                     for k in range(n)])


def _cantilever_file(folder, n: int = N_MODES, mass=None, freq=None, zeta: float = 0.02) -> str:
    """A modal file of the cantilever's first n modes, its tip the interface point (y translation)."""
    bl = _beta_roots(n)
    f = bl ** 2 * math.sqrt(EI / (MU * L ** 4)) / (2.0 * math.pi)
    tip = np.zeros((n, 3))
    tip[:, 1] = 2.0 * (-1.0) ** np.arange(n)             # phi_n(L) = 2 (-1)^(n+1), int phi^2 = L
    m = np.full(n, MU * L)
    if mass is not None:
        m[1] = mass
    if freq is not None:
        f[0] = freq
    path = folder / "beam.toml"
    path.write_text(to_toml("cantilever", "Euler-Bernoulli, analytic", f, m, zeta, {"tip": tip}, {}))
    return str(path)


def _engine_file(folder, k: float, node='["casing", 0, 0]') -> str:
    """An engine file of one mount spring (y) on the cantilever's tip (only what the airframe reads)."""
    path = folder / "engine.toml"
    path.write_text(f'[airframe]\nmodel = "beam.toml"\n\n[mount.tip]\ninterface = "tip"\n'
                    f'springs = [{{ node = {node}, dir = 1, k = {k!r}, c = 0.0 }}]\n')
    return str(path)


def test_cantilever_modes_give_the_static_tip_flexibility(tmp_path):
    model = read(_cantilever_file(tmp_path))
    flex = static_flexibility(model, "tip")[1, 1]
    # the truncated series 4 L^3 / EI sum (beta_n L)^-4 misses the modes above the 8th: 8e-5 of L^3 / 3 EI
    assert flex == pytest.approx(L ** 3 / (3.0 * EI), rel=1.5e-4)
    assert model.w[0] == pytest.approx(1.87510407 ** 2 * math.sqrt(EI / (MU * L ** 4)), rel=1e-8)


def _tip_spring_frequency(k: float) -> float:
    """First natural frequency [rad/s] of the clamped beam with a tip spring k (module docstring)."""
    def det(b):
        x = b * L
        ch, c, sh, s = math.cosh(x), math.cos(x), math.sinh(x), math.sin(x)
        # w = A (cosh - cos) + B (sinh - sin); rows: w''(L) = 0 and EI w'''(L) - k w(L) = 0
        a11, a12 = b * b * (ch + c), b * b * (sh + s)
        a21 = EI * b ** 3 * (sh - s) - k * (ch - c)
        a22 = EI * b ** 3 * (ch + c) - k * (sh - s)
        return a11 * a22 - a12 * a21
    grid = np.linspace(0.5, 4.0, 3500) / L
    vals = [det(b) for b in grid]
    i = next(j for j in range(len(grid) - 1) if vals[j] * vals[j + 1] < 0)
    b = brentq(det, grid[i], grid[i + 1])
    return b * b * math.sqrt(EI / MU)


def _step_response(folder, k: float, zeta: float, steps: int, h: float = 2e-4, delta: float = 1e-3):
    """The tip's displacement after the engine's side of the spring steps to ``delta`` (the component at rest)."""
    _cantilever_file(folder, zeta=zeta)
    comp = create("airframe.modal", "airframe", {"model_file": _engine_file(folder, k)})
    comp.setup(0.0)
    comp.set_inputs({"X_mount_tip": [delta], "V_mount_tip": [0.0]})
    u = np.empty(steps)
    for i in range(steps):
        comp.do_step(i * h, h)
        u[i] = delta - comp.y["F_tip"][1] / k        # the spring's load on the airframe: k (delta - u_tip)
    assert comp.y["F_tip"][0] == 0.0 and comp.y["F_tip"][2] == 0.0     # no other axis carries anything
    return h * np.arange(1, steps + 1), u


def test_airframe_component_on_a_tip_spring_matches_the_beam(tmp_path):
    k = 3.0 * EI / L ** 3                  # the beam's own static tip stiffness
    delta = 1e-3
    # heavily damped (zeta 0.5: settled to 1e-6 in 2 s): the static deflection of two equal springs in series,
    # to the modes' truncation (8e-5)
    _, u = _step_response(tmp_path, k, 0.5, 10000)
    assert u[-1] == pytest.approx(0.5 * delta, rel=2e-4)
    # 2 % damping: the period from the upward crossings of the static value over 2 s
    t, u = _step_response(tmp_path, k, 0.02, 10000)
    d = u - 0.5 * delta
    up = np.flatnonzero((d[:-1] < 0) & (d[1:] >= 0))
    tc = t[up] - d[up] * (t[1] - t[0]) / (d[up + 1] - d[up])
    w = 2.0 * math.pi / np.mean(np.diff(tc))
    # the damped frequency of the first mode (sqrt(1 - zeta^2) of the undamped): measured 0.13 % above it (the
    # higher modes' share of the crossings, the Ritz truncation)
    assert w == pytest.approx(_tip_spring_frequency(k) * math.sqrt(1 - 0.02 ** 2), rel=3e-3)


def test_example_airframe_is_its_derivation():
    """The shipped file is what its derivation writes: the same text around the numbers, and the numbers equal to
    round-off (the eigenvectors' last printed digits move with the BLAS library and its thread count)."""
    number = re.compile(r"[-+]?(?:\d+\.\d*|\.\d+|\d+)(?:[eE][-+]?\d+)?")
    shipped, derived = EXAMPLE.read_text(), example.text()
    assert number.sub("#", shipped) == number.sub("#", derived)
    a, b = (np.array([float(x) for x in number.findall(t)]) for t in (shipped, derived))
    assert a.shape == b.shape and np.allclose(a, b, rtol=1e-6, atol=1e-9)
    m = read(EXAMPLE)
    assert m.n == 40 and np.all(np.diff(m.w) >= 0)


def test_pylon_engine_on_rigid_mounts_is_the_paper_engine():
    a_data, _ = fem.load_data()
    b_data, _ = fem.load_data(PYLON)
    mounts = a_data["casing"].pop("mounts")
    for key in ("mount", "airframe"):
        b_data.pop(key)
    a_data["engine"].pop("name"), b_data["engine"].pop("name")
    assert a_data == b_data
    # every casing spring of engine.toml is one of the mounts', with its stiffness and damping
    springs = [(s["node"][1], s["node"][2], s["dir"], s["k"], s["c"]) for m in fem.load_data(PYLON)[0]["mount"].values()
               for s in m["springs"]]
    assert sorted(springs) == sorted((m["ring"], m["node"], m["dir"], m["k"], m["c"]) for m in mounts)
    a, b = fem.load(), fem.load(PYLON)
    assert np.array_equal(a.K, b.K) and np.array_equal(a.C, b.C) and np.array_equal(a.M, b.M)


@pytest.mark.parametrize("kw, key", [({"mass": -5.0}, "modes.modal_mass_kg[1]"),
                                     ({"freq": 0.0}, "modes.frequency_Hz[0]")])
def test_bad_modal_file_is_one_line_naming_the_key(tmp_path, monkeypatch, capsys, kw, key):
    _cantilever_file(tmp_path, **kw)
    with pytest.raises(ValueError, match=key.replace("[", r"\[")):
        read(tmp_path / "beam.toml")
    engine = PYLON.read_text().replace('model = "../../airframe/data/pylon_wing.toml"', 'model = "beam.toml"')
    (tmp_path / "engine.toml").write_text(engine.replace('interface = "pylon_aft"', 'interface = "tip"')
                                          .replace('interface = "pylon_fwd"', 'interface = "tip"'))
    monkeypatch.chdir(tmp_path)
    assert main(["check-engine", str(tmp_path / "engine.toml")]) == 2
    out = capsys.readouterr().out.splitlines()
    assert len(out) == 2 and key in out[1]
    # a run: the airframe component refuses the file when it is made, before its ports are connected
    with pytest.raises(ContractError, match=re.escape(key)):
        create("airframe.modal", "airframe", {"model_file": str(tmp_path / "engine.toml")})


@pytest.mark.parametrize("old, new, says", [
    ('name = "cantilever"', 'name = "cantilever"\nnmae = "x"', "airframe.nmae: unknown key (known: format, name, source)"),
    ("[modes]", "[respnse.mid]\nshape = [[0.0, 1.0, 0.0]]\n\n[modes]", "respnse: unknown table (known: airframe, modes, "
                                                                     "interface, response)"),
])
def test_a_misspelt_table_or_key_of_the_airframe_file_is_named(tmp_path, old, new, says):
    """Read as absent, it lost a response point or a name without a word; the file's other tables already named
    theirs (modes.*, interface.NAME.*)."""
    path = tmp_path / "beam.toml"
    _cantilever_file(tmp_path)
    text = path.read_text()
    assert old in text
    path.write_text(text.replace(old, new, 1))
    with pytest.raises(ValueError) as err:
        read(path)
    assert str(err.value) == f"airframe model {path}: {says}"


def test_a_shape_row_or_position_of_another_length_names_what_it_needs(tmp_path):
    """A shape row shorter than the first, a position of 2 numbers: the message said 'needs one value per mode
    (3)', where a row holds a point's components (T1 T2 T3 ...) and a position its x y z."""
    path = tmp_path / "beam.toml"
    _cantilever_file(tmp_path)
    text = path.read_text()
    rows = re.search(r"shape = \[\n(.*?)\]\n", text, re.S).group(1).splitlines()
    short = rows[1].rsplit(",", 2)[0] + "],"
    path.write_text(text.replace(rows[1], short, 1))
    with pytest.raises(ValueError) as err:
        read(path)
    assert str(err.value).endswith("interface.tip.shape[1]: needs as many values as shape[0] (3: T1 T2 T3), got 2")
    path.write_text(text.replace("[interface.tip]", "[interface.tip]\nposition_mm = [1.0, 2.0]", 1))
    with pytest.raises(ValueError) as err:
        read(path)
    assert str(err.value).endswith("interface.tip.position_mm: needs 3 values (x y z, mm), got 2")


def test_mount_on_a_missing_node_is_one_line(tmp_path, monkeypatch, capsys):
    bad = PYLON.read_text().replace('{ node = ["casing", 6, 0], dir = 1', '{ node = ["casing", 9, 0], dir = 1')
    bad = bad.replace('"../../airframe/data/pylon_wing.toml"', repr(str(EXAMPLE)).replace("'", '"'))
    (tmp_path / "engine.toml").write_text(bad)
    monkeypatch.chdir(tmp_path)
    assert main(["check-engine", str(tmp_path / "engine.toml")]) == 2
    out = capsys.readouterr().out.splitlines()
    assert len(out) == 2
    assert "[mount.fwd] springs[0].node" in out[1] and "does not exist" in out[1]


def test_the_format_pages_example_is_read(tmp_path):
    page = (fem.DEFAULT_FILE.parents[3] / "docs" / "reference" / "airframe-format.md").read_text()
    (tmp_path / "a.toml").write_text(re.search(r"## An example\n.*?```toml\n(.*?)```", page, re.S).group(1))
    m = read(tmp_path / "a.toml")
    # the page's cantilever: its tip flexibility with two modes, 4 L^3 / EI (1.8751^-4 + 4.6941^-4), 99.5 % of
    # L^3 / 3 EI (the page's frequencies to 3 digits)
    assert static_flexibility(m, "tip")[1, 1] == pytest.approx(0.9954 * L ** 3 / (3.0 * EI), rel=2e-3)
    assert sorted(m.response) == ["mid_span"]


def test_a_rotation_spring_carries_a_moment(tmp_path):
    """A spring on a rotation (dir 3: about x) of a spool node, to an interface point whose shape has rotations:
    the rotor gets its port, the airframe a moment output, and a held engine rotation settles at the static
    moment of the spring in series with the airframe's rotational flexibility there (the retained modes')."""
    k = 1.0e6                                         # N m/rad
    engine = tmp_path / "engine.toml"
    engine.write_text(f'[airframe]\nmodel = {str(EXAMPLE)!r}\n\n[mount.fwd]\ninterface = "pylon_fwd"\n'
                      f'springs = [{{ node = ["pt", 5], dir = 3, k = {k!r}, c = 0.0 }}]\n'.replace("'", '"'))
    comp = create("airframe.modal", "airframe", {"model_file": str(engine)})
    assert comp.variable("M_fwd").size == 3 and comp.variable("X_mount_fwd").size == 1
    comp.setup(0.0)
    theta, h = 1e-4, 1e-3
    comp.set_inputs({"X_mount_fwd": [theta], "V_mount_fwd": [0.0]})
    for i in range(8000):                             # 8 s: measured within 3e-6 of the static value over the last 2
        comp.do_step(i * h, h)
    f_rr = static_flexibility(read(EXAMPLE), "pylon_fwd")[3, 3]      # k f_rr = 0.12: the airframe yields 11 %
    assert comp.y["M_fwd"][0] == pytest.approx(k * theta / (1.0 + k * f_rr), rel=1e-4)
    assert np.all(comp.y["F_fwd"] == 0.0)
    # the engine side: the spring is in the model at the node's rotation, a port of one value
    data = PYLON.read_text().replace('\n[mount.aft]\n', '\n[mount.rot]\ninterface = "pylon_fwd"\n'
                                     'springs = [{ node = ["pt", 5], dir = 3, k = 1.0e6, c = 0.0 }]\n\n[mount.aft]\n')
    data = data.replace('"../../airframe/data/pylon_wing.toml"', repr(str(EXAMPLE)).replace("'", '"'))
    (tmp_path / "pylon.toml").write_text(data)
    full = fem.load(tmp_path / "pylon.toml")
    i = full.ports["mount_rot"][0]
    assert full.K[i, i] - fem.load(PYLON).K[i, i] == pytest.approx(k)


def _point_file(folder, a1: float = 0.02, b2: float = 0.05) -> str:
    """Two modes at one interface point p: mode 1 translates it along x and y (shape a1), mode 2 turns it about z
    (b2); heavily damped (zeta 0.5) so that a held engine settles within a second."""
    shape = np.array([[a1, a1, 0.0, 0.0, 0.0, 0.0], [0.0, 0.0, 0.0, 0.0, 0.0, b2]])
    path = folder / "point.toml"
    path.write_text(to_toml("point", "two modes", [5.0, 8.0], [30.0, 4.0], 0.5, {"p": shape}, {}))
    return str(path)


@pytest.mark.parametrize("d, offset_mm", [(1, [400.0, 0.0, 0.0]), (0, [0.0, 300.0, 0.0])])
def test_an_offset_spring_carries_its_moment_into_the_airframe(tmp_path, d, offset_mm):
    """A translation spring ending off the interface point (offset_mm r) against a hand-computed static case: the
    point's static stiffnesses are k_t = m1 (2 pi f1)^2 / a1^2 (translation) and k_r = m2 (2 pi f2)^2 / b2^2
    (rotation about z); the spring's end moves with the point, u_a = e_d . (u + theta x r), and the point takes
    the force f e_d and the moment r x f e_d. With the engine held at delta along d: f = k delta / (1 + k / k_t +
    k rho^2 / k_r) (rho the lever arm about z, 0.4 and 0.3 m), F = f e_d, M = r x f e_d (+0.4 f about z for a y
    spring at +x, -0.3 f for an x spring at +y)."""
    k, delta, a1, b2 = 2.0e6, 1e-3, 0.02, 0.05
    _point_file(tmp_path, a1, b2)
    engine = tmp_path / "engine.toml"
    engine.write_text(f'[airframe]\nmodel = "point.toml"\n\n[mount.m]\ninterface = "p"\n'
                      f'springs = [{{ node = ["casing", 0, 0], dir = {d}, k = {k!r}, c = 0.0, '
                      f'offset_mm = [{", ".join(map(str, offset_mm))}] }}]\n')
    comp = create("airframe.modal", "airframe", {"model_file": str(engine)})
    comp.setup(0.0)
    comp.set_inputs({"X_mount_m": [delta], "V_mount_m": [0.0]})
    h = 2e-4
    for i in range(5000):                             # 1 s: 16 time constants of the slower mode
        comp.do_step(i * h, h)
    k_t = 30.0 * (2 * math.pi * 5.0) ** 2 / a1 ** 2
    k_r = 4.0 * (2 * math.pi * 8.0) ** 2 / b2 ** 2
    r = np.array(offset_mm) * 1e-3
    f = k * delta / (1.0 + k / k_t + k * (r[0] ** 2 + r[1] ** 2) / k_r)
    assert comp.y["F_m"] == pytest.approx(f * np.eye(3)[d], rel=1e-6, abs=1e-9 * f)
    assert comp.y["M_m"] == pytest.approx(np.cross(r, f * np.eye(3)[d]), rel=1e-6, abs=1e-9 * f)
    assert abs(comp.y["M_m"][2]) == pytest.approx((0.4 if d == 1 else 0.3) * f, rel=1e-6)


@pytest.mark.parametrize("spring, model, key", [
    ('{ node = ["casing", 0, 0], dir = 1, k = 1e6, offset_mm = [1, 2] }', "point", "offset_mm"),
    ('{ node = ["pt", 5], dir = 3, k = 1e6, offset_mm = [1, 2, 3] }', "point", "offset_mm"),
    ('{ node = ["casing", 0, 0], dir = 1, k = 1e6, offset_mm = [1, 2, 3] }', "beam", "offset_mm"),
])
def test_a_bad_offset_is_one_line(tmp_path, spring, model, key):
    """offset_mm: not three numbers, on a rotation spring, or on a point whose shape has translations only."""
    from rotorcosim.components.airframe.mounting import installed

    _point_file(tmp_path)
    _cantilever_file(tmp_path)
    engine = tmp_path / "engine.toml"
    engine.write_text(f'[airframe]\nmodel = "{model}.toml"\n\n[mount.m]\ninterface = "{"p" if model == "point" else "tip"}"\n'
                      f'springs = [{spring}]\n')
    with pytest.raises(ValueError, match=rf"^\[mount\.m\] springs\[0\]\.{key}: ") as exc:
        installed(str(engine))
    assert "\n" not in str(exc.value)


def test_a_spring_given_twice_is_one_line(tmp_path):
    """Two springs of a mount at one node, direction and offset (a spring copied twice doubled the stiffness
    silently): refused naming both; the same node in another direction is two springs."""
    from rotorcosim.components.airframe.mounting import installed

    _point_file(tmp_path)
    engine = tmp_path / "engine.toml"
    one = '{ node = ["casing", 0, 0], dir = 1, k = 1e6 }'
    engine.write_text(f'[airframe]\nmodel = "point.toml"\n\n[mount.m]\ninterface = "p"\nsprings = [{one}, {one}]\n')
    with pytest.raises(ValueError, match=r"^\[mount\.m\] springs\[1\]: the same node, dir and offset as springs\[0\]"):
        installed(str(engine))
    engine.write_text(f'[airframe]\nmodel = "point.toml"\n\n[mount.m]\ninterface = "p"\n'
                      f'springs = [{one}, {one.replace("dir = 1", "dir = 0")}]\n')
    installed(str(engine))


def test_a_moment_s_and_an_acceleration_s_columns_are_x_y_z(tmp_path):
    """The time series' `columns` of M_NAME and a_NAME are x, y, z, as outputs.md says and as F_NAME's are (they
    read 1, 2, 3: a vector not in m, m/s or N got numbered columns)."""
    from rotorcosim.master.observer.recorder_csv import column_names

    engine = tmp_path / "engine.toml"
    engine.write_text(f'[airframe]\nmodel = {str(EXAMPLE)!r}\n\n[mount.fwd]\ninterface = "pylon_fwd"\n'
                      f'springs = [{{ node = ["pt", 5], dir = 3, k = 1.0e6, c = 0.0 }}]\n'.replace("'", '"'))
    comp = create("airframe.modal", "airframe", {"model_file": str(engine)})
    for port in ("F_fwd", "M_fwd", "a_flight_deck", "a_seat_track"):
        assert comp.variable(port).column_labels() == ["x", "y", "z"], port
    variables = {"airframe.a_flight_deck": comp.variable("a_flight_deck")}
    assert column_names(["airframe.a_flight_deck"], variables)[0] == "airframe.a_flight_deck[x] (m/s2)"


def test_an_airframe_without_a_mount_is_one_line(tmp_path, monkeypatch, capsys):
    """[airframe] without any [mount.NAME]: check-engine said 'no problem found' and a run stood the engine on
    its ground, the airframe read and left out (a [mount] without [airframe] was refused already)."""
    text = PYLON.read_text().replace('"../../airframe/data/pylon_wing.toml"', repr(str(EXAMPLE)).replace("'", '"'))
    text = re.sub(r"\n\[mount\.\w+\]\n.*?(?=\n\[(?!mount))", "", text, flags=re.S)
    assert "\n[mount." not in text and "\n[airframe]" in text
    (tmp_path / "engine.toml").write_text(text)
    monkeypatch.chdir(tmp_path)
    assert main(["check-engine", str(tmp_path / "engine.toml")]) == 2
    out = capsys.readouterr().out.splitlines()
    assert len(out) == 2 and out[1].strip().startswith("[airframe]: no [mount.NAME] table hangs the engine from it")
