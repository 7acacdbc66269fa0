"""kinetic.rng: derived seeds, independent streams and the jitted draws."""

import numpy as np
import pytest
from numba import njit

from kinetic.rng import (
    derive_seed,
    disk_point,
    exponential,
    normal_pair,
    random_unit_vector,
    stream_states,
    uniform,
    uniform_open,
    unit_vector_3d,
    xoshiro_disk_point,
    xoshiro_normal_pair,
    xoshiro_uniform,
    xoshiro_uniform_open,
    xoshiro_unit_2d,
    xoshiro_unit_3d,
)

_MASK = (1 << 64) - 1


def _xoshiro256plus(words, n):
    """Blackman and Vigna's reference generator, in Python integers."""
    s0, s1, s2, s3 = (int(w) for w in words)
    out = []
    for _ in range(n):
        out.append((s0 + s3) & _MASK)
        t = (s1 << 17) & _MASK
        s2 ^= s0
        s3 ^= s1
        s1 ^= s2
        s0 ^= s3
        s2 ^= t
        s3 = ((s3 << 45) | (s3 >> 19)) & _MASK
    return out


@njit(cache=False)
def _array_uniforms(state, n):
    out = np.empty(n)
    for k in range(n):
        out[k] = uniform(state)
    return out


@njit(cache=False)
def _scalar_uniforms(state, n):
    s0, s1, s2, s3 = state[0], state[1], state[2], state[3]
    out = np.empty(n)
    for k in range(n):
        out[k], s0, s1, s2, s3 = xoshiro_uniform(s0, s1, s2, s3)
    return out


@njit(cache=False)
def _mixed_array(state, n):
    """A sequence of the array-state draws whose scalar twins exist."""
    out = np.empty((n, 6))
    for k in range(n):
        out[k, 0] = uniform_open(state)
        out[k, 1], out[k, 2], out[k, 3] = disk_point(state)
        out[k, 4], out[k, 5] = normal_pair(state)
    return out


@njit(cache=False)
def _mixed_scalar(state, n):
    s0, s1, s2, s3 = state[0], state[1], state[2], state[3]
    out = np.empty((n, 6))
    for k in range(n):
        out[k, 0], s0, s1, s2, s3 = xoshiro_uniform_open(s0, s1, s2, s3)
        out[k, 1], out[k, 2], out[k, 3], s0, s1, s2, s3 = xoshiro_disk_point(s0, s1, s2, s3)
        out[k, 4], out[k, 5], s0, s1, s2, s3 = xoshiro_normal_pair(s0, s1, s2, s3)
    state[0], state[1], state[2], state[3] = s0, s1, s2, s3
    return out


@njit(cache=False)
def _directions(state, n, kind):
    s0, s1, s2, s3 = state[0], state[1], state[2], state[3]
    out = np.zeros((n, 3))
    for k in range(n):
        if kind == 0:
            out[k, 0], out[k, 1], s0, s1, s2, s3 = xoshiro_unit_2d(s0, s1, s2, s3)
        elif kind == 1:
            out[k, 0], out[k, 1], out[k, 2], s0, s1, s2, s3 = xoshiro_unit_3d(s0, s1, s2, s3)
        else:
            out[k, 0], out[k, 1], out[k, 2] = unit_vector_3d(state)
    return out


@njit(cache=False)
def _draw_moments(state, n):
    out = np.zeros(6)
    for _ in range(n):
        u = uniform(state)
        g1, g2 = normal_pair(state)
        e = exponential(state)
        out[0] += u
        out[1] += u * u
        out[2] += g1 + g2
        out[3] += g1 * g1 + g2 * g2
        out[4] += g1 * g2
        out[5] += e
    return out


@njit(cache=False)
def _direction_moments(state, n, d):
    """Mean, second-moment tensor and fourth moment of each component of n draws, and the
    largest departure of |n|^2 from 1."""
    direction = np.empty(d)
    mean, second, fourth = np.zeros(d), np.zeros((d, d)), np.zeros(d)
    norm_error = 0.0
    for _ in range(n):
        random_unit_vector(state, direction)
        mean += direction
        second += np.outer(direction, direction)
        fourth += direction**4
        norm_error = max(norm_error, abs(np.sum(direction * direction) - 1.0))
    return mean / n, second / n, fourth / n, norm_error


