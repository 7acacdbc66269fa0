"""Values that each key's schema accepts but that contradict other keys, or that an engine
front would refuse, stop the parse (``kinetic.studies.check``) with the keys named. Each
of these used to pass the parse and then fail its jobs at their start, fail the analysis
after every simulation, or write an empty figure."""

import copy
from pathlib import Path

import pytest

from kinetic import studies
from kinetic.config import load_configs

CI = Path(__file__).resolve().parents[2] / "config" / "ci.yaml"


@pytest.fixture(scope="module")
def ci():
    return load_configs([CI])


def _with(config, dotted, value):
    changed = copy.deepcopy(config)
    *path, last = dotted.split(".")
    node = changed
    for key in path:
        node = node[key]
    node[last] = value
    return changed


# (dotted key, value, fragment of the message); the ci config's runs have 3000 steady
# samples, its montanero2007 runs 40 windows of 0.6 τ
REFUSED = [
    # the error-against-CPU study had no run and wrote an empty figure and table
    ("costantini2010.error_restitution", 0.5, "error_restitution = 0.5, which must be among"),
    ("costantini2010.figures.particles", 700, "figures.particles = 700"),
    # every analysis failed after the simulations: blocks of 0 samples
    ("costantini2010.blocks_per_realization", 10_000, "blocks_per_realization = 10000 cuts"),
    # the event-disks jobs failed at their start
    ("krauth2025.disks.n_disks", 3, "start = classic: the classic start is 4 disks"),
    ("krauth2025.disks.snapshot_interval", 2000, "snapshot_interval = 2000 exceeds the duration"),
    # accepted as 0.003 CPU-hours, 10^15 snapshots a realization (about 500 days)
    ("krauth2025.disks.snapshot_interval", 1e-12, "snapshots of a realization of duration"),
    # the error-against-CPU study read NaN at the short checkpoint
    ("visco2008.md.checkpoints", [1, 200], "checkpoints [1] are shorter than error_window"),
    # every montanero2007 job failed at its start (histogram_start is steady_from rounded up)
    ("montanero2007.protocol.steady_from", 23.5, "steady_from"),
]


def test_the_ci_config_passes(ci):
    studies.check(ci)


@pytest.mark.parametrize(("key", "value", "fragment"), REFUSED, ids=[row[0] for row in REFUSED])
def test_contradictory_values_stop_the_parse(ci, key, value, fragment):
    with pytest.raises(ValueError) as error:
        studies.check(_with(ci, key, value))
    assert fragment in str(error.value)


def test_cloning_jobs_are_checked_by_the_fronts_own_checks(ci):
    """A histogram the GPU's shared memory cannot hold stops the parse of a cuda build
    (every cloning job failed at its start), and a transient of exactly one kept
    collision at λ = -1.5 (the study's renewal time, within rounding of the bound) no
    longer fails them."""
    fine = _with(_with(ci, "visco2008.cloning.histogram_bins", 2000), "backend", "cuda")
    with pytest.raises(ValueError, match=r"visco2008.cloning: job .*histogram_bins must be"):
        studies.check(fine)
    studies.check(_with(ci, "visco2008.cloning.histogram_bins", 2000))  # the CPU has no limit
    renewal = _with(ci, "visco2008.cloning.transient", 0)
    studies.check(_with(renewal, "visco2008.cloning.transient_kept_collisions", 1))
