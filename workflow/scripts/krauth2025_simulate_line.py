"""One washing-line sample of krauth2025 §4.4.1 (rule krauth2025_simulate_line): the pin density
by naive-pin or direct-pin, with the exact density of Eq. (4.7) averaged over the same
bins (``density_exact``) and on a fine grid (``density_curve``) for the figures."""

import numpy as np

from kinetic import io
from kinetic.samplers import naive_acceptance, sample_line
from kinetic.theory import krauth2025
from kinetic.workflow_support import start, write_output

log = start(snakemake)
job = dict(snakemake.params.job)
data = sample_line(**job)
n, length, sigma = job["n_pins"], job["length"], job["sigma"]


def exact(x):
    return n * krauth2025.pin_density(x, n, length, sigma)


curve = np.linspace(sigma, length - sigma, 2001)
extra = io.make_dataset(
    {
        "density_exact": (
            "x",
            krauth2025.bin_average(exact, data.bin_edges.values),
            "1/length",
            "N pi(x) of Eq. 4.7 averaged over the bin",
        ),
        "density_curve": ("x_curve", exact(curve), "1/length", "N pi(x) of Eq. 4.7"),
        "acceptance_exact": (
            (),
            naive_acceptance(n, length, sigma),
            "1",
            "naive-pin acceptance Z_{N,L} / (L - 2 sigma)^N (Eq. 4.6)",
        ),
    },
    {
        "x": ("x", data.x.values, "length", "pin centre (bin middle)"),
        "x_curve": ("x_curve", curve, "length", "pin centre"),
    },
)
data = data.merge(extra, combine_attrs="override")
write_output(snakemake, data, job["seed"])
log.info(
    "wrote %s: %d configurations (%d started) in %.1f CPU s",
    snakemake.output[0],
    job["samples"] * job["batches"],
    int(data.started.sum()),
    float(data.cpu_seconds.sum()),
)
