"""Extreme cases of the DSMC engine: each works with a stated accuracy.

- A velocity outlier far above every thermal speed: the rigorous bound includes it, so
  its collision rate is exact (no acceptance probability is ever capped at 1), at the
  price of a lower acceptance ratio while it lasts.
- α = 0.1: strong dissipation, large a2 and an overpopulated high-energy tail: the HCS
  runs stably and a2 is measured to better than 1 % (fixed-seed error bar).
- ε* = 0.2: outside linear response. The force dV_x/dt = -(ε/2) V_x² accelerates the
  particles that move against x faster than collisions (rate ~ |c|/√2 per τ) can stop
  them, which gives the marginal a power-law tail towards -x, g(c_x) ~ |c_x|^(-γ):
  crudely γ ≈ 2 + √2 κ/ε* with κ ~ 1/2 (the share of its speed a fast sphere loses per
  collision); measured γ ≈ 5.5 at ε* = 0.2 for 4 < |c_x| < 12. Moments of order >= γ - 1
  do not exist: at ε* = 0.2 the heat flux <c² c_x> has no variance and b'_2, b'_3 no
  mean; at ε* = 0.025 (γ ≈ 30) nothing of the sort matters. The run works (no step
  diverges at the allowed time steps); the departure from linear response is shown.
"""

import numpy as np
import pytest

from kinetic import rng
from kinetic.analysis.checks import tolerance_factor
from kinetic.analysis.statistics import mean_and_sem
from kinetic.dsmc import (
    HomogeneousSettings,
    Samples,
    advance_gas,
    kernels,
    new_gas,
    realization_streams,
    simulate_homogeneous,
)
from kinetic.gas import candidate_coefficient, cross_section


def test_velocity_outlier_collides_at_its_exact_rate():
    d, n, speed, density, window, trials = 3, 300, 60.0, 1.0, 0.004, 3000
    streams = rng.stream_states(81, trials)
    collided, expected = 0, 0.0
    for state in streams:
        velocity = np.empty((d, n))
        kernels.maxwellian(velocity, state, 1.0)
        velocity[:, 0] = [speed, 0.0, 0.0]  # about 35 thermal speeds
        before = velocity[:, 0].copy()
        # exact rate of particle 0 in this configuration: n/(N-1) S sum_j |v_0 - v_j|
        rate = (
            density
            / (n - 1)
            * cross_section(d)
            * np.sum(np.linalg.norm(velocity[:, 1:] - before[:, None], axis=0))
        )
        bounds = np.empty(d + 2)
        kernels.speed_bounds(velocity, 0, n, bounds)
        tally = np.zeros(4, dtype=np.int64)
        kernels.collide_range(
            velocity,
            0,
            n,
            state,
            kernels.Collisions(
                kernels.HARD_SPHERES,
                1.0,
                candidate_coefficient("hard_spheres", d, density, n),
                window,
                True,
                bounds,
                np.zeros(1),
                tally,
            ),
        )
        collided += not np.array_equal(velocity[:, 0], before)
        expected += -np.expm1(-rate * window)
        assert tally[kernels.TALLY_EXCEEDED] == 0
    p = expected / trials
    sem = np.sqrt(p * (1 - p) / trials)
    assert abs(collided / trials - p) < 4 * sem
    # a bound that ignored the outlier (2 x the thermal maximum ~ 11) would cap the
    # outlier's rate at about a sixth of its true value: the test tells the two apart
    assert p > 0.4


def test_outlier_in_a_thermostatted_run_is_absorbed():
    n = 5000
    velocity = np.random.default_rng(82).normal(size=(3, n))
    velocity[:, 0] = [120.0, 0.0, 0.0]  # about 1/3 of the total energy in one particle
    settings = HomogeneousSettings(n_particles=n, restitution=1.0, time_step=0.05)
    gas = new_gas(settings, realization_streams(82, 0, 1)[0], velocity)
    first_bound = gas.bounds[3] + gas.bounds[4]
    advance_gas(gas, 200)  # 10 tau
    assert gas.bounds[3] + gas.bounds[4] < first_bound / 4  # the outlier has thermalised
    samples = Samples(stride=1)
    advance_gas(gas, 200, samples)
    a2 = 4 * samples.moment_sums[4] / samples.moment_sums[0] / 15 - 1
    assert abs(a2) < 0.02  # back to a Maxwellian (statistical error ~ 0.005)


