"""The support fuse (components/fuse): its force law against the closed forms of its docstring (intact, soft path,
bumper with friction), the break at the load inside its own step (no master locating it), and what it hands the
master (indicator, discrete update)."""
from __future__ import annotations

import math

import pytest

from rotorcosim.components.fuse.kernel import V_REG, support_force
from rotorcosim.components.registry import create

K, C, F_BREAK, K_B = 4.0e6, 252.98, 1500.0, 4.0e5


def _fuse(**extra):
    f = create("fuse.support", "fuse", {"k_intact": K, "damping": C, "break_load": F_BREAK, "k_broken": K_B, **extra})
    f.setup(0.0)
    return f


def _step(f, x, v, t=0.0, h=1e-5):
    f.set_inputs({"X": [*x, 0.0], "V": [*v, 0.0]})
    f.do_step(t, h)
    return f.y["F_support"]


def test_intact_and_broken_paths_are_spring_and_damper():
    """Below the break load the fuse carries k x + c v; on the rotor, the opposite (axial 0)."""
    f = _fuse()
    F = _step(f, (1e-4, -2e-4), (0.03, 0.01))
    assert F == pytest.approx([K * 1e-4 + C * 0.03, -K * 2e-4 + C * 0.01], rel=1e-14)
    assert f.y["F_rotor"] == pytest.approx([-F[0], -F[1], 0.0], rel=1e-14)
    assert f.indicators() == pytest.approx([K * math.hypot(1e-4, 2e-4) - F_BREAK])
    assert f.y["broken"][0] == 0.0


def test_break_inside_its_own_step_then_the_soft_path():
    """A step whose displacement puts k_intact |x| at the break load breaks the fuse at its end (what an FMU of it
    does in another tool); the indicator then says so once, the discrete update records the values, and no
    indicator is left (one stage). The soft path carries k_broken x + c v."""
    f = _fuse()
    x = (F_BREAK / K * 1.01, 0.0)
    F = _step(f, x, (0.0, 0.0))
    assert f.y["broken"][0] == 1.0 and F == pytest.approx([K_B * x[0], 0.0], rel=1e-14)
    assert f.indicators() == [1.0]
    what = f.update_discrete(1e-5, [0])
    assert what["kind"] == "break" and what["values"]["F_elastic_N"] == pytest.approx(1.01 * F_BREAK)
    assert f.indicators().size == 0
    F = _step(f, (-3e-4, 1e-4), (0.1, 0.0), t=1e-5)
    assert F == pytest.approx([-K_B * 3e-4 + C * 0.1, K_B * 1e-4], rel=1e-14)
    # the snapshot carries the broken state: a rollback to before the break restores the intact fuse
    g = _fuse()
    snap = g.get_state()
    _step(g, x, (0.0, 0.0))
    g.set_state(snap)
    assert _step(g, (1e-5, 0.0), (0.0, 0.0)) == pytest.approx([K * 1e-5, 0.0])


def test_bumper_contact_and_friction():
    """Beyond the clearance the bumper pushes back radially by k_b (r - clearance) and its friction opposes the
    tangential velocity with mu times that force (sliding much faster than V_REG); inside it, nothing."""
    kb, clr, mu = 1.0e8, 2.0e-4, 0.3
    x, y, vx, vy = 3.0e-4, 0.0, 0.0, 0.5          # radial along x, sliding along +y
    fx, fy = support_force(x, y, vx, vy, 0.0, 0.0, kb, clr, mu)
    fn = kb * (3.0e-4 - clr)
    assert fx == pytest.approx(fn, rel=1e-14)
    assert fy == pytest.approx(mu * fn * 0.5 / math.sqrt(0.25 + V_REG ** 2), rel=1e-14)
    assert fy == pytest.approx(mu * fn, rel=1e-7)
    assert support_force(1.0e-4, 0.0, 0.0, 0.5, 0.0, 0.0, kb, clr, mu) == (0.0, 0.0)
    # through the component, after the break (the soft path and the bumper add)
    f = _fuse(bumper_clearance=clr, bumper_stiffness=kb, bumper_friction=mu)
    _step(f, (F_BREAK / K * 1.01, 0.0), (0.0, 0.0))
    F = _step(f, (x, y), (vx, vy), t=1e-5)
    assert F == pytest.approx([K_B * x + fx, C * vy + fy], rel=1e-12)


