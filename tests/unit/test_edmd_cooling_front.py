"""kinetic.edmd.simulate_cooling_modes: validation, the segment construction, observers."""

import math

import numpy as np
import pytest

from kinetic import rng
from kinetic.edmd import HardSphereSystem, simulate_cooling_modes
from kinetic.edmd.cooling import transverse_modes
from kinetic.studies.costantini2010 import mean_free_time

DENSITY = 0.005
MEAN_FREE_TIME = mean_free_time(DENSITY)
BASE = {
    "n_particles": 100,
    "density": DENSITY,
    "restitution": 0.9,
    "drag_rate": 1e-4,
    "equilibration": 0.0,
    "sample_interval": 0.2 * MEAN_FREE_TIME,
    "n_samples": 5,
    "seed": 4,
}


@pytest.mark.parametrize(
    ("key", "value", "message"),
    [
        ("n_particles", -5, "n_particles"),
        ("n_particles", 10.5, "n_particles must be an integer"),
        ("restitution", 1.2, "restitution"),
        ("restitution", math.nan, "restitution"),
        ("restitution", "0.5", "restitution must be a real number"),
        ("drag_rate", -1.0, "drag_rate"),
        ("n_samples", 0, "n_samples"),
        ("seed", 1.9, "seed must be an integer"),
        ("seed", True, "seed must be an integer"),
        ("sample_interval", 0.0, "sample_interval"),
        ("density", math.inf, "density"),
    ],
)
def test_bad_arguments_are_refused_before_any_work(key, value, message):
    with pytest.raises((TypeError, ValueError), match=message):
        simulate_cooling_modes(**(BASE | {key: value}))


def test_a_drag_too_strong_for_one_segment_is_refused():
    with pytest.raises(ValueError, match="sample more often"):
        simulate_cooling_modes(**(BASE | {"drag_rate": 1.0}))


def test_a_drag_that_heats_the_gas_away_is_refused_before_any_work(monkeypatch):
    """An elastic gas with drag heats as e^(2 ω0 τ) (T = 9e6 T0 after 400 time units at
    ω0 = 0.02, and a run of 800 did not end); an inelastic one to Eq. 12's T_s. Both
    engines' fronts judge the drag by ``heated_temperature``: the MD's refuses beyond 4 T0,
    and holds a drag of ζ(T0)/2, or a slight one in an elastic gas."""
    from kinetic.edmd import cooling
    from kinetic.theory.costantini2010 import drag_rate, heated_temperature

    def built(*args, **kwargs):
        raise AssertionError("a system was built before the drag was judged")

    monkeypatch.setattr(cooling, "HardSphereSystem", built)
    elastic = BASE | {"restitution": 1.0, "drag_rate": 0.02, "equilibration": 400.0}
    with pytest.raises(ValueError, match=r"restitution = 1\.0 to T = 5\.405e\+07 T0") as error:
        simulate_cooling_modes(**elastic)
    assert "drag_rate = 0.02" in str(error.value)
    hot = BASE | {"drag_rate": 3 * drag_rate(0.9, DENSITY), "equilibration": 1e5}
    assert heated_temperature(0.9, DENSITY, hot["drag_rate"], 1e5) == pytest.approx(9.0, rel=1e-3)
    with pytest.raises(ValueError, match=r"heats the gas at restitution = 0\.9"):
        simulate_cooling_modes(**hot)
    steady = drag_rate(0.9, DENSITY)
    assert heated_temperature(0.9, DENSITY, steady, 1e9) == 1.0
    assert heated_temperature(1.0, DENSITY, 1e-4, 100.0) == pytest.approx(math.exp(0.02))


def test_elastic_run_without_drag_is_the_plain_engine_run():
    arguments = BASE | {"restitution": 1.0, "drag_rate": 0.0, "n_samples": 4}
    dataset = simulate_cooling_modes(**arguments)
    system = HardSphereSystem(n_particles=100, density=DENSITY, stream=rng.stream_states(4, 1)[0])
    system.run(until=3 * arguments["sample_interval"])
    side = math.sqrt(100 / DENSITY)
    modes, norms = transverse_modes(system.positions(), system.velocities(), side)
    np.testing.assert_allclose(dataset.mode_real[0, -1], modes.real, rtol=1e-9, atol=1e-9)
    np.testing.assert_allclose(dataset.mode_imag[0, -1], modes.imag, rtol=1e-9, atol=1e-9)
    # the two runs order their arithmetic differently, and chaos amplifies the round-off
    # over the three intervals: 5e-12 relative in the norms with one seed of three
    np.testing.assert_allclose(dataset.mode_norm[0, -1], norms, rtol=1e-9)
    np.testing.assert_allclose(dataset.temperature, 1.0, rtol=1e-12)
    assert float(np.abs(dataset.momentum).max()) < 1e-12


def test_scaling_every_velocity_only_changes_the_time_scale():
    """The property the stationary representation rests on: velocities times c and the
    duration divided by c give the same trajectory. c = 2 is exact in floating point, so
    the trajectories agree bit for bit; c = 3 rounds, and chaos amplifies the round-off
    (about x1000 per 30 collisions here), so it is compared over a short run: 15 time
    units, 13-32 collisions over eleven seeds, positions within 2e-11 and velocities
    within 2e-10 of each other (a run of 10 held 7-22 collisions, too few to check with
    some seeds; one of 25 reached 2e-9 and 2e-7)."""
    stream = rng.stream_states(9, 1)[0]
    for factor, duration, tolerance in ((2.0, 100.0, 0.0), (3.0, 15.0, 1e-9)):
        reference = HardSphereSystem(n_particles=80, density=0.01, restitution=0.8, stream=stream)
        scaled = HardSphereSystem(n_particles=80, density=0.01, restitution=0.8, stream=stream)
        scaled.scale_velocities(factor)
        reference.run(until=duration)
        scaled.run(until=duration / factor)
        assert scaled.collisions == reference.collisions > 10
        np.testing.assert_allclose(
            scaled.positions(), reference.positions(), rtol=0, atol=tolerance
        )
        np.testing.assert_allclose(
            scaled.velocities(), factor * reference.velocities(), rtol=10 * tolerance
        )


