"""costantini2010's figures against 1/N (Figs 4 and 5): the 1/N fits drawn through the
points they were fitted to. The axis is 10³/N and the fits are a + b/N, so a line drawn
as a + b x would be a thousand times too steep (as Figs 4 and 5 were until this test).
And the run labels, from which Fig. 3's legend once listed the same DSMC run twice."""

import numpy as np
import pandas as pd

from kinetic.plotting import costantini2010 as figures

SIZES = (1000, 2000, 3000)
FITS = {("dsmc", 0.8): (0.21, -30.0), ("md", 0.8): (0.20, 45.0)}  # a, b of a + b/N


def _tables():
    rows, fits = [], []
    for (method, alpha), (a, b) in FITS.items():
        for n in SIZES:
            rows.append(
                dict(
                    method=method,
                    alpha=alpha,
                    fictive_factor=10 if method == "dsmc" else np.nan,
                    n_particles=n,
                    nu_star=a + b / n,
                    nu_star_err=0.002,
                )
            )
        fits.append(
            dict(
                method=method,
                alpha=alpha,
                quantity="nu_star",
                intercept=a,
                intercept_err=0.003,
                slope=b,
                slope_err=5.0,
                chi2=0.0,
                dof=1,
            )
        )
    return pd.DataFrame(rows), pd.DataFrame(fits)


def test_the_fit_lines_pass_through_the_points_they_fit():
    table, fits = _tables()
    study = {"dsmc": {"fictive_factor": 10}}
    fig = figures.inverse_n_figure(table, fits, None, study, "nu_star", r"$\nu^*$")
    (ax,) = fig.axes[:1]
    lines = [line for line in ax.get_lines() if len(line.get_xdata()) == 50]
    assert len(lines) == len(FITS)
    for line, (a, b) in zip(lines, FITS.values(), strict=True):
        x, y = (np.asarray(values, float) for values in line.get_data())
        drawn = np.interp([1000.0 / n for n in SIZES], x, y)
        np.testing.assert_allclose(drawn, [a + b / n for n in SIZES], rtol=0, atol=1e-9)
        assert y[0] == a  # at 1/N = 0 the line starts from the intercept


def test_run_labels_give_the_real_particles_per_cell_only_when_asked():
    """Fig. 3's panels differ only in the real particles per cell (whole cells per side:
    1000/13² = 5.9, 2000/18² = 6.2): without it in the label the legend lists DSMC once."""
    import xarray as xr

    labels = {
        figures.run_label(
            xr.Dataset(
                attrs=dict(engine="dsmc", cells_per_side=cells, fictive_factor=10, n_particles=n)
            ),
            per_cell=per_cell,
        )
        for n, cells in ((1000, 13), (2000, 18))
        for per_cell in (True, False)
    }
    assert labels == {
        r"DSMC, $\Lambda=10$, 5.9 real/cell",
        r"DSMC, $\Lambda=10$, 6.2 real/cell",
        r"DSMC, $\Lambda=10$",
    }


def test_the_fit_band_is_the_lines_standard_error():
    """The shaded band of a 1/N fit is the standard error of a + b/N from the fit's
    covariance: through two points the line is exact, so at each point the band is that
    point's own error; at 1/N -> 0 it is the intercept's error (not the slope's, not a sum
    that forgets the anticorrelation of a and b)."""
    from kinetic.analysis import costantini2010 as analysis

    n, errors = np.array([1000.0, 3000.0]), np.array([0.004, 0.001])
    fit = pd.Series(analysis.extrapolate_inverse_n(n, 0.2 + 50.0 / n, errors))
    np.testing.assert_allclose(figures.fit_band(fit, 1.0 / n), errors, rtol=1e-9)
    np.testing.assert_allclose(figures.fit_band(fit, 0.0), fit.intercept_err, rtol=1e-12)
    assert fit.covariance < 0  # the intercept and the slope of points at x > 0
    assert figures.fit_band(fit.drop("covariance"), 0.0) is None  # an older table: no band


def test_the_figure_shades_each_fit_with_its_band():
    table, fits = _tables()
    fits["covariance"] = -0.01
    fig = figures.inverse_n_figure(
        table, fits, None, {"dsmc": {"fictive_factor": 10}}, "nu_star", r"$\nu^*$"
    )
    kinds = [type(collection).__name__ for collection in fig.axes[0].collections]
    assert sum(kind.endswith("PolyCollection") for kind in kinds) == len(FITS)
