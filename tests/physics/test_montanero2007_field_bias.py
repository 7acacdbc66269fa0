"""montanero2007 Figs 3, 4, Table 1: the protocol's finite field biases the Sonine
coefficients at O(eps*^2). At alpha = 0.3 the bias of b'_3 is resolved by two fixed-seed
runs at eps* = 0.05 and 0.1, with the sign the default build measures at eps* = 0.025 and
0.05 (+0.24 +- 0.03), while b'_1 (i.e. kappa') moves a hundred times less relative to its
value. b'_3 weighs the far tail, so its error from few realizations scatters widely: with
16 realizations a seed pair gave 1.2 to 7 standard errors; with 48, 3.5 to 10 over nine
seed pairs (the test's is one of them). The check is a one-sided detection of a positive
bias at 3 standard errors (were there no bias, 0.1 % of seeds would pass it)."""

from _montanero2007_runs import steady_run

from kinetic.analysis import montanero2007 as analysis


def test_b3_carries_a_resolved_positive_field_bias():
    common = {"restitution": 0.3, "n_particles": 4000, "realizations": 48, "duration": 42.0}
    low, high = (
        analysis.summary_row(None, steady_run(reduced_field=field, seed=seed, **common))
        for field, seed in ((0.05, 21), (0.1, 22))
    )
    out = analysis.field_extrapolation(low, high)
    z_b3 = out["b3_full_bias"] / out["b3_full_bias_err"]
    assert z_b3 > 3.0, out
    # relative to the value, the bias of b'_3 exceeds that of b'_1 (kappa') many times;
    # the value is the one measured at the lower field (b'_3 = 2.7 +- 0.13 for one salted
    # seed pair, whose extrapolation to zero field, -0.3 +- 0.7, resolved nothing)
    relative_b3 = out["b3_full_bias"] / low["b3_full"]
    relative_b1 = abs(out["b1_full_bias"]) / low["b1_full"]
    assert relative_b3 > 3 * relative_b1, (out, low)
