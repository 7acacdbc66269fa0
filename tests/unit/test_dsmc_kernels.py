"""Kernel-level checks of kinetic.dsmc.kernels: random streams, pair selection, bounds."""

import numpy as np
import pytest

from kinetic import rng
from kinetic.dsmc import kernels
from kinetic.experimental.speed_classes import SpeedClasses, collide_speed_classes
from kinetic.gas import candidate_coefficient


def _gas(d, n, seed=1):
    state = rng.stream_states(seed, 1)[0].copy()
    velocity = np.empty((d, n))
    kernels.maxwellian(velocity, state, 1.0)
    bounds = np.empty(d + 2)
    kernels.speed_bounds(velocity, 0, n, bounds)
    return velocity, state, bounds


def test_pair_indices_are_distinct_and_uniform():
    s = [np.uint64(w) for w in rng.stream_states(3, 1)[0]]
    n, draws = 5, 20000
    counts = np.zeros((n, n), dtype=int)
    for _ in range(draws):
        i, j, *words = kernels._pair(n, *s)
        s = [np.uint64(w) for w in words]
        counts[i, j] += 1
    assert np.trace(counts) == 0
    expected = draws / (n * (n - 1))
    off_diagonal = counts[~np.eye(n, dtype=bool)]
    chi2 = np.sum((off_diagonal - expected) ** 2 / expected)
    dof = off_diagonal.size - 1
    assert chi2 < dof + 5 * np.sqrt(2 * dof)


