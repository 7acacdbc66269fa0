"""ζ* measured from the energy dissipated in collisions, in DSMC and MD, against Eq. 12
(first Sonine with van Noije-Ernst's a2: percent-level offsets are expected), and the
noise viscosity exceeds the kinematic one (ν̄*/ν* > 1) at α = 0.7."""

from _costantini2010_runs import analysed

from kinetic.theory import costantini2010 as theory


def test_measured_cooling_rate_is_eq_12_within_a_few_per_cent():
    expected = float(theory.zeta_star(0.7))
    for result in (analysed("dsmc", 500, 0.7, fictive_factor=10), analysed("md", 500, 0.7)):
        measured, error = float(result.zeta_star), float(result.zeta_star_err)
        assert error < 0.01 * measured
        assert abs(measured / expected - 1.0) < 0.05
        # the steady state balances dissipation and drag: ζ(T_s) = 2ω0
        assert abs(measured - float(result.zeta_star_balance)) < 4 * error + 0.01 * measured


def test_fluctuation_dissipation_ratio_exceeds_one_when_inelastic():
    md = analysed("md", 1000, 0.7, realizations=3)
    assert float(md.ratio) - 1.0 > 2.0 * float(md.ratio_err)
