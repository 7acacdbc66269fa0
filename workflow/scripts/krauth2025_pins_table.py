"""krauth2025 §4.4.1 in numbers (kinetic.analysis.krauth2025.pins_table; rule
krauth2025_pins_table): the pin densities at the posts and in the bulk, their ratio,
naive-pin's acceptance and the wall-rift pressure of each washing-line sample, beside the
exact values."""

from kinetic import io
from kinetic.analysis import krauth2025 as analysis
from kinetic.workflow_support import start

start(snakemake)
table = analysis.pins_table(
    [io.read_dataset(path) for path in snakemake.input.lines],
    [io.read_dataset(path) for path in snakemake.input.theory],
)
io.write_table(table, snakemake.output.csv, snakemake.output.md, float_format=".5g")
