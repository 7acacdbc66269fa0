"""ζ* measured from the energy dissipated in collisions, in MD and DSMC, against Eq. 12; the
paper rule's collision excess; and the noise viscosity above the kinematic one (ν̄*/ν* >
1) at α = 0.7.

The drag is set from Eq. 12 and pins the dissipation rate to 2ω0 T, so the measured ζ* =
2ω0/(n√(2T_s)) tests the steady temperature: ζ*/ζ*(Eq. 12) = T_s^(-1/2), and an engine
whose cooling rate is off by x % settles x % away in ζ*. Errors come from 6 realizations
of 4 blocks (Student's 4σ for 23 degrees of freedom: 4.9 errors)."""

import math

import pytest
from _costantini2010_runs import STUDY, analysed

from kinetic.analysis.checks import tolerance_factor
from kinetic.edmd.system import contact_value
from kinetic.studies import costantini2010 as study
from kinetic.theory import costantini2010 as theory

ALPHA, N, FICTIVE, REALIZATIONS = 0.7, 500, 10, 6
#: what Eq. 12 leaves out of DSMC's ζ*, at most: its first-Sonine a2 (the exact dilute ζ*
#: is 0.06 % below it) and the finite gas's T_s (0.1-0.2 % in ζ*). Seeds 5-10 gave -0.01
#: to +0.15 % (± 0.06 %) with the majorant rule; sampled after the step's collisions
#: (before 2026-12-01) they gave +0.9 to +1.2 %, the Lie step's 3ω0Δτ/2 (ω0Δτ = 0.0063)
EQ_12_ALLOWANCE = 0.002
#: what Enskog's χ · Eq. 12 leaves out of MD's ζ* (MD collides χ = 1.0062 times faster than
#: a dilute gas at nσ² = 0.005): the a2 above, and MD's T_s 0.2-0.4 % above its N → ∞
#: limit (docs/reproduced.md, "MD's density and size"), 0.1-0.2 % in ζ*. Seeds 5-8 gave
#: -0.4 to +0.3 % (± 0.05-0.25 %) against χ · Eq. 12, +0.2 to +0.9 % against Eq. 12
ENSKOG_ALLOWANCE = 0.005
#: the paper rule's excess beyond 1/N̄: its step's first-order T_s shift, e^{-ω0Δτ} at the
#: reported point (+ω0Δτ/2 = 0.32 % in ζ*; test_costantini2010_time_step), its Maxwellian
#: ω_c's a2 bias (3a2/16 = 0.04 % at α = 0.7) and what docs/reproduced.md leaves
#: unexplained; seeds 5-10 gave +0.10 to +0.25 % (± 0.08 %)
EXCESS_ALLOWANCE = 0.004


def _runs(rule):
    return analysed("dsmc", N, ALPHA, fictive_factor=FICTIVE, rule=rule, realizations=REALIZATIONS)


def _band(result, name="zeta_star"):
    return tolerance_factor(4.0, int(result.blocks) - 1) * float(result[f"{name}_err"])


def test_measured_cooling_rate_is_eq_12_in_md_and_majorant_dsmc():
    """DSMC's ζ* is Eq. 12's; MD's is Enskog's χ times it (the dense gas collides faster)."""
    dilute = float(theory.zeta_star(ALPHA))
    chi = contact_value(STUDY["density"], 2)
    assert chi == pytest.approx(1.0062, abs=1e-4)
    md = analysed("md", N, ALPHA, realizations=REALIZATIONS)
    for result, expected, allowance in (
        (md, chi * dilute, ENSKOG_ALLOWANCE),
        (_runs("majorant"), dilute, EQ_12_ALLOWANCE),
    ):
        measured = float(result.zeta_star)
        assert float(result.zeta_star_err) < 0.005 * measured
        assert abs(measured / expected - 1.0) < _band(result) / expected + allowance
    for result in (_runs("majorant"), _runs("paper")):
        # the steady state balances dissipation and drag, ζ(T_s) = 2ω0: at the reported
        # point a step's loss over T is 2 sinh(ω0Δτ)/Δτ, (ω0Δτ)²/6 = 7e-6 above 2ω0, and T
        # is sampled once an interval where the loss is summed over every step (seeds 5-10:
        # -0.001 to +0.023 %; 0.6 % sampled after the collisions, 2ω0(1 + ω0Δτ))
        balance = float(result.zeta_star_balance)
        assert abs(float(result.zeta_star) - balance) < _band(result) + 0.001 * balance


def test_paper_rule_collides_one_over_n_too_often():
    """The paper's rule draws each cell's collisions from the Maxwellian ω_c of its N̄
    simulated particles and so collides 1 + 1/N̄ times too often (docs/reproduced.md,
    costantini2010's cell-size study): 62 a cell here, +1.62 % in ζ* over the majorant
    rule on the same cells and step."""
    paper, majorant = _runs("paper"), _runs("majorant")
    run = study.Run("dsmc", N, ALPHA, FICTIVE, cell_side=0.5, time_step=0.05)
    simulated_per_cell = FICTIVE * run.real_particles_per_cell(STUDY["density"])
    excess = float(paper.zeta_star) / float(majorant.zeta_star) - 1.0
    error = math.hypot(
        float(paper.zeta_star_err) / float(paper.zeta_star),
        float(majorant.zeta_star_err) / float(majorant.zeta_star),
    )
    factor = tolerance_factor(4.0, int(paper.blocks) - 1)
    assert abs(excess - 1.0 / simulated_per_cell) < factor * error + EXCESS_ALLOWANCE
    assert excess > factor * error  # the excess is resolved


def test_fluctuation_dissipation_ratio_exceeds_one_when_inelastic():
    md = analysed("md", N, ALPHA, realizations=REALIZATIONS)
    assert float(md.ratio) - 1.0 > _band(md, "ratio")
