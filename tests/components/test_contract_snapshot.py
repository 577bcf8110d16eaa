"""The default get_state / set_state (components/contract.py): the very copy copy.deepcopy gives, also on the
direct path taken for dicts of arrays."""
import copy

import numpy as np

from rotorcosim.components.contract import _copy_snapshot


def _same(a, b):
    """Equal values and types all the way down (arrays: dtype, shape, memory order)."""
    assert type(a) is type(b)
    if isinstance(a, np.ndarray):
        assert a.dtype == b.dtype and a.shape == b.shape and a.strides == b.strides and np.array_equal(a, b)
    elif isinstance(a, dict):
        assert list(a) == list(b)
        for k in a:
            _same(a[k], b[k])
    elif isinstance(a, (list, tuple)):
        assert len(a) == len(b)
        for x, y in zip(a, b):
            _same(x, y)
    else:
        assert a == b


def _snap():
    state = {"balls": np.arange(12.0).reshape(3, 4), "f": np.asfortranarray(np.arange(6.0).reshape(2, 3)),
             "n": np.arange(3)}
    return (0.25, state, {"T": np.array([300.0])}, {"P": np.array([3.0]), "view": np.arange(8.0)[::2]})


def test_direct_copy_is_deepcopy_and_independent():
    src = _snap()
    out, ref = _copy_snapshot(src), copy.deepcopy(src)
    _same(out, ref)
    # no array of the copy shares memory with the source: changing the source leaves the copy as it was
    for part in (1, 2, 3):
        for key, arr in src[part].items():
            assert not np.shares_memory(out[part][key], arr), (part, key)
    src[1]["balls"] += 1.0
    src[3]["view"] += 1.0
    assert out[1]["balls"][0, 0] == 0.0 and out[3]["view"].tolist() == [0.0, 2.0, 4.0, 6.0]
    assert out[1]["f"].flags.f_contiguous and out[3]["view"].strides == ref[3]["view"].strides
    _same(out, ref)


def test_shared_arrays_and_other_types_go_through_deepcopy():
    t = np.array([300.0])
    shared = (0.0, {}, {"T": t}, {"T_out": t})              # one array seen twice: deepcopy shares its copy
    out = _copy_snapshot(shared)
    assert out[2]["T"] is out[3]["T_out"] and out[2]["T"] is not t
    odd = (0.0, {"k": 3, "x": [1.0, 2.0], "o": np.array([{}], dtype=object)}, {}, {})
    _same(_copy_snapshot(odd), copy.deepcopy(odd))
    assert _copy_snapshot(odd)[1]["x"] is not odd[1]["x"]


def test_restore_state_takes_the_snapshot_or_defers_to_an_overridden_set_state():
    from rotorcosim.components.contract import Component, Memoryless

    class Plain(Component):
        pass

    class OwnSnapshot(Memoryless, Component):   # a class with its own snapshot: restore_state is its set_state
        pass

    a = Plain.__new__(Plain)
    a.time, a.state, a.u, a.y = _snap()
    snap = a.get_state()
    a.state["balls"] += 7.0
    a.restore_state(snap)
    assert a.state is snap[1] and a.state["balls"][0, 0] == 0.0      # taken as it is, no copy

    b = OwnSnapshot.__new__(OwnSnapshot)
    b.time, b.u, b.y = 1.0, {"F": np.array([2.0])}, {"P": np.array([3.0])}
    snap = b.get_state()
    b.u["F"][0] = 9.0
    b.restore_state(snap)
    assert b.u["F"][0] == 2.0 and b.u["F"] is not snap[1]["F"]          # through Memoryless.set_state's copy
