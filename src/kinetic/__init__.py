"""kinetic: engines, theory and figures for kinetic-theory documents on hard-sphere gases."""

from importlib.metadata import PackageNotFoundError, version

try:
    __version__ = version("kinetic")
except PackageNotFoundError:  # running from a source tree that was not installed
    __version__ = "0+unknown"
