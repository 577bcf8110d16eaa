"""The line ``rotorcosim run`` ends with: its estimate of the staggered scheme's error, readable at every size (an
hour of windmilling estimates 0.001 %, which two decimals printed as "0.00 %")."""
from rotorcosim.master.cli.run import estimate_text


def test_the_estimate_reads_at_every_size():
    assert estimate_text(0.59, "bearing #0 squeeze-film oil temperature") == (
        "; estimated error of the staggered scheme 0.59 % (bearing #0 squeeze-film oil temperature)")
    assert estimate_text(0.0010385, None) == "; estimated error of the staggered scheme 0.001 %"
    assert estimate_text(0.0, None) == "; estimated error of the staggered scheme 0.00 %"
    assert estimate_text(66.2, "x") == "; estimated error of the staggered scheme 66.20 % (x)"
    assert estimate_text(None, "x") == ""
