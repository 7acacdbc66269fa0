"""kinetic.theory.tabulate.visco2008_cloning_reference: the exact solution of visco2008
Eq. (28) that the cloning checks compare with, extrapolated in the quadrature's n^-2."""

import numpy as np

from kinetic.theory.tabulate import coarse_nodes, visco2008_cloning_reference
from kinetic.theory.visco2008_exact import reference_solution

#: mu at lambda = -1.5 and 1, Richardson's combination of 600 and 900 nodes (within
#: 1e-7 of each other's differences; 300 nodes alone are 4.3e-4 and 1.6e-5 off)
CONVERGED_MU = np.array([3.71911529, -0.57655246])


def test_the_extrapolated_reference_is_two_orders_closer_than_its_finer_grid():
    reference = visco2008_cloning_reference(lambdas=[-1.5, 1.0], n_nodes=120)
    alone = reference_solution([-1.5, 1.0], 2, n_nodes=120)[0]
    assert coarse_nodes(120) == 80 and reference.attrs["coarse_nodes"] == 80
    # 120 nodes alone: 2.7e-3 and 1.0e-4 off; extrapolated from 120 and 80: 1.5e-5, 1e-6
    assert np.all(np.abs(alone - CONVERGED_MU) > [2e-3, 8e-5])
    assert np.all(np.abs(reference.mu.values - CONVERGED_MU) < [3e-5, 2e-6])
    # and it never crosses the exact bound mu >= -1/sqrt(2)
    edge = visco2008_cloning_reference(lambdas=[8.0], n_nodes=120)
    assert edge.mu.values[0] >= -1.0 / np.sqrt(2.0)
