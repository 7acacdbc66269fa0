"""Event-driven MD of the cooling granular gas in the stationary representation.

N inelastic hard disks (restitution α) in a periodic square box at density n, run in the
rescaled variables of the homogeneous cooling state: velocities w and time τ with, between
collisions, dr/dτ = w and dw/dτ = +ω0 w (ω0 = ``drag_rate``). The engine's hard-core
dynamics is run in its own time t (straight flights, no drag) in segments of
Δτ = ``sample_interval``: at the start of a segment its velocities v equal w, within the
segment τ − τ_start = ln(1 + ω0 t)/ω0 and w = (1 + ω0 t) v, so the segment lasts
t_seg = (e^{ω0Δτ} − 1)/ω0 of engine time, and at its end every velocity is multiplied by
e^{ω0Δτ} (``HardSphereSystem.run``'s ``scale``, the numbers of ``scale_velocities``: a
common factor only changes the time scale of hard-core dynamics, so this is exact, with
no time-step error). Unlike the
``rescale_every`` thermostat, which resets the temperature to a fixed value, the factor
is prescribed: the temperature is free to relax to T_s with ζ(T_s) = 2ω0.

Observers at every τ_j = equilibration + j Δτ (``kinetic.dsmc.simulate_cooling_modes``
returns the same dataset; see its docstring for the variables). The energy dissipated in
a segment is the segment's loss of Σv²/2 in engine units times e^{ω0Δτ}: a collision at
engine time t loses (1 + ω0 t)² times its loss in w units, and the segment's mean factor
(e^{2ω0τ} over collisions spread evenly in τ: e^{x} sinh(x)/x, x = ω0Δτ) is replaced by
its geometric midpoint e^{x}, which records x²/6 too little (5e-5 at α = 0.8 and Δτ = 0.2
mean free times). The first sample's interval is the equilibration's last segment (NaN
if shorter than an interval), as in the DSMC engine. MD conserves
momentum, but the drag multiplies the round-off momentum by e^{ω0 τ}: whenever it exceeds
``DRIFT_LIMIT`` at a sample the centre-of-mass velocity is subtracted (a uniform shift:
relative motion unchanged) and every event predicted anew.

Units: m = σ = 1, initial temperature T0 = 1, time σ√(m/T0).
"""

from __future__ import annotations

import math
import time
from typing import Any

import numpy as np

from kinetic import io, rng, validate
from kinetic.edmd.layout import X0, V
from kinetic.edmd.system import HardSphereSystem
from kinetic.fourier import mode_sums, mode_terms
from kinetic.jit import kernel
from kinetic.progress import Progress
from kinetic.validate import integer, real

__all__ = ["simulate_cooling_modes", "transverse_modes"]

MODES = ("wy_kx", "wx_ky")

DRIFT_LIMIT = 1e-13
"""Relative total momentum |Σw|/(N√T) above which the centre-of-mass velocity is removed
(round-off is ~1e-16; the drag multiplies it by e^{ω0 Δτ} per segment)."""


def transverse_modes(positions: np.ndarray, velocities: np.ndarray, box_side: float):
    """(modes, norms): Σ_j w_{j,y} e^{i k x_j} and Σ_j w_{j,x} e^{i k y_j} at k = 2π/L, and
    their normalisers Σ w_y², Σ w_x² (positions, velocities: (N, 2) arrays)."""
    k = 2.0 * math.pi / box_side
    modes = np.array(
        [
            np.sum(velocities[:, 1] * np.exp(1j * k * positions[:, 0])),
            np.sum(velocities[:, 0] * np.exp(1j * k * positions[:, 1])),
        ]
    )
    norms = np.array([np.sum(velocities[:, 1] ** 2), np.sum(velocities[:, 0] ** 2)])
    return modes, norms


_OBSERVED = ("temperature", "px", "py", "re_y", "im_y", "re_x", "im_x", "norm_y", "norm_x")
"""The entries of :func:`_observe`'s row: T, Σw/(N√T), the two modes Σ w_y e^{ikx} and
Σ w_x e^{iky} (real, imaginary) and their norms Σ w_y², Σ w_x²."""


