"""Estimators with error bars, cumulants, histograms, Legendre transforms and fits."""
