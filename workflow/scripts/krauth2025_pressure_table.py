"""krauth2025 §4.4.3 in numbers (rule krauth2025_pressure_table): the four disks' βP by
every estimator and the finite-N averages of Eqs. (4.13, 4.14) against their references
(``kinetic.analysis.krauth2025.pressure_table``)."""

from kinetic import io
from kinetic.analysis.krauth2025 import pressure_table
from kinetic.workflow_support import start

start(snakemake)
table = pressure_table(io.read_dataset(snakemake.input.md), io.read_dataset(snakemake.input.direct))
io.write_table(table, snakemake.output.csv, snakemake.output.md, float_format=".5g")
