"""The simulate front: reproducible, independent of batching, conventions of kinetic.io."""

import numpy as np

from kinetic import io
from kinetic.edmd import simulate

PROTOCOL = {
    "n_particles": 200,
    "density": 0.02,
    "seed": 12,
    "duration": 20.0,
    "windows": [1.0, 5.0],
    "checkpoints": [10.0, 20.0],
    "equilibration": 5.0,
}


def _values(dataset):
    return {name: dataset[name].values for name in dataset.data_vars if name != "cpu_time"}


def test_same_seed_same_data_and_batches_do_not_matter():
    whole = simulate(realizations=3, **PROTOCOL)
    again = simulate(realizations=3, **PROTOCOL)
    first = simulate(realizations=1, **PROTOCOL)
    rest = simulate(realizations=2, first_realization=1, **PROTOCOL)
    for name, value in _values(whole).items():
        np.testing.assert_array_equal(value, _values(again)[name], err_msg=name)
        joined = np.concatenate([first[name].values, rest[name].values])
        np.testing.assert_array_equal(value, joined, err_msg=name)
    assert list(rest["realization"].values) == [1, 2]


def test_dataset_follows_the_conventions_and_counts_add_up():
    dataset = simulate(realizations=2, **PROTOCOL)
    io.check_conventions(dataset)
    assert io.parameters_of(dataset)["density"] == 0.02
    assert dataset.attrs["seed"] == 12
    histogram = dataset["window_histogram"].values  # (realization, checkpoint, window, count)
    counts = np.arange(histogram.shape[-1])
    windows_per_run = np.floor(
        dataset["checkpoint"].values[:, None] / dataset["window"].values[None, :] + 1e-9
    )
    # every complete window contributes one count per particle
    np.testing.assert_array_equal(
        histogram.sum(axis=-1), np.broadcast_to(windows_per_run * 200, histogram.shape[:-1])
    )
    # counts in windows never exceed twice the collisions (each involves two particles)
    assert np.all((histogram * counts).sum(axis=-1) <= 2 * dataset["collisions"].values[:, :, None])
    assert dataset["window_overflow"].values.sum() == 0


def test_bad_systems_are_refused_without_building_one(monkeypatch):
    import pytest

    from kinetic.edmd.system import HardSphereSystem

    def built(*args, **kwargs):
        raise AssertionError("a system was built before the arguments were validated")

    monkeypatch.setattr(HardSphereSystem, "__init__", built)
    with pytest.raises(ValueError, match="close packing"):
        simulate(realizations=1, **{**PROTOCOL, "density": 5.0})
    with pytest.raises(TypeError, match="n_particles must be an integer"):
        simulate(realizations=1, **{**PROTOCOL, "n_particles": 100.5})


def test_windows_that_end_at_a_checkpoint_are_all_counted():
    """Windows whose lengths divide the checkpoints (every config's): each realization
    counts every complete window, the last included, whose end (a sum of window lengths)
    rounds a few ulps either side of the checkpoint; one beyond it was dropped, by chance
    (about half the realizations lost the last window of some length, and a window as
    long as the run left a realization with no count at all)."""
    protocol = PROTOCOL | {"windows": [1.0, 2.0, 5.0, 10.0, 20.0], "checkpoints": [10.0, 20.0]}
    dataset = simulate(realizations=6, **protocol)
    complete = np.floor(dataset["checkpoint"].values[:, None] / dataset["window"].values[None, :])
    counted = dataset["window_histogram"].values.sum(axis=-1)
    np.testing.assert_array_equal(counted, np.broadcast_to(complete * 200, counted.shape))


def test_every_realization_counts_in_windows_of_the_same_simulated_time():
    """Windows are in Enskog's mean free time, the same in every realization. They were in
    the mean free time each realization measured while equilibrating (1.4 % apart at 10
    collisions a particle), and the pooled count histogram then mixed windows of different
    lengths: k2 came out 0.0098 high at t = 50 in the default build."""
    from kinetic.edmd.system import enskog_collision_frequency

    dataset = simulate(realizations=3, **PROTOCOL)
    tau = 1.0 / enskog_collision_frequency(PROTOCOL["density"], 2)
    expected = np.broadcast_to(np.asarray(PROTOCOL["windows"]) * tau, (3, 2))
    np.testing.assert_allclose(dataset["window_time"].values, expected, rtol=1e-15)
    measured = dataset["equilibration_mean_free_time"].values
    assert np.ptp(measured) > 0  # the measured ones differ: they no longer set the windows
    production = dataset["production_time"].values[:, -1]
    np.testing.assert_allclose(production, PROTOCOL["duration"] * tau, rtol=1e-9)
