"""visco2008 Figs 1, 2, 10, 12: histograms are compared with bin averages of the theory,
(S(a) - S(b))/(b - a) from the survival functions S; these must be the integrals of the
densities of Eqs. (9), (14), (A1) and (D3), with S(0) = 1 (normalisation)."""

import numpy as np
import pytest

from kinetic import plotting
from kinetic.analysis import collision_statistics
from kinetic.theory import visco2008

PAIRS = [
    (visco2008.free_flight_time_survival, visco2008.free_flight_time_pdf),
    (visco2008.weighted_free_flight_time_survival, visco2008.weighted_free_flight_time_pdf),
    (visco2008.free_path_survival, visco2008.free_path_pdf),
    (visco2008.maxwell_free_path_survival, visco2008.maxwell_free_path_pdf),
]


@pytest.mark.parametrize(("survival", "density"), PAIRS)
def test_bin_averages_from_survival_equal_quadrature_of_the_density(survival, density):
    grid = np.linspace(0.0, 2.5, 26)  # the default config's spacing, 0.1
    tabulated = survival(grid, 2)
    assert tabulated[0] == pytest.approx(1.0, abs=1e-10)  # the density is normalised
    edges = np.linspace(0.0, 2.0, 9) + 0.037  # bins not aligned with the grid
    edges[0] = 0.0  # the first bin touches x = 0, where Eq. (14) has an x ln x term
    averaged = collision_statistics.bin_averaged_density(grid, tabulated, edges)
    reference = plotting.bin_average(
        lambda x: density(x.ravel(), 2).reshape(x.shape), edges, points=16
    )
    np.testing.assert_allclose(averaged, reference, rtol=5e-5)


def test_free_path_density_is_finite_at_zero():
    # Eq. (14) at x = 0: <r²/v> l over the Maxwellian, 1.2193 (d = 2); (D3): π/2
    assert visco2008.free_path_pdf(np.array([0.0]), 2)[0] == pytest.approx(1.21930, abs=5e-5)
    assert visco2008.maxwell_free_path_pdf(np.array([0.0]), 2)[0] == pytest.approx(np.pi / 2)