@kernel
def _observe(phase, t, box_side, terms, row):
    """The sample of :data:`_OBSERVED` of the disks ``phase`` at engine time ``t``
    (positions x0 + v t), after the mean velocity; ``terms`` (4, n) is a work array
    (``kinetic.fourier.mode_terms``). Sums in slot order: those of
    :func:`transverse_modes` of the positions and velocities but for their rounding."""
    n = phase.shape[0]
    sum_x = 0.0
    sum_y = 0.0
    for i in range(n):
        sum_x += phase[i, V]
        sum_y += phase[i, V + 1]
    mean_x = sum_x / n
    mean_y = sum_y / n
    spread = 0.0
    norm_y = 0.0
    norm_x = 0.0
    inverse_side = 1.0 / box_side  # k x in turns: x / L
    for i in range(n):
        wx = phase[i, V]
        wy = phase[i, V + 1]
        spread += (wx - mean_x) ** 2 + (wy - mean_y) ** 2
        norm_y += wy * wy
        norm_x += wx * wx
        # the rows of phase are strided: gather the columns for the vectorized pass
        terms[0, i] = inverse_side * (phase[i, X0] + wx * t)
        terms[1, i] = inverse_side * (phase[i, X0 + 1] + wy * t)
        terms[2, i] = wx
        terms[3, i] = wy
    for i in range(n):
        terms[0, i], terms[1, i], terms[2, i], terms[3, i] = mode_terms(
            terms[0, i], terms[1, i], terms[2, i], terms[3, i]
        )
    re_y, im_y, re_x, im_x = mode_sums(terms, n)
    temperature = spread / (2.0 * n)
    row[0] = temperature
    row[1] = sum_x / (n * math.sqrt(temperature))
    row[2] = sum_y / (n * math.sqrt(temperature))
    row[3] = re_y
    row[4] = im_y
    row[5] = re_x
    row[6] = im_x
    row[7] = norm_y
    row[8] = norm_x


MAX_HEATING = 4.0
"""Largest temperature (units of T0) a drag may heat the gas to within a run
(``kinetic.theory.costantini2010.heated_temperature``): the stationary representation holds
T at T0; a drag that heats an elastic gas ran away (T = 9 × 10⁶ T0 after 400 time units at
ω0 = 0.02, and a run of 800 did not end)."""


def _advance(system: HardSphereSystem, duration: float, drag_rate: float) -> float:
    """Advance τ by ``duration`` (one segment); return the energy dissipated per particle
    in w units (see the module docstring). The velocities are scaled by e^{ω0Δτ} in the
    pass that rebases the clock (``HardSphereSystem.run``'s ``scale``), and the energy at
    the segment's end is read after it, divided by the factor squared (a relative
    rounding of 10⁻¹⁶ on a loss of about 10⁻³ of the energy a segment). In d = 2 the
    energy per particle Σv²/(2N) is the kinetic temperature."""
    factor = math.exp(drag_rate * duration)
    engine_time = math.expm1(drag_rate * duration) / drag_rate if drag_rate else duration
    before = system.kinetic_temperature()
    system.run(until=system.time + engine_time, scale=factor)
    after = system.kinetic_temperature() / (factor * factor)
    return (before - after) * factor