def test_strong_dissipation_alpha_0_1():
    run = simulate_homogeneous(
        n_particles=20000,
        restitution=0.1,
        duration=160.0,
        time_step=0.4,
        sample_interval=8.0,
        seed=83,
        n_realizations=2,
        sample_stride=1,
        histogram_start=16.0,
        speed_max=6.0,
        n_speed_bins=12,
    )
    a2, sem = mean_and_sem(run.a2.isel(time=slice(2, None)).values.ravel())
    assert sem < 0.01 * a2  # stated accuracy: a2 to better than 1 %
    eq_2_16 = 16 * 0.9 * (1 - 2 * 0.01) / (25 + 72 - 0.1 * 33 - 2 * 0.9 * 0.01)
    assert abs(a2 - eq_2_16) < 4 * sem + 0.05 * eq_2_16  # Eq. 2.16 still within 5 %
    # overpopulated tail: |c| > 3 is several times more frequent than for a Maxwellian
    counts = run.speed_counts.sum("realization").values
    tail = (counts[6:].sum() + int(run.speed_overflow.sum())) / run.histogram_observations.sum()
    maxwell_tail = 0.000_535  # P(|c| > 3) = erfc(3) + 6 e^-9 / sqrt(pi) in d = 3
    assert tail > 3 * maxwell_tail


@pytest.mark.parametrize("force_step", ["euler", "exact"])
def test_large_field_works_and_shows_the_departure_from_linear_response(force_step):
    common = dict(
        n_particles=10000,
        restitution=1.0,
        duration=40.0,
        time_step=0.05,
        sample_interval=4.0,
        seed=84,
        n_realizations=8,
        sample_stride=2,
        force_step=force_step,
    )
    response, anisotropy, far_tail = {}, {}, {}
    for field in (0.05, 0.2):
        run = simulate_homogeneous(reduced_field=field, **common).isel(time=slice(2, None))
        response[field] = run.heat_flux.mean("time").values / field
        moments = run.moments.mean("time")
        anisotropy[field] = (moments.sel(moment="cx2") - moments.sel(moment="c2") / 3).values
        far_tail[field] = (run.cx_outside.sel(side="below") / run.histogram_observations).values
    # linear response fails at 0.2: the heat flux per unit field grows in magnitude, every
    # realization's q/ε* at 0.2 lies beyond 5 standard deviations of one realization's at
    # 0.05 (9-14 over eight seeds). At 0.2 q has no variance (the tail above), so its
    # mean's standard error means nothing: one realization in eight may sit far out
    low = np.mean(response[0.05])
    spread = np.std(response[0.05], ddof=1)
    assert np.max(response[0.2]) < low - 5 * spread
    assert low < 0
    # second-order effects: Π_xx ~ ε*² is resolved at 0.2 (20-40 errors) and consistent
    # with 16 times less at 0.05, where 8 realizations hardly resolve it: the 4-sigma band
    # of an error from 8 realizations is Student's, 8.5 errors (with the normal 4, the
    # check failed for one seed in six, the errors' own scatter)
    aniso, aniso_sem = mean_and_sem(anisotropy[0.2])
    small, small_sem = mean_and_sem(anisotropy[0.05])
    assert aniso > 5 * aniso_sem
    band = tolerance_factor(4.0, len(anisotropy[0.05]) - 1) * np.hypot(aniso_sem / 16, small_sem)
    assert abs(aniso / 16 - small) < band
    # the power-law tail: c_x < -6 (a Gaussian gives 1e-17) in every realization at 0.2
    # (1.0e-4 to 1.8e-4 at the least over 12 seeds), hardly ever at 0.05: pooled over 8
    # realizations (1.6e7 observations) it is at least 100 times rarer there than in any
    # realization at 0.2. Over 12 seeds it never occurred at 0.05 (the exact step); one
    # salted seed saw it 3 times in a realization, so "never" was a claim about the seed
    assert np.all(far_tail[0.2] > 1e-5)
    assert np.mean(far_tail[0.05]) < 0.01 * np.min(far_tail[0.2])
