"""kinetic: engines, theory and figures for kinetic-theory documents on hard-sphere gases."""

from importlib.metadata import PackageNotFoundError, version

try:
    __version__ = version("kinetic")
except PackageNotFoundError:  # running from a source tree that was not installed
    __version__ = "0+unknown"

DOCUMENTS = ("visco2008", "montanero2007", "krauth2025", "costantini2010")
"""The four documents: each is a config section, a directory under the results root, a
study module (``kinetic.studies``) and a prefix of its rules' names."""
