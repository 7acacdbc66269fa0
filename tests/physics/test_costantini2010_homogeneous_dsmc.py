"""Homogeneous DSMC (one collision cell) relaxes the transverse mode at a wrong rate:
collisions between particles anywhere in the box exchange momentum across the mode, so
it decays much faster than in MD, and adding fictive particles (Λ = 1 -> 10) does not
change that."""

from _costantini2010_runs import SIGMAS, analysed, z_score


def test_homogeneous_dsmc_decays_too_fast_whatever_the_fictive_factor():
    one = analysed("dsmc", 500, 1.0, fictive_factor=1, homogeneous=True)
    ten = analysed("dsmc", 500, 1.0, fictive_factor=10, homogeneous=True)
    md = analysed("md", 500, 1.0)
    assert abs(z_score(one, ten)) < SIGMAS
    assert z_score(md, ten) > SIGMAS
    assert float(ten.tau_c) < 0.6 * float(md.tau_c)