def simulate_cooling_modes(
    *,
    n_particles: int,
    density: float,
    restitution: float,
    drag_rate: float,
    equilibration: float,
    sample_interval: float,
    n_samples: int,
    seed: int,
    n_realizations: int = 1,
    first_realization: int = 0,
    cell_occupancy: float | None = None,
    label: str | None = None,
):
    """Temperature and transverse modes of the cooling gas by event-driven MD.

    Arguments as in ``kinetic.dsmc.simulate_cooling_modes`` (without the DSMC ones), plus
    ``cell_occupancy`` (passed to ``HardSphereSystem``: speed only). Samples at
    τ_j = equilibration + j·sample_interval; the equilibration is run in segments of at
    most ``sample_interval``. Realization k uses row k of
    ``kinetic.rng.stream_states(seed, first_realization + n_realizations)``.
    Raises ``kinetic.edmd.InelasticCollapseError`` if the gas collapses.
    """
    n_particles = integer("n_particles", n_particles, 2)
    density = real("density", density, 0.0, 0.5, low_open=True)
    restitution = real("restitution", restitution, 0.0, 1.0, low_open=True)
    drag_rate = real("drag_rate", drag_rate, 0.0, 1e6)
    equilibration = real("equilibration", equilibration, 0.0, 1e15)
    sample_interval = real("sample_interval", sample_interval, 0.0, 1e12, low_open=True)
    n_samples = integer("n_samples", n_samples, 1, 10**9)
    seed = validate.seed(seed)
    first_realization, n_realizations = validate.realizations(
        first_realization, n_realizations, count_name="n_realizations"
    )
    if cell_occupancy is not None:
        cell_occupancy = real("cell_occupancy", cell_occupancy, 0.0, 1e6, low_open=True)
    if drag_rate * sample_interval > 0.5:
        raise ValueError(
            f"drag_rate x sample_interval = {drag_rate * sample_interval:.3g} > 0.5: the "
            "velocities would grow by more than e^0.5 within one segment; sample more often"
        )
    from kinetic.theory.costantini2010 import heated_temperature, warn_if_unstable

    duration = equilibration + (n_samples - 1) * sample_interval
    heated = heated_temperature(restitution, density, drag_rate, duration)
    if heated > MAX_HEATING:
        raise ValueError(
            f"drag_rate = {drag_rate!r} heats the gas at restitution = {restitution!r} to "
            f"T = {heated:.4g} T0 within the run ({duration!r} time units; Eq. 12's steady "
            f"T_s = (2 drag_rate/zeta(T0))^2, an elastic gas without bound), more than "
            f"{MAX_HEATING} T0, with the collisions of a run growing as sqrt(T). Use drag_rate "
            "= zeta(T0)/2 (kinetic.theory.costantini2010.drag_rate) to hold T near T0"
        )
    validate.fits_in_memory(  # the samples' arrays, 80 B a sample and realization
        f"n_realizations = {n_realizations} x n_samples = {n_samples}",
        80.0 * n_realizations * n_samples,
    )
    warn_if_unstable(n_particles, density, restitution)
    box_side = math.sqrt(n_particles / density)
    states = rng.stream_states(seed, n_realizations, first_realization)
    sample_times = equilibration + sample_interval * np.arange(n_samples)

    temperature = np.empty((n_realizations, n_samples))
    modes = np.empty((n_realizations, n_samples, 2), dtype=complex)
    norms = np.empty((n_realizations, n_samples, 2))
    dissipated = np.full((n_realizations, n_samples), np.nan)
    momentum = np.empty((n_realizations, n_samples, 2))
    collisions = np.zeros(n_realizations, dtype=np.int64)
    cpu_seconds = np.zeros(n_realizations)
    row = np.empty(len(_OBSERVED))
    terms = np.empty((4, n_particles))
    progress = Progress(
        n_realizations * (n_samples + equilibration / sample_interval),
        label=label or f"md cooling modes N={n_particles} alpha={restitution:g}",
        unit="segments",
    )

    for r, stream in enumerate(states):
        begin = time.process_time()
        system = HardSphereSystem(
            n_particles=n_particles,
            density=density,
            restitution=restitution,
            stream=stream,
            cell_occupancy=cell_occupancy,
        )
        tau = 0.0
        last_loss, last_step = np.nan, 0.0  # the latest equilibration segment
        while tau < equilibration - 1e-12 * max(1.0, equilibration):
            last_step = min(sample_interval, equilibration - tau)
            last_loss = _advance(system, last_step, drag_rate)
            tau += last_step
            progress.update(last_step / sample_interval)
        for j in range(n_samples):
            if j > 0 or equilibration > 0:
                step = sample_times[j] - tau
                lost = _advance(system, step, drag_rate)
                tau = sample_times[j]
                if j == 0:
                    # the first sample closes the equilibration's last segment (the step
                    # here only absorbs its rounding): that segment's loss, if it was a
                    # whole interval, as the DSMC engine records it
                    lost, step = lost + last_loss, step + last_step
                whole = abs(step - sample_interval) <= 1e-9 * sample_interval
                dissipated[r, j] = lost if whole else np.nan
            _observe(system.phase, float(system.clock[0]), box_side, terms, row)
            temperature[r, j] = row[0]
            momentum[r, j] = row[1:3]
            if np.abs(row[1:3]).max() > DRIFT_LIMIT:
                system.remove_drift()
            modes[r, j] = (complex(row[3], row[4]), complex(row[5], row[6]))
            norms[r, j] = row[7:9]
            progress.update(1.0)
        collisions[r] = system.collisions
        cpu_seconds[r] = time.process_time() - begin

    realization_dims = ("realization", "time")
    mode_dims = ("realization", "time", "mode")
    dataset = io.make_dataset(
        {
            "temperature": (realization_dims, temperature, "T0", "granular temperature"),
            "mode_real": (mode_dims, modes.real, "sqrt(T0/m)", "real part of the mode"),
            "mode_imag": (mode_dims, modes.imag, "sqrt(T0/m)", "imaginary part of the mode"),
            "mode_norm": (mode_dims, norms, "T0/m", "sum of the squared velocity component"),
            "dissipated_energy": (
                realization_dims,
                dissipated,
                "T0",
                "energy lost in collisions per particle in the preceding sample interval",
            ),
            "momentum": (
                ("realization", "time", "axis"),
                momentum,
                "1",
                "total momentum / (N sqrt(T))",
            ),
            "collisions": ("realization", collisions, "1", "collisions executed"),
            "cpu_seconds": ("realization", cpu_seconds, "s", "process CPU time"),
        },
        coords={
            "realization": (
                "realization",
                np.arange(first_realization, first_realization + n_realizations),
                "1",
                "realization number",
            ),
            "time": ("time", sample_times, "sigma*sqrt(m/T0)", "rescaled time tau"),
            "mode": ("mode", list(MODES), "1", "w_y e^{ikx} or its x <-> y twin"),
            "axis": ("axis", ["x", "y"], "1", "axis"),
        },
    )
    parameters: dict[str, Any] = {
        "engine": "md",
        "n_particles": n_particles,
        "density": density,
        "restitution": restitution,
        "drag_rate": drag_rate,
        "equilibration": equilibration,
        "sample_interval": sample_interval,
        "n_samples": n_samples,
        "n_realizations": n_realizations,
        "first_realization": first_realization,
        "box_side": box_side,
        "wavenumber": 2.0 * math.pi / box_side,
    }
    return io.stamp(dataset, parameters=parameters, seed=seed)
