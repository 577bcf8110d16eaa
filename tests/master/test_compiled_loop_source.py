"""The compiled loop's generated part stays small: its source depends on the number of components only.

Its first compilation on a fresh machine is what a user waits for (one generated function spelling out every
link and port of the blade-loss system took 95-140 s CPU to compile: notes/old/s3/i16.md); the links, ports and
observers' buffer are tables processed by the fixed functions of master/loop_ops.py instead."""
from __future__ import annotations

from rotorcosim.master.compiled import _source


def test_the_loop_source_grows_by_one_kernel_call_per_component():
    sizes = {n: len(_source(n).splitlines()) for n in (1, 9, 40)}
    per = (sizes[40] - sizes[9]) / 31
    assert per == 2.0  # "elif i == n:" and the kernel call
    assert sizes[9] - sizes[1] == 16
    assert sizes[9] < 90


def test_the_loop_source_holds_no_link_or_port():
    src = _source(9)
    assert "op.gather(i," in src and "op.produced(i," in src and src.count("op.call_kernel(") == 9
    for word in ("math.", "sqrt", ".P_", "buf[row", "m0[", "v0["):
        assert word not in src