def test_generator_is_xoshiro256plus_in_both_state_layouts():
    state = stream_states(11, 1)[0]
    expected = [(x >> 11) * 2.0**-53 for x in _xoshiro256plus(state, 1000)]
    assert _array_uniforms(state.copy(), 1000).tolist() == expected
    assert _scalar_uniforms(state.copy(), 1000).tolist() == expected


def test_scalar_state_draws_follow_the_array_state_stream():
    """The scalar twins (used by loops that keep the state in registers) draw exactly the
    numbers of the array-state draws, rejections included, and leave the same state."""
    array_state = stream_states(5, 1)[0].copy()
    scalar_state = array_state.copy()
    expected = _mixed_array(array_state, 2000)
    drawn = _mixed_scalar(scalar_state, 2000)
    np.testing.assert_array_equal(drawn, expected)
    np.testing.assert_array_equal(scalar_state, array_state)
    assert np.all(drawn[:, 0] > 0.0) and np.all(drawn[:, 0] <= 1.0)
    assert np.all((drawn[:, 3] > 0.0) & (drawn[:, 3] < 1.0))


@pytest.mark.parametrize(("kind", "d"), [(0, 2), (1, 3), (2, 3)])
def test_rejection_directions_are_unit_and_isotropic(kind, d):
    n = 40000
    directions = _directions(stream_states(5, 1)[0].copy(), n, kind)[:, :d]
    np.testing.assert_allclose(np.sum(directions**2, axis=1), 1.0, atol=1e-12)
    # each component: mean 0 (sd 1/sqrt(d n)) and second moment 1/d
    assert np.all(np.abs(directions.mean(axis=0)) < 5.0 / np.sqrt(d * n))
    second = (directions**2).mean(axis=0)
    assert np.all(np.abs(second - 1.0 / d) < 5.0 * np.sqrt(2.0 / (d * d * n)))


def test_derive_seed_is_stable_and_key_dependent():
    assert derive_seed(1, "a") == derive_seed(1, "a")
    assert derive_seed(1, "a") != derive_seed(1, "b")
    assert derive_seed(1, "a") != derive_seed(2, "a")
    assert 0 <= derive_seed(123, "visco2008/md/chunk0") < 2**63


@pytest.mark.parametrize("bad", [-1, 1.5, "7", True])
def test_derive_seed_rejects_non_integer_or_negative_root(bad):
    with pytest.raises((TypeError, ValueError)):
        derive_seed(bad, "key")


def test_streams_are_reproducible_and_prefix_stable():
    a = stream_states(42, 3)
    b = stream_states(42, 5)
    assert a.dtype == np.uint64 and a.shape == (3, 4)
    np.testing.assert_array_equal(a, b[:3])
    assert len({tuple(row) for row in b}) == 5


def test_a_late_range_of_streams_is_the_spawned_children_built_alone():
    """Streams first..first+n-1 are SeedSequence(seed).spawn's children of those indices
    (the rows of a job of late realizations do not depend on the rows before them, and
    cost nothing for them: a first of 10⁹ took 11 s per 10⁶ earlier rows before); a seed
    beyond 63 bits is refused (netCDF attributes hold no more)."""
    spawned = np.random.SeedSequence(42).spawn(9)
    expected = np.array([child.generate_state(4, np.uint64) for child in spawned[5:9]])
    np.testing.assert_array_equal(stream_states(42, 4, 5), expected)
    np.testing.assert_array_equal(stream_states(42, 4, 5), stream_states(42, 9)[5:])
    assert stream_states(42, 2, 10**12).shape == (2, 4)
    with pytest.raises(ValueError, match="too large"):
        stream_states(2**63, 1)


def test_draws_have_the_right_moments():
    n = 200_000
    sums = _draw_moments(stream_states(3, 1)[0], n) / n
    # 5-sigma bounds from the variance of each estimator
    assert abs(sums[0] - 0.5) < 5 * np.sqrt(1 / 12 / n)
    assert abs(sums[1] - 1 / 3) < 5 * np.sqrt(4 / 45 / n)
    assert abs(sums[2]) < 5 * np.sqrt(2 / n)
    assert abs(sums[3] - 2) < 5 * np.sqrt(4 / n)
    assert abs(sums[4]) < 5 * np.sqrt(1 / n)
    assert abs(sums[5] - 1) < 5 * np.sqrt(1 / n)


