"""krauth2025 Fig. 4.13: pins on a ring. Density of the other pins at forward distance r
from a pin, from independent Markov chains (local moves; standard errors across chains),
against the mapping of a pair on the ring onto one pin on a washing line of length
L − 2σ (Eq. 4.7), at each point (dashed) and averaged over each bin (steps: what the
histogram estimates): the pins attract each other as the posts attract them."""

import numpy as np

from kinetic import io, plotting
from kinetic.workflow_support import start

start(snakemake)
data = io.read_dataset(snakemake.input.ring)
theory = io.read_dataset(snakemake.input.theory)
attrs = data.attrs
fig, ax = plotting.figure()
ax.plot(
    theory["r_curve"],
    theory["pair_density_curve"],
    "--",
    color="0.4",
    lw=0.6,
    label=r"$(N-1)\,\pi_{N-1,\,L-2\sigma}(r-\sigma)$",
)
plotting.theory_steps(
    ax,
    theory["bin_edges"].values,
    theory["pair_density_exact"].values,
    lw=0.8,
    label="the same, bin averages",
)
# one bin in ``every``, and every bin of the first and last ``every`` (both contacts)
size = data.sizes["r"]
every = max(1, size // 60)
index = np.arange(size)
shown = (index % every == 0) | (index < every) | (index >= size - every)
plotting.errorbar(
    ax,
    data["r"].values[shown],
    data["pair_density"].values[shown],
    data["pair_density_sem"].values[shown],
    ms=2.5,
    label=f"Markov chains ({int(attrs['realizations'])})",
)
ax.set_xlabel("forward distance $r$ on the ring")
ax.set_ylabel("density of the other pins")
ax.set_title(
    f"$N = {int(attrs['n_pins'])}$ pins on a ring of length $L = {float(attrs['length']):g}$",
    fontsize=8,
)
plotting.legend_outside(ax)
plotting.save(fig, snakemake.output.pdf)
