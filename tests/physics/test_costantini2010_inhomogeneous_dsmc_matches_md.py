"""Inhomogeneous DSMC (cells of half a mean free path) reproduces MD's transverse mode:
the same correlation time and amplitude within error, C(0) = 1 in the elastic gas (equal
time velocities are uncorrelated), and the same result with more fictive particles.

MD and DSMC at Λ = 10 run 12 realizations (τ_c to about 3.5 %, so 4 combined errors are
20 % of τ_c; with 3 and 2 realizations they were 45 %), Λ = 40 runs 4. Seeds 5, 6 and 7
gave z(MD − Λ = 10) = 1.85, 1.15 and −0.89, z(Λ = 10 − Λ = 40) = 0.37, −0.22 and 0.99."""

from _costantini2010_runs import SIGMAS, analysed, z_score


def test_elastic_gas_dsmc_agrees_with_md_and_with_more_fictive_particles():
    md = analysed("md", 500, 1.0, realizations=12)
    ten = analysed("dsmc", 500, 1.0, fictive_factor=10, realizations=12)
    forty = analysed("dsmc", 500, 1.0, fictive_factor=40, realizations=4)
    assert abs(z_score(md, ten)) < SIGMAS
    assert abs(z_score(ten, forty)) < SIGMAS
    assert abs(z_score(md, ten, "amplitude")) < SIGMAS
    for result in (md, ten, forty):
        zero, error = float(result.correlation[0]), float(result.correlation_sem[0])
        assert abs(zero - 1.0) < SIGMAS * error
        assert float(result.max_momentum) < 1e-10
