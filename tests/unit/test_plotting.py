"""The shared figure helpers: bin averages are exact for polynomials, captions carry the
numbers they are given."""

import numpy as np
import pytest
from scipy.special import erf

from kinetic import plotting
from kinetic.workflow_support import write_caption


def test_bin_average_is_exact_for_polynomials():
    edges = np.array([0.0, 0.5, 2.0, 3.0])
    got = plotting.bin_average(lambda x: x**3 - x, edges)
    exact = np.diff(edges**4 / 4 - edges**2 / 2) / np.diff(edges)
    np.testing.assert_allclose(got, exact, rtol=1e-13)


def test_bin_average_of_a_gaussian_differs_from_its_midpoint_value():
    edges = np.array([1.5, 2.5])
    got = plotting.bin_average(lambda x: np.exp(-(x**2)), edges)[0]
    exact = (erf(2.5) - erf(1.5)) * np.sqrt(np.pi) / 2
    assert got == pytest.approx(exact, rel=1e-10)
    assert got / np.exp(-4.0) > 1.6  # the midpoint value misses the bin mean by 60 %


def test_caption_is_rendered_from_values(tmp_path):
    template = tmp_path / "t.rst"
    template.write_text("k2 = {k2:.3f} ({z:+.1f} sigma)")
    text = write_caption(template, tmp_path / "out" / "c.rst", k2=0.12345, z=-1.26)
    assert text == "k2 = 0.123 (-1.3 sigma)"
    assert (tmp_path / "out" / "c.rst").read_text() == text


def test_every_method_has_a_label():
    assert set(plotting.METHOD_STYLE) == set(plotting.METHOD_LABELS)
