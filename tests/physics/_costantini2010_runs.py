"""Small fixed-seed runs shared by the costantini2010 physics tests (not a test module)."""

import functools

from kinetic import dsmc, edmd
from kinetic.analysis.costantini2010 import analyse_run
from kinetic.studies import costantini2010 as study

SIGMAS = 4.0

STUDY = {
    "density": 0.005,
    "a2": "van_noije_ernst",
    "sample_interval": 0.1,
    "transient": 10.0,
    "duration": 150.0,
    "min_duration": 300.0,
    "dsmc": {"collision_rule": "paper"},
}


@functools.cache
def analysed(
    engine,
    n_particles,
    restitution,
    *,
    fictive_factor=1,
    homogeneous=False,
    cell_side=0.5,
    time_step=0.05,
    realizations=2,
    seed=5,
    rule="paper",
):
    """``analyse_run`` of a short run (4 blocks per realization)."""
    run = study.Run(
        engine,
        n_particles,
        restitution,
        fictive_factor if engine == "dsmc" else 1,
        homogeneous=homogeneous,
        cell_side=None if engine == "md" or homogeneous else cell_side,
        time_step=None if engine == "md" else time_step,
    )
    settings = STUDY | {"dsmc": {"collision_rule": rule}}
    arguments = run.engine_arguments(settings)
    front = dsmc.simulate_cooling_modes if engine == "dsmc" else edmd.simulate_cooling_modes
    dataset = front(**arguments, seed=seed, n_realizations=realizations)
    return analyse_run(
        dataset,
        transient=STUDY["transient"] * study.mean_free_time(STUDY["density"]),
        max_lag=3.0,
        blocks_per_realization=4,
        fit_start=0.4,
        fit_stop=0.2,
    )


def z_score(a, b, name="tau_c"):
    """Difference of ``name`` between two analysed runs in combined standard errors."""
    difference = float(a[name]) - float(b[name])
    return difference / (float(a[f"{name}_err"]) ** 2 + float(b[f"{name}_err"]) ** 2) ** 0.5
