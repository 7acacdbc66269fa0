"""Variants of the engines that no document's simulation runs, kept for the benchmarks and
the tests that compare them with the engines (an edit here reruns no simulation: the
workflow's simulation rules depend only on the engine packages and what their fronts
import).

- ``speed_classes``: DSMC with an exact majorant per pair drawn through speed classes,
  against the engine's uniform pairs (``kinetic.bench.dsmc``,
  ``tests/physics/test_dsmc_pair_selections_agree.py``).
"""