def test_streams_are_independent():
    """Two streams of one seed, and the first streams of two seeds: uncorrelated at lags
    -2..2 (within 5/√n), and neither is a shifted copy of the other (among 2 × 10⁵ draws of
    53 bits, an independent stream repeats one of another's with probability ~10⁻⁶)."""
    n = 100_000
    pairs = [stream_states(9, 2), np.concatenate([stream_states(9, 1), stream_states(10, 1)])]
    for states in pairs:
        first = _array_uniforms(states[0].copy(), 2 * n) - 0.5
        second = _array_uniforms(states[1].copy(), 2 * n) - 0.5
        for lag in range(-2, 3):
            a, b = first[2 + lag : n + 2 + lag], second[2 : n + 2]
            assert abs(np.mean(a * b)) / (1 / 12) < 5 / np.sqrt(n), lag
        assert not np.intersect1d(first, second).size


@pytest.mark.parametrize("d", [2, 3, 5])
def test_unit_vectors_are_isotropic(d):
    """Uniform on the sphere S^(d-1): <n_i> = 0, <n_i n_j> = δ_ij/d and <n_i^4> = 3/(d(d+2))
    (directions along the axes or the diagonals have the first two right and the fourth
    wrong: 1/d and 1/d^2), each within 5 standard errors of its estimator."""
    n = 100_000
    mean, second, fourth, norm_error = _direction_moments(stream_states(5, 1)[0], n, d)
    assert norm_error < 1e-12
    assert np.all(np.abs(mean) < 5 * np.sqrt(1 / d / n))
    m4, m8 = 3.0 / (d * (d + 2)), 105.0 / (d * (d + 2) * (d + 4) * (d + 6))
    diagonal, off = np.diag(second), second[~np.eye(d, dtype=bool)]
    assert np.all(np.abs(diagonal - 1.0 / d) < 5 * np.sqrt((m4 - 1.0 / d**2) / n))
    assert np.all(np.abs(off) < 5 * np.sqrt(1.0 / (d * (d + 2)) / n))
    assert np.all(np.abs(fourth - m4) < 5 * np.sqrt((m8 - m4**2) / n))


def _splitmix64(z):
    """Vigna's splitmix64 in Python integers: ``(output, next counter)``."""
    z = (z + 0x9E3779B97F4A7C15) & _MASK
    x = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & _MASK
    x = ((x ^ (x >> 27)) * 0x94D049BB133111EB) & _MASK
    return x ^ (x >> 31), z


def test_thread_states_are_splitmix64_of_the_row_and_index_and_all_distinct():
    """The GPU engines' per-thread streams (kinetic.rng.thread_state, the same source on
    both targets): the documented splitmix64 construction, deterministic, and distinct
    for 10⁵ threads of a row and between rows; the first uniforms of neighbouring threads
    are uncorrelated."""
    from kinetic.rng import thread_state

    rows = stream_states(17, 2)
    key = [int(w) for w in rows[0]]
    index = 12345
    z = key[0] ^ ((index * 0x94D049BB133111EB) & _MASK)
    expected = []
    for k in range(4):
        value, z = _splitmix64(z)
        expected.append(value ^ key[k + 1] if k < 3 else value)
    assert [int(w) for w in thread_state(*rows[0], index)] == expected

    @njit
    def states(row, count):
        out = np.empty((count, 4), dtype=np.uint64)
        for i in range(count):
            out[i] = thread_state(row[0], row[1], row[2], row[3], i)
        return out

    count = 100_000
    first, second = states(rows[0], count), states(rows[1], count)
    assert np.array_equal(first, states(rows[0], count))
    assert np.unique(np.concatenate([first, second]), axis=0).shape[0] == 2 * count
    assert first.any(axis=1).all()
    uniforms = np.array([xoshiro_uniform(*state)[0] for state in first[:20_000]])
    correlation = np.corrcoef(uniforms[:-1], uniforms[1:])[0, 1]
    assert abs(correlation) < 5 / np.sqrt(uniforms.size)
    assert abs(uniforms.mean() - 0.5) < 5 * np.sqrt(1 / 12 / uniforms.size)
