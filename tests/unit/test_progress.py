"""Progress lines: periodic, with an ETA, and one line at completion."""

import logging

import pytest

from kinetic.progress import Progress, format_seconds


def test_format_seconds():
    assert format_seconds(42.4) == "42s"
    assert format_seconds(75) == "1m15s"
    assert format_seconds(3725) == "1h02m"


def test_completion_is_logged_once_and_eta_is_finite(caplog):
    caplog.set_level(logging.INFO, logger="kinetic")
    progress = Progress(10, label="run", unit="steps", interval=3600.0)
    progress.update(4)  # first call always logs (no previous line)
    progress.update(3)  # within the interval: silent
    progress.update(3)  # reaches the total: logs 100%
    progress.update(0)  # fronts may report again after the last chunk
    lines = [record.getMessage() for record in caplog.records]
    assert len(lines) == 2, lines
    assert " 40.0% 4/10 steps" in lines[0] and "ETA" in lines[0] and "?" not in lines[0]
    assert "100.0% 10/10 steps" in lines[1]


def test_total_must_be_positive():
    with pytest.raises(ValueError, match="total must be > 0"):
        Progress(0, label="run")
