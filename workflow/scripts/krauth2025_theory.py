"""Exact pin densities of krauth2025 section 4.4.1 for the figures (rules
krauth2025_theory_line and krauth2025_theory_ring): Eq. 4.7 on a line, the ring-to-line
mapping on a ring, bin-averaged on the samplers' bins and on fine grids."""

from kinetic.theory import krauth2025
from kinetic.workflow_support import start, write_output

log = start(snakemake)
curves = dict(snakemake.params.curves)
if snakemake.rule == "krauth2025_theory_ring":
    dataset = krauth2025.ring_dataset(**curves)
else:
    dataset = krauth2025.line_dataset(**curves)
write_output(snakemake, dataset, None, parameters=curves)
log.info("wrote %s (%s)", snakemake.output[0], curves)
