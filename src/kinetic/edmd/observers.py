"""Observers of the event-driven MD: preallocated arrays the kernel fills at each collision.

Nothing stores the whole history: memory is bounded by the number of window lengths, the
histogram sizes, the number of sample times and the capacity of the collision record.

- **Counting windows**: the time axis is cut into consecutive windows of each length
  ``window_lengths[w]`` (all windows start at the same time); each particle's collisions
  inside the current window are counted, and when a window closes the counts of all N
  particles go into ``window_histogram[w, n]`` (number of particle-windows with n
  collisions; counts ≥ ``count_bins`` go to ``window_overflow[w]``).
- **Free flights**: the time between two successive collisions of a particle and the
  distance it flew, histogrammed with fixed bin widths, plus the sums
  ``flight_sums`` = [flights, Σ time, Σ time², Σ path, Σ path², time overflow, path overflow].
- **Samples**: temperature Σv²/(dN) and collision count at the increasing times
  ``sample_times`` (absolute simulation times).
- **Walls**: per face (2k + 1 for the upper wall of axis k, 2k for the lower one): hits,
  Σ|v⊥|, Σ 1/|v⊥| (the kinetic and wall-rift pressure estimators of krauth2025, Eq. 4.9,
  4.10).
- **Record**: the last ``record_capacity`` collisions (time, pair, normal relative speed)
  in a ring buffer; slot ``c % capacity`` holds collision number c.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from kinetic import validate
from kinetic.edmd.layout import ObserverBuffers

__all__ = ["Observers"]


@dataclass
class Observers:
    """Observer arrays handed to the kernel; build with ``Observers.create``.

    Shapes: W window lengths, N particles, H count bins, B_t/B_x flight-time/path bins,
    S sample times, R record slots, F = 2 d faces (times and lengths in simulation units).
    """

    window_length: np.ndarray  # (W,) float64
    window_end: np.ndarray  # (W,) float64, absolute end of each current window
    window_count: np.ndarray  # (N, W) int32, counts inside the current windows
    window_histogram: np.ndarray  # (W, H) int64
    window_overflow: np.ndarray  # (W,) int64
    flight_histogram: np.ndarray  # (B_t,) int64
    path_histogram: np.ndarray  # (B_x,) int64
    bin_widths: np.ndarray  # (2,) float64: flight-time bin, free-path bin
    flight_sums: np.ndarray  # (7,) float64
    wall_statistics: np.ndarray  # (6, 3) float64
    sample_times: np.ndarray  # (S,) float64 (working copy, rebased with the clock)
    sample_temperature: np.ndarray  # (S,) float64
    sample_collisions: np.ndarray  # (S,) int64
    sample_cursor: np.ndarray  # (1,) int64
    record_time: np.ndarray  # (R,) float64
    record_pair: np.ndarray  # (R, 2) int32
    record_normal_speed: np.ndarray  # (R,) float64
    observing: bool = False
    absolute_sample_times: np.ndarray = field(default_factory=lambda: np.zeros(0))

    @classmethod
    def create(
        cls,
        n_particles: int,
        *,
        window_lengths=(),
        count_bins: int = 1,
        flight_bin_width: float = 1.0,
        flight_bins: int = 0,
        path_bin_width: float = 1.0,
        path_bins: int = 0,
        sample_times=(),
        record_capacity: int = 0,
    ) -> Observers:
        """Allocate the observers; every size may be 0 (that observer is then off).

        Window lengths, bin widths and sample times are in simulation time/length units.
        Windows start when ``start(t)`` is called.
        """
        window_lengths = np.asarray(window_lengths, dtype=float).reshape(-1)
        sample_times = np.asarray(sample_times, dtype=float).reshape(-1)
        if np.any(~np.isfinite(window_lengths)) or np.any(window_lengths <= 0):
            raise ValueError(f"window lengths must be finite and > 0, got {window_lengths}")
        if not np.all(np.isfinite(sample_times)):  # a NaN blocked every later sample
            raise ValueError(f"sample_times must be finite, got {sample_times}")
        if sample_times.size and np.any(np.diff(sample_times) < 0):
            raise ValueError("sample_times must be increasing")
        for name, value in (
            ("flight_bin_width", flight_bin_width),
            ("path_bin_width", path_bin_width),
        ):
            validate.real(name, value, 0.0, math.inf, low_open=True)
        count_bins = validate.integer("count_bins", count_bins, 1)
        flight_bins = validate.integer("flight_bins", flight_bins, 0)
        path_bins = validate.integer("path_bins", path_bins, 0)
        record_capacity = validate.integer("record_capacity", record_capacity, 0)
        n_windows = window_lengths.size
        return cls(
            window_length=window_lengths,
            window_end=np.full(n_windows, np.inf),
            window_count=np.zeros((n_particles, n_windows), dtype=np.int32),
            window_histogram=np.zeros((n_windows, max(int(count_bins), 1)), dtype=np.int64),
            window_overflow=np.zeros(n_windows, dtype=np.int64),
            flight_histogram=np.zeros(int(flight_bins), dtype=np.int64),
            path_histogram=np.zeros(int(path_bins), dtype=np.int64),
            bin_widths=np.array([flight_bin_width, path_bin_width], dtype=float),
            flight_sums=np.zeros(7),
            wall_statistics=np.zeros((6, 3)),
            sample_times=sample_times.copy(),
            sample_temperature=np.full(sample_times.size, np.nan),
            sample_collisions=np.full(sample_times.size, -1, dtype=np.int64),
            sample_cursor=np.zeros(1, dtype=np.int64),
            record_time=np.zeros(int(record_capacity)),
            record_pair=np.zeros((int(record_capacity), 2), dtype=np.int32),
            record_normal_speed=np.zeros(int(record_capacity)),
            absolute_sample_times=sample_times.copy(),
        )

    def start(self, system) -> None:
        """Start observing ``system`` now: the windows open, flights are recorded, the
        sample times (absolute simulation times) are put on the system's clock."""
        clock = float(system.clock[0])
        self.window_end[:] = clock + self.window_length
        self.window_count[:] = 0
        self.sample_times[:] = self.absolute_sample_times - system.time_origin
        self.sample_cursor[0] = int(np.searchsorted(self.sample_times, clock, side="left"))
        self.observing = True

    def collision_records(self, system) -> dict[str, np.ndarray]:
        """The recorded collisions in order: absolute times, label pairs, normal speeds."""
        capacity = self.record_time.shape[0]
        total = system.collisions
        count = min(capacity, total)
        slots = np.arange(total - count, total) % capacity if capacity else np.zeros(0, int)
        return {
            "time": self.record_time[slots] + system.time_origin,
            "pair": self.record_pair[slots].copy(),
            "normal_speed": self.record_normal_speed[slots].copy(),
        }

    def kernel_arguments(self) -> ObserverBuffers:
        """The observer buffers as ``kernels.advance`` takes them."""
        return ObserverBuffers(
            self.window_length,
            self.window_end,
            self.window_count,
            self.window_histogram,
            self.window_overflow,
            self.flight_histogram,
            self.path_histogram,
            self.bin_widths,
            self.flight_sums,
            self.wall_statistics,
            self.sample_times,
            self.sample_temperature,
            self.sample_collisions,
            self.sample_cursor,
            self.record_time,
            self.record_pair,
            self.record_normal_speed,
        )