def test_the_second_index_does_not_depend_on_the_first_at_large_n():
    """N = 2²²: whether j falls in the upper half is a fair coin whatever i's parity (one
    draw for both shared 11 bits: j of an even i was never in the upper half, of an odd i
    always). Binomial, 4 standard deviations."""
    s = [np.uint64(w) for w in rng.stream_states(5, 1)[0]]
    n, draws = 2**22, 20000
    upper = np.zeros((2, 2), dtype=int)  # (i parity, j in the upper half)
    for _ in range(draws):
        i, j, *words = kernels._pair(n, *s)
        s = [np.uint64(w) for w in words]
        upper[i % 2, int(j >= n // 2)] += 1
    for parity in (0, 1):
        total = upper[parity].sum()
        assert abs(upper[parity, 1] - total / 2) < 4 * np.sqrt(total / 4), upper


def test_maxwellian_has_zero_momentum_and_exact_energy():
    velocity, _, _ = _gas(3, 1001)
    assert np.all(np.abs(velocity.sum(axis=1)) < 1e-12)
    assert np.sum(velocity**2) / 1001 == pytest.approx(3.0, rel=1e-14)


def test_speed_bounds_are_the_two_largest_speeds():
    velocity, _, bounds = _gas(3, 500)
    speeds = np.sort(np.linalg.norm(velocity - bounds[:3, None], axis=0))
    np.testing.assert_allclose(bounds[:3], velocity.mean(axis=1), atol=1e-15)
    assert bounds[3] == pytest.approx(speeds[-1])
    assert bounds[4] == pytest.approx(speeds[-2])


@pytest.mark.parametrize("d", [2, 3])
def test_bound_stays_rigorous_while_collisions_raise_it(d):
    n = 400
    velocity, state, bounds = _gas(d, n)
    tally = np.zeros(4, dtype=np.int64)
    coefficient = candidate_coefficient("hard_spheres", d, 1.0, n)
    for _ in range(50):
        kernels.collide_range(
            velocity,
            0,
            n,
            state,
            kernels.Collisions(
                kernels.HARD_SPHERES, 1.0, coefficient, 0.2, False, bounds, np.zeros(1), tally
            ),
        )
        speeds = np.sort(np.linalg.norm(velocity - bounds[:d, None], axis=0))
        assert bounds[d] >= speeds[-1] * (1 - 1e-12)
        assert bounds[d] + bounds[d + 1] >= (speeds[-1] + speeds[-2]) * (1 - 1e-12)
    assert tally[kernels.TALLY_RAISED] > 0
    assert tally[kernels.TALLY_EXCEEDED] == 0


@pytest.mark.parametrize("kernel", [kernels.HARD_SPHERES, kernels.VERY_HARD])
def test_stale_bound_is_detected_and_raised(kernel):
    d, n = 3, 200
    velocity, state, bounds = _gas(d, n)
    velocity[:, 0] += [60.0, 0.0, 0.0]  # outlier injected behind the kernel's back
    tally = np.zeros(4, dtype=np.int64)
    kernels.collide_range(
        velocity,
        0,
        n,
        state,
        kernels.Collisions(kernel, 1.0, 0.05, 1.0, False, bounds, np.zeros(1), tally),
    )
    assert tally[kernels.TALLY_EXCEEDED] >= 1
    speeds = np.linalg.norm(velocity - bounds[:d, None], axis=0)
    assert bounds[d] >= speeds.max() * (1 - 1e-12)


def test_ntc_carry_keeps_the_candidate_count_of_split_steps():
    d, n = 3, 1000
    v1, s1, b1 = _gas(d, n)
    tally_once, tally_split = np.zeros(4, dtype=np.int64), np.zeros(4, dtype=np.int64)
    # Maxwell molecules: constant rate, so the number of candidates is deterministic
    kernels.collide_range(
        v1,
        0,
        n,
        s1,
        kernels.Collisions(kernels.MAXWELL, 1.0, 0.001, 1.0, False, b1, np.zeros(1), tally_once),
    )
    v2, s2, b2 = _gas(d, n)
    carry = np.zeros(1)
    for _ in range(10):
        kernels.collide_range(
            v2,
            0,
            n,
            s2,
            kernels.Collisions(kernels.MAXWELL, 1.0, 0.001, 0.1, False, b2, carry, tally_split),
        )
    rate = 0.001 * n * (n - 1) / 2
    assert tally_once[0] == int(rate * 1.0)
    assert abs(tally_split[0] - rate * 1.0) <= 1


def test_force_steps_are_the_euler_and_exact_maps_then_the_thermostat():
    d, n, a = 3, 50, 0.01
    velocity, _, _ = _gas(d, n)
    for exact in (False, True):
        v = velocity.copy()
        factor = 1.0 / (1.0 + a * v[0]) if exact else 1.0 - a * v[0]
        expected = v * factor
        expected -= expected.mean(axis=1, keepdims=True)
        expected *= np.sqrt(2 * 1.5 * n / np.sum(expected**2))
        status, _ = kernels.force_and_thermostat(v, a, exact, 1.5, np.empty(d + 2))
        assert status == kernels.STATUS_OK
        np.testing.assert_allclose(v, expected, rtol=1e-12, atol=1e-13)


@pytest.mark.parametrize("strang", [False, True])
@pytest.mark.parametrize("d", [2, 3])
def test_deferred_thermostat_gives_the_steps_of_the_explicit_one(d, strang):
    """``advance`` applies each step's thermostat in the next step's force update and
    collides the stored velocities W at the rate of the thermostatted ones s (W - u).
    Maxwell molecules collide at a rate that does not depend on the velocities and are
    always accepted, so both ways draw the same random numbers for the same pairs: 40
    steps of ``advance`` (field, inelastic, a snapshot every 7 steps) must equal
    ``collide_range`` then ``force_and_thermostat`` (Strang: around the collisions),
    step by step, to round-off."""
    n, a, alpha, dt = 400, 0.02, 0.6, 0.05
    velocity, state, bounds = _gas(d, n)
    coefficient = 4.0 / n
    reference, reference_state, reference_bounds = velocity.copy(), state.copy(), bounds.copy()
    reference_moments = np.zeros(kernels.N_MOMENTS + 1)
    reference_steps = kernels.Collisions(
        kernels.MAXWELL, alpha, coefficient, dt, False, reference_bounds, np.zeros(1),
        np.zeros(4, dtype=np.int64),
    )  # fmt: skip
    half_step = 0.5 * a if strang else a
    for step in range(1, 41):
        if strang:
            kernels.force_and_thermostat(reference, half_step, True, 1.5, reference_bounds)
        kernels.collide_range(reference, 0, n, reference_state, reference_steps)
        kernels.force_and_thermostat(reference, half_step, True, 1.5, reference_bounds)
        if step % 7 == 0:
            reference_moments[0] += 1.0
            kernels.accumulate_moments(reference, 1.0, reference_moments[1:])
    tally = np.zeros(4, dtype=np.int64)
    collisions = kernels.Collisions(
        kernels.MAXWELL, alpha, coefficient, dt, False, bounds, np.zeros(1), tally
    )
    forcing = kernels.Forcing(a, True, strang, 1.5, 0.0)
    moments = np.zeros(kernels.N_MOMENTS + 1)
    sampling = kernels.Sampling(
        7, 1.0, moments, False, -5.0, 0.1, np.zeros(100), np.zeros(100), 0.1, np.zeros(60)
    )
    status = kernels.advance(velocity, state, collisions, forcing, sampling, np.zeros(5), 40)
    assert status == kernels.STATUS_OK
    assert tally[kernels.TALLY_ACCEPTED] == reference_steps.tally[kernels.TALLY_ACCEPTED] > n
    np.testing.assert_array_equal(state, reference_state)  # the same draws
    np.testing.assert_allclose(velocity, reference, rtol=0, atol=1e-11)
    np.testing.assert_allclose(moments, reference_moments, rtol=1e-10, atol=1e-12)
    speeds = np.sqrt(np.sum((velocity - bounds[:d, None]) ** 2, axis=0))
    assert speeds.max() <= bounds[d] * (1 + 1e-12)  # the bounds hold for what is returned


@pytest.mark.parametrize("kernel", [kernels.HARD_SPHERES, kernels.VERY_HARD])
def test_stored_velocities_collide_at_the_rate_of_the_thermostatted_ones(kernel):
    """Between a force update and the next, ``advance`` collides W, whose thermostatted
    velocities are V = s (W - u), under ``_deferred``: candidates at s**p times W's rate
    (p = 1 hard spheres, 2 very hard), accepted on W's relative speeds. With the same
    random numbers that is V's collision step: the same candidates and collisions, and
    s (W' - u) = V' to round-off. Without the factor s**p the candidates number 1/1.3 or
    1/1.3² of V's and the test fails."""
    d, n, scale, shift = 3, 500, 1.3, np.array([0.2, -0.1, 0.05])
    v, state, _ = _gas(d, n)
    w = v / scale + shift[:, None]
    w_bounds = np.empty(d + 2)
    kernels.speed_bounds(w, 0, n, w_bounds)
    v_bounds = w_bounds.copy()  # the same bound, carried over to V (as apply_thermostat)
    v_bounds[:d] = scale * (w_bounds[:d] - shift)
    v_bounds[d:] *= scale
    p = 1.0 if kernel == kernels.HARD_SPHERES else 2.0
    runs = []
    for velocity, velocity_bounds, factor in ((v, v_bounds, 1.0), (w, w_bounds, scale)):
        tally = np.zeros(4, dtype=np.int64)
        collisions = kernels.Collisions(
            kernel, 0.7, 0.02, 1.0, False, velocity_bounds, np.zeros(1), tally
        )
        kernels.collide_range(
            velocity, 0, n, state.copy(), kernels._deferred(collisions, factor, p)
        )
        runs.append(tally)
    np.testing.assert_array_equal(runs[0], runs[1])
    assert runs[0][kernels.TALLY_ACCEPTED] > n / 10
    np.testing.assert_allclose(scale * (w - shift[:, None]), v, rtol=0, atol=1e-12)


def test_exact_force_step_composes_like_the_flow_it_integrates():
    """``force_update``'s exact step V -> V/(1 + a V_x) is the time-a flow of dV/dt =
    -V_x V: two steps of a/2 equal one step of a (no thermostat: scale 1, u = 0), in d = 2
    and 3, to round-off. The Euler step V (1 - a V_x) does not compose (an O(a²) gap)."""
    a = 0.3
    for d in (2, 3):
        start = np.random.default_rng(d).normal(size=(d, 64))
        halves, whole, euler = start.copy(), start.copy(), start.copy()
        for _ in range(2):
            assert (
                kernels.force_update(halves, 1.0, 0.0, 0.0, 0.0, 0.5 * a, True) == kernels.STATUS_OK
            )
        assert kernels.force_update(whole, 1.0, 0.0, 0.0, 0.0, a, True) == kernels.STATUS_OK
        np.testing.assert_allclose(halves, whole, rtol=1e-13, atol=1e-15)
        for _ in range(2):
            kernels.force_update(euler, 1.0, 0.0, 0.0, 0.0, 0.5 * a, False)
        gap = np.abs(euler - whole).max()
        assert gap > 1e-3


@pytest.mark.parametrize("selection", ["uniform", "speed_classes"])
def test_collisions_follow_the_hard_sphere_rate_in_a_heavy_tailed_gas(selection):
    """Pair selection is exact whatever the velocities: in a gas with a heavy tail (a
    Maxwellian plus 3 % of particles five times faster), short Poisson runs from the same
    frozen start collide each particle at the rate C Σ_j |v_i - v_j| (C = pair_coefficient).
    Over 400 runs of ~25 collisions among 600 particles (the start changes little), the
    participations per speed class against that expectation: χ² with p > 1e-3, and the
    total within 4.5 standard errors; both for ``collide_range`` (uniform pairs under the
    largest relative speed) and ``collide_speed_classes`` (a majorant per pair; it returns
    the particles in another order, so a particle that collided is one whose velocity is
    no longer among the output's)."""
    from scipy import stats

    d, n, runs, coefficient = 3, 600, 400, 1.0e-4
    velocity, _, bounds = _gas(d, n, seed=5)
    velocity[:, : n // 33] *= 5.0
    velocity -= velocity.mean(axis=1, keepdims=True)
    kernels.speed_bounds(velocity, 0, n, bounds)
    g = np.sqrt(((velocity[:, :, None] - velocity[:, None, :]) ** 2).sum(axis=0))
    rate = coefficient * g.sum(axis=1)  # collisions per unit time of each particle
    duration = 25.0 / (0.5 * rate.sum())
    speed = np.sqrt((velocity**2).sum(axis=0))
    edges = np.quantile(speed, np.linspace(0, 1, 9))
    edges[-1] += 1.0
    classes = np.digitize(speed, edges[1:-1])
    observed = np.zeros(8)
    work = SpeedClasses(n)
    states = rng.stream_states(77, runs)
    for r in range(runs):
        v = velocity.copy()
        b = bounds.copy()
        tally = np.zeros(4, dtype=np.int64)
        if selection == "speed_classes":
            collide_speed_classes(
                v,
                states[r],
                kernels.Collisions(
                    kernels.HARD_SPHERES, 1.0, coefficient, duration, True, b, np.zeros(1), tally
                ),
                work.arrays(),
            )
            assert np.allclose(v.sum(axis=1), velocity.sum(axis=1), atol=1e-10)
        else:
            kernels.collide_range(
                v,
                0,
                n,
                states[r],
                kernels.Collisions(
                    kernels.HARD_SPHERES, 1.0, coefficient, duration, True, b, np.zeros(1), tally
                ),
            )
        assert tally[kernels.TALLY_EXCEEDED] == 0
        changed = ~np.isin(velocity[0], v[0])
        observed += np.bincount(classes[changed], minlength=8)
    # a particle hit twice in a run counts once: expectation 1 - exp(-rate t), nearly rate t
    expected = runs * np.bincount(classes, weights=-np.expm1(-rate * duration), minlength=8)
    chi2 = float(np.sum((observed - expected) ** 2 / expected))
    assert stats.chi2.sf(chi2, 8) > 1e-3, (observed, expected)
    assert abs(observed.sum() - expected.sum()) < 4.5 * np.sqrt(expected.sum())
    # power: a selection blind to the speeds (the same rate for every particle) fails
    blind = observed.sum() * np.bincount(classes, minlength=8) / n
    assert stats.chi2.sf(float(np.sum((observed - blind) ** 2 / blind)), 8) < 1e-12


@pytest.mark.parametrize("d", [2, 3])
def test_speed_classes_conserve_the_particles_through_new_layouts(d):
    """One call of about 20 collision times: the elastic gas (α = 1) keeps momentum and
    energy to round-off; the cooling gas (α = 0.5, no thermostat) loses 98 % of its
    energy, so its speeds fall by about 11 classes and the slow classes overflow and are
    laid out again: momentum is still conserved, no particle is lost or duplicated in the
    moves (finite velocities, the same count, conserved momentum) and the reported
    largest speed still bounds every speed."""
    n = 3000
    for alpha in (1.0, 0.5):
        velocity, state, bounds = _gas(d, n, seed=11)
        energy = float(np.sum(velocity**2))
        momentum = velocity.sum(axis=1)
        tally = np.zeros(4, dtype=np.int64)
        coefficient = 1.0 / (n - 1)  # each particle collides at about <|g|> ~ 2
        collide_speed_classes(
            velocity,
            state,
            kernels.Collisions(
                kernels.HARD_SPHERES, alpha, coefficient, 20.0, False, bounds, np.zeros(1), tally
            ),
            SpeedClasses(n).arrays(),
        )
        assert velocity.shape == (d, n) and np.all(np.isfinite(velocity))
        assert tally[kernels.TALLY_EXCEEDED] == 0
        assert tally[kernels.TALLY_ACCEPTED] > 4 * n
        assert np.allclose(velocity.sum(axis=1), momentum, atol=1e-9)
        after = float(np.sum(velocity**2))
        if alpha == 1.0:
            assert after == pytest.approx(energy, rel=1e-11)
        else:
            assert after < 0.1 * energy
        # the class bounds stay valid: the largest speeds reported bound every speed
        speeds = np.linalg.norm(velocity - bounds[:d, None], axis=0)
        assert bounds[d] >= speeds.max() * (1 - 1e-12)


@pytest.mark.parametrize("n_particles", [20, 131, 2000, 2047])
def test_column_groups_hold_every_particle_once_whatever_the_shifts(n_particles):
    """``kernels.column_particle`` (the CUDA backend's groups): for random
    shifts, the G groups of the column layout partition the N particles, each group
    holding m or m - 1 of them, and a group changes its members from one draw to the next."""
    n_rows = max(1, n_particles // 128)
    n_columns = -(-n_particles // n_rows)
    full_rows = n_particles - (n_columns - 1) * n_rows
    generator = np.random.default_rng(n_particles)
    groups = []
    for _ in range(3):
        shifts = generator.integers(0, n_rows, n_columns)
        members = [
            [
                p
                for j in range(n_columns)
                if (p := kernels.column_particle(j, g, shifts[j], n_rows, n_columns, full_rows))
                >= 0
            ]
            for g in range(n_rows)
        ]
        assert sorted(p for group in members for p in group) == list(range(n_particles))
        assert {len(group) for group in members} <= {n_columns, n_columns - 1}
        groups.append(members)
    if n_rows > 1:
        assert groups[0] != groups[1]


def test_group_members_collide_in_place_as_the_group_copied_out():
    """``kernels.collide_members`` (the CUDA backend's ``sparse`` collisions) on one group
    of the columns layout, in place, gives the group's particles bit for bit what
    ``collide_range`` gives them copied out in member order (the same stream, majorant and
    tally), and leaves every other particle alone; ``member_bounds`` is ``speed_bounds``
    of the copy."""
    d, n = 3, 2047
    velocity, state, _ = _gas(d, n)
    n_rows = n // 128
    n_columns = -(-n // n_rows)
    full_rows = n - (n_columns - 1) * n_rows
    key = np.uint64(0x9E3779B97F4A7C15)
    sizes = set()
    for g in range(n_rows):
        members = (n_rows, n_columns, full_rows, g, key)
        size = kernels.group_size(members)
        sizes.add(size)
        index = [kernels._member(0, a, members) for a in range(size)]
        assert min(index) >= 0 and len(set(index)) == size
        copied = velocity[:, index].copy()
        bounds = np.empty(d + 2)
        copied_bounds = np.empty(d + 2)
        kernels.member_bounds(velocity, 0, size, members, bounds)
        kernels.speed_bounds(copied, 0, size, copied_bounds)
        np.testing.assert_array_equal(bounds, copied_bounds)
        coefficient = candidate_coefficient("hard_spheres", d, 1.0, size)
        tallies = np.zeros((2, 4), dtype=np.int64)
        streams = np.stack([state, state])
        before = velocity.copy()
        for k, (v, b, m) in enumerate(((velocity, bounds, members), (copied, copied_bounds, None))):
            collisions = kernels.Collisions(
                kernels.HARD_SPHERES, 0.8, coefficient, 1.0, False, b, np.zeros(1), tallies[k]
            )
            if m is None:
                kernels.collide_range(v, 0, size, streams[k], collisions)
            else:
                kernels.collide_members(v, 0, size, m, streams[k], collisions)
        assert tallies[0, kernels.TALLY_ACCEPTED] > 10
        np.testing.assert_array_equal(tallies[0], tallies[1])
        np.testing.assert_array_equal(velocity[:, index], copied)
        others = np.setdiff1d(np.arange(n), index)
        np.testing.assert_array_equal(velocity[:, others], before[:, others])
        np.testing.assert_array_equal(bounds, copied_bounds)
    assert sizes == {n_columns, n_columns - 1}  # groups with and without the last column