@pytest.mark.parametrize("key, value, message", [
    ("break_load", 0.0, "fuse.break_load must be > 0"),
    ("break_load", -1.0, "fuse.break_load must be > 0"),
    ("k_broken", 5.0e6, "fuse.k_broken must be within [0, k_intact"),
    ("bumper_clearance", -1e-3, "fuse.bumper_clearance must be >= 0"),
    ("event_tolerance", 0.0, "fuse.event_tolerance must be > 0"),
])
def test_bad_parameters_name_the_key(key, value, message):
    from rotorcosim.components.contract import ContractError

    f = create("fuse.support", "fuse", {"k_intact": K, "break_load": F_BREAK, key: value})
    with pytest.raises(ContractError, match=message.replace("[", r"\[")):
        f.setup(0.0)


def _two_stage(**extra):
    return _fuse(stages=2, break_load_2=200.0, k_broken_2=1.0e5, **extra)


def test_two_stages_break_in_turn_into_softer_paths():
    """stages = 2: intact k x + c v until k_intact |x| reaches break_load; then k_broken x + c v, whose indicator is
    k_broken |x| - break_load_2; at that load the second break, to k_broken_2 x + c v, and no indicator left. Each
    discrete update says which stage it reached and the elastic force that broke it."""
    f = _two_stage()
    F = _step(f, (1e-4, 0.0), (0.0, 0.02))
    assert F == pytest.approx([K * 1e-4, C * 0.02], rel=1e-14) and f.y["broken"][0] == 0.0
    x1 = F_BREAK / K * 1.001
    F = _step(f, (x1, 0.0), (0.0, 0.0))
    assert f.y["broken"][0] == 1.0 and F == pytest.approx([K_B * x1, 0.0], rel=1e-14)
    assert f.indicators() == [1.0]
    what = f.update_discrete(1e-5, [0])
    assert what["values"]["stage"] == 1 and what["values"]["F_elastic_N"] == pytest.approx(1.001 * F_BREAK)
    # on the soft path: its own indicator, below its load
    assert f.indicators() == pytest.approx([K_B * x1 - 200.0])
    x2 = 200.0 / K_B * 1.002
    F = _step(f, (0.0, -x2), (0.01, 0.0), t=1e-5)
    assert f.y["broken"][0] == 2.0 and F == pytest.approx([C * 0.01, -1.0e5 * x2], rel=1e-14)
    what = f.update_discrete(2e-5, [0])
    assert what["values"]["stage"] == 2 and what["values"]["F_elastic_N"] == pytest.approx(1.002 * 200.0)
    assert what["values"]["break_load_N"] == 200.0
    assert f.indicators().size == 0


def test_a_displacement_past_both_loads_breaks_both_stages_in_one_update():
    """A located first break whose displacement already loads the soft path past break_load_2 breaks the second
    stage in the same update (one event, the stage reached 2), so that no crossing is left unseen."""
    f = _fuse(stages=2, break_load_2=160.0, k_broken_2=1.0e5)
    x = 170.0 / K_B
    _step(f, (x, 0.0), (0.0, 0.0))
    assert f.y["broken"][0] == 2.0
    what = f.update_discrete(1e-5, [0])
    assert what["values"]["stage"] == 2 and f.indicators().size == 0
    assert f.y["F_support"] == pytest.approx([1.0e5 * x, 0.0], rel=1e-14)


@pytest.mark.parametrize("extra, message", [
    ({"stages": 3}, "fuse.stages must be 1 or 2"),
    ({"break_load_2": 100.0}, "fuse.break_load_2 is a second stage's key: give it with stages = 2"),
    ({"stages": 2, "break_load_2": 0.0}, "fuse.break_load_2 must be above 150 N with stages = 2"),
    ({"stages": 2, "break_load_2": float("nan")}, "fuse.break_load_2: value is not finite"),
    ({"stages": 2, "break_load_2": 140.0}, "fuse.break_load_2 must be above 150 N"),
    ({"stages": 2, "break_load_2": 400.0, "k_broken_2": 4.0e5}, "fuse.k_broken_2 must be within [0, k_broken"),
    ({"stages": 2, "break_load_2": 400.0, "k_broken": 0.0}, "fuse.k_broken must be > 0 with stages = 2"),
])
def test_inconsistent_stages_name_the_key(extra, message):
    """A second stage that cannot work is refused in one line naming its key: a second load at or below what the
    soft path carries at the first break (k_broken / k_intact of break_load: both would break at once), a stiffness
    after it not below the soft path's, a soft path that carries nothing, a second stage's key without stages = 2."""
    from rotorcosim.components.contract import ContractError

    params = {"k_intact": K, "break_load": F_BREAK, "k_broken": K_B, **extra}
    with pytest.raises(ContractError, match=message.replace("[", r"\[")):
        create("fuse.support", "fuse", params).setup(0.0)
