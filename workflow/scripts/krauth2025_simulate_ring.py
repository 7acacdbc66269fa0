"""Pins on a ring, krauth2025 Fig. 4.13 (rule krauth2025_simulate_ring): the pair density from
independent Markov chains, with the exact density of the ring-to-line mapping averaged
over the same bins (``pair_density_exact``) and on a fine grid (``pair_density_curve``)."""

import numpy as np

from kinetic import io
from kinetic.samplers import sample_ring
from kinetic.theory import krauth2025
from kinetic.workflow_support import start, write_output

log = start(snakemake)
job = dict(snakemake.params.job)
data = sample_ring(**job)
n, length, sigma = job["n_pins"], job["length"], job["sigma"]


def exact(r):
    return krauth2025.ring_pair_density(r, n, length, sigma)


curve = np.linspace(0.0, length, 4001)
extra = io.make_dataset(
    {
        "pair_density_exact": (
            "r",
            krauth2025.bin_average(exact, data.bin_edges.values),
            "1/length",
            "(N - 1) pi_{N-1, L-2 sigma}(r - sigma) averaged over the bin",
        ),
        "pair_density_curve": (
            "r_curve",
            exact(curve),
            "1/length",
            "(N - 1) pi_{N-1, L-2 sigma}(r - sigma)",
        ),
    },
    {
        "r": ("r", data.r.values, "length", "forward distance (bin middle)"),
        "r_curve": ("r_curve", curve, "length", "forward distance"),
    },
)
data = data.merge(extra, combine_attrs="override")
write_output(snakemake, data, job["seed"])
log.info(
    "wrote %s: %d chains, acceptance %.3f, %.1f CPU s",
    snakemake.output[0],
    job["chains"],
    float(data.acceptance.mean()),
    float(data.cpu_seconds.sum()),
)