def test_scaling_in_the_rebase_is_scaling_after_the_run():
    """``run(until=..., scale=f)``, the cooling front's segment (the velocities scaled in
    the pass that rebases the clock, one calendar rebuild), gives the state of
    ``run(until=...)`` then ``scale_velocities(f)`` bit for bit, segment after segment:
    the same collisions, phase rows, last collision times and calendar. Also where the
    run stops on a collision count (scaled after the run) and for a zero-length run."""
    stream = rng.stream_states(11, 1)[0]
    fused = HardSphereSystem(n_particles=80, density=0.01, restitution=0.8, stream=stream)
    apart = HardSphereSystem(n_particles=80, density=0.01, restitution=0.8, stream=stream)
    factor = math.exp(0.003 * 2.0)
    for until in (20.0, 40.0, 40.0, 65.0, 90.0):
        fused.run(until=until, scale=factor)
        apart.run(until=until)
        apart.scale_velocities(factor)
    fused.run(collisions=7, scale=1.5)
    apart.run(collisions=7)
    apart.scale_velocities(1.5)
    assert fused.collisions == apart.collisions > 40
    for name in ("phase", "last_collision", "heads", "links", "heap_time", "calendar"):
        np.testing.assert_array_equal(getattr(fused, name), getattr(apart, name), err_msg=name)
    assert fused.time == apart.time
    with pytest.raises(ValueError, match="scale"):
        fused.run(until=100.0, scale=0.0)


def test_mode_observer_and_batching():
    both = simulate_cooling_modes(**(BASE | {"n_realizations": 3}))
    last = simulate_cooling_modes(**(BASE | {"n_realizations": 1, "first_realization": 2}))
    for name in ("mode_real", "mode_imag", "temperature", "dissipated_energy"):
        np.testing.assert_array_equal(both[name][2:], last[name])
    assert list(last.realization.values) == [2]
    assert set(both.mode.values) == {"wy_kx", "wx_ky"}
    # modes of random positions have |w⊥|² ~ Σ w_y²: the ratio is O(1)
    power = (both.mode_real**2 + both.mode_imag**2) / both.mode_norm
    assert 0.0 < float(power.mean()) < 10.0


def test_first_dissipation_is_the_equilibrations_last_interval():
    """The first sample's dissipated energy is that of the interval before it, as in the
    DSMC engine: the equilibration's last segment when it is a whole interval (it was 0,
    which lowered a run's mean dissipation by 1/n_samples), NaN when it is shorter. The
    same gas run one interval less before its first sample records that interval as its
    second sample's."""
    interval = BASE["sample_interval"]
    late = simulate_cooling_modes(**(BASE | {"equilibration": 2 * interval}))
    early = simulate_cooling_modes(**(BASE | {"equilibration": interval, "n_samples": 6}))
    lost = late.dissipated_energy.values[0]
    assert np.all(lost > 0)
    np.testing.assert_allclose(lost, early.dissipated_energy.values[0, 1:], rtol=1e-9)
    partial = simulate_cooling_modes(**(BASE | {"equilibration": 0.5 * interval}))
    assert np.isnan(partial.dissipated_energy.values[0, 0])
    assert np.all(partial.dissipated_energy.values[0, 1:] > 0)


def test_both_engines_warn_of_a_box_beyond_the_shear_instability(caplog, monkeypatch):
    """N = 3000 at nσ² = 0.05 and α = 0.5 lies beyond L_c (the study refuses it; the
    engines, which run it as physics, warn): the transverse modes grow."""
    import logging

    from kinetic.dsmc import inhomogeneous
    from kinetic.edmd import cooling

    def no_run(*args, **kwargs):
        raise RuntimeError("stopped after the warnings")

    monkeypatch.setattr(cooling, "HardSphereSystem", no_run)
    monkeypatch.setattr(inhomogeneous, "new_cooling_gas", no_run)
    monkeypatch.setattr(inhomogeneous, "_compile_outside_the_timers", lambda *a, **k: None)
    unstable = {"n_particles": 3000, "density": 0.05, "restitution": 0.5, "drag_rate": 0.0}
    run = {"equilibration": 0.0, "sample_interval": 1.0, "n_samples": 2, "seed": 1} | unstable
    with caplog.at_level(logging.WARNING, logger="kinetic"):
        with pytest.raises(RuntimeError, match="stopped after"):
            simulate_cooling_modes(**run)
        with pytest.raises(RuntimeError, match="stopped after"):
            inhomogeneous.simulate_cooling_modes(
                **run, fictive_factor=1, cells_per_side=10, time_step=0.5, collision_rule="paper"
            )
    assert caplog.text.count("shear-unstable") == 2
    caplog.clear()
    with (
        caplog.at_level(logging.WARNING, logger="kinetic"),
        pytest.raises(RuntimeError, match="stopped after"),
    ):
        simulate_cooling_modes(**run | {"n_particles": 300})
    assert "shear-unstable" not in caplog.text
