"""The montanero2007 study: which DSMC runs, and how their batches are read back.

The study needs several families of runs of the forced, thermostatted homogeneous gas
of :func:`kinetic.dsmc.simulate_homogeneous` (d = 3 inelastic hard spheres, montanero2007
units: time in τ = λ/v0, field ε* = λ ε, velocities c = V/v0):

``scan``
    one run per α of the config's ``alphas`` at the protocol's field (Figs 1–7, Table 1);
``field``
    the linear-response partner of Fig. 1 (same α, larger ε*);
``hcs``
    zero field (the homogeneous cooling state in scaled variables) for the a2 check;
``error``
    the error-against-run-time study (settings × α);
``extreme``
    fields up to ε* = 0.2 (departure from linear response) and strong dissipation.

Every run is named by a plain string (``alpha030``, ``field_alpha030``,
``hcs_alpha050``, ``error_<setting>_alpha100``, ``extreme_field200_alpha100``); the
names are the keys of :func:`run_plan`, so Snakemake wildcards are looked up, never
parsed.  A run's realizations are split into jobs by :mod:`kinetic.batches`;
realization k always uses stream row k of the run's seed, so batching does not change
the data.
"""

from __future__ import annotations

import copy
from collections.abc import Mapping, Sequence
from typing import Any

from kinetic.studies import Job, backend_arguments, points_job, run_jobs
from kinetic.studies.montanero2007_front import (
    engine_arguments,
    engine_run,
    simulate_batch,
    simulate_batches,
)
from kinetic.theory.montanero2007 import FIG07_QUOTED_SHARES

__all__ = [
    "PROTOCOL_KEYS",
    "alpha_key",
    "check",
    "jobs",
    "run_batches",
    "run_plan",
    "simulate_batch",
    "simulate_batches",
]

PROTOCOL_KEYS = (
    "n_particles",
    "time_step",
    "force_step",
    "selection",
    "splitting",
    "reduced_field",
    "duration",
    "steady_from",
    "sample_interval",
    "sample_stride",
    "realizations",
    "realizations_per_job",
    "cx_max",
    "cx_bins",
)
"""Keys of a run's protocol (the config's ``protocol`` section, overridable per family)."""


def alpha_key(alpha: float) -> str:
    """``0.3 -> 'alpha030'``, ``1.0 -> 'alpha100'`` (restitution to two decimals)."""
    hundredths = round(float(alpha) * 100)
    if abs(hundredths - float(alpha) * 100) > 1e-6 or not 0 < hundredths <= 100:
        raise ValueError(f"restitution {alpha!r} must be in (0, 1] with at most two decimals")
    return f"alpha{hundredths:03d}"


def _field_key(reduced_field: float) -> str:
    thousandths = round(float(reduced_field) * 1000)
    if abs(thousandths - float(reduced_field) * 1000) > 1e-6:
        raise ValueError(f"reduced field {reduced_field!r} must have at most three decimals")
    return f"field{thousandths:03d}"


def _run(protocol: Mapping[str, Any], family: str, restitution: float, **overrides) -> dict:
    run = {**copy.deepcopy(dict(protocol)), **overrides}
    run["family"] = family
    run["restitution"] = float(restitution)
    missing = [key for key in PROTOCOL_KEYS if key not in run]
    if missing:
        raise ValueError(f"montanero2007 run of family {family!r} lacks {missing}")
    return run


def _check_restitution_keys(section: Mapping[str, Any]) -> None:
    """Every restitution of the section names a run (``alpha_key``): refuse one with more
    than two decimals naming its config key, before any run is planned."""
    lists = {
        "alphas": section["alphas"],
        "field_check.restitution": [section["field_check"]["restitution"]],
        "hcs.alphas": section["hcs"]["alphas"],
        "error_study.alphas": section["error_study"]["alphas"],
        "extreme.alphas": section["extreme"]["alphas"],
        "extreme.strong_dissipation": section["extreme"].get("strong_dissipation", []),
    }
    for key, values in lists.items():
        for index, alpha in enumerate(values):
            try:
                alpha_key(alpha)
            except ValueError as error:
                where = key if key.endswith("restitution") else f"{key}[{index}]"
                raise ValueError(f"config key montanero2007.{where} = {alpha!r}: {error}") from None


def run_plan(section: Mapping[str, Any]) -> dict[str, dict[str, Any]]:
    """Every run of the study: ``{name: parameters}`` from the config section.

    ``section`` is the validated ``config["montanero2007"]`` (see
    ``workflow/schemas/montanero2007.schema.yaml``).  Each run's parameters hold the
    protocol keys (:data:`PROTOCOL_KEYS`), ``restitution`` and ``family``.
    """
    _check_restitution_keys(section)
    protocol = section["protocol"]
    plan: dict[str, dict[str, Any]] = {}
    for alpha in section["alphas"]:
        plan[alpha_key(alpha)] = _run(protocol, "scan", alpha)
    field = section["field_check"]
    plan[f"field_{alpha_key(field['restitution'])}"] = _run(
        protocol, "field", field["restitution"], reduced_field=field["reduced_field"]
    )
    for alpha in section["alphas"]:
        name = field_partner(section, alpha)
        if name not in plan:
            plan[name] = _run(
                protocol,
                "bias",
                alpha,
                **{
                    **section["field_bias"].get("overrides", {}),
                    "reduced_field": _bias_field(section),
                },
            )
    hcs = section["hcs"]
    for alpha in hcs["alphas"]:
        plan[f"hcs_{alpha_key(alpha)}"] = _run(
            protocol, "hcs", alpha, **{**hcs.get("overrides", {}), "reduced_field": 0.0}
        )
    error = section["error_study"]
    for setting, overrides in error["settings"].items():
        for alpha in error["alphas"]:
            plan[f"error_{setting}_{alpha_key(alpha)}"] = _run(
                protocol,
                "error",
                alpha,
                **{**error.get("overrides", {}), **overrides},
                setting=setting,
            )
    extreme = section["extreme"]
    for alpha in extreme["alphas"]:
        for reduced_field in extreme["reduced_fields"]:
            name = f"extreme_{_field_key(reduced_field)}_{alpha_key(alpha)}"
            plan[name] = _run(
                protocol,
                "extreme",
                alpha,
                **{**extreme.get("overrides", {}), "reduced_field": reduced_field},
            )
    for alpha in extreme.get("strong_dissipation", []):
        plan[f"extreme_{alpha_key(alpha)}"] = _run(
            protocol, "extreme", alpha, **extreme.get("overrides", {})
        )
    for name, run in plan.items():
        _check_run(name, run)
    _check_references(section)
    return plan


def _bias_field(section: Mapping[str, Any]) -> float:
    return float(section["field_bias"]["reduced_field"])


def field_partner(section: Mapping[str, Any], alpha: float) -> str:
    """Name of the run at restitution ``alpha`` and the larger field of ``field_bias``.

    Beside each scan run it gives the O(eps*^2) bias of the scan's estimates
    (:func:`kinetic.analysis.montanero2007.field_extrapolation`).  The Fig 1 partner
    (``field_check``, the protocol's statistics) serves when it has the same restitution and
    field, so that run is not simulated twice.
    """
    field = section["field_check"]
    if alpha_key(alpha) == alpha_key(field["restitution"]) and float(
        field["reduced_field"]
    ) == _bias_field(section):
        return f"field_{alpha_key(alpha)}"
    return f"bias_{_field_key(_bias_field(section))}_{alpha_key(alpha)}"


def _check_references(section: Mapping[str, Any]) -> None:
    """Figures, the error study and the extreme fields reuse scan runs: those must exist."""
    scan = {alpha_key(alpha) for alpha in section["alphas"]}
    figures = section["figures"]
    wanted = {
        "figures.fig01_alpha": [figures["fig01_alpha"]],
        "field_check.restitution": [section["field_check"]["restitution"]],
        "error_study.alphas": section["error_study"]["alphas"],
        "extreme.alphas": section["extreme"]["alphas"],
        **{f"figures.{key}": figures[key] for key in figures if key.endswith("_alphas")},
    }
    for key, alphas in wanted.items():
        missing = [alpha for alpha in alphas if alpha_key(alpha) not in scan]
        if missing:
            raise ValueError(
                f"config key montanero2007.{key} names restitution {missing}, which is not in "
                f"montanero2007.alphas = {list(section['alphas'])} (that key reuses scan runs)"
            )
    quoted = [
        alpha
        for alpha in FIG07_QUOTED_SHARES
        if alpha_key(alpha) not in {alpha_key(a) for a in figures["fig07_alphas"]}
    ]
    if quoted:
        raise ValueError(
            f"config key montanero2007.figures.fig07_alphas = {list(figures['fig07_alphas'])} "
            f"must hold {quoted}: Fig. 7's caption sets the document's shares there"
        )
    if _bias_field(section) <= section["protocol"]["reduced_field"]:
        raise ValueError(
            f"config key montanero2007.field_bias.reduced_field = {_bias_field(section)} must "
            f"exceed protocol.reduced_field = {section['protocol']['reduced_field']} (the "
            "scan's field)"
        )
    half = section["protocol"]["cx_bins"] // 2
    if half % figures["phi_rebin"]:
        raise ValueError(
            f"config key montanero2007.figures.phi_rebin = {figures['phi_rebin']} must divide "
            f"protocol.cx_bins / 2 = {half}"
        )


def _check_run(name: str, run: Mapping[str, Any]) -> None:
    """Cross-key constraints the schema cannot express; errors name the run and the keys."""
    windows = run["duration"] / run["sample_interval"]
    steps = run["sample_interval"] / run["time_step"]
    for label, ratio, what in (
        ("duration / sample_interval", windows, "a whole number of windows"),
        ("sample_interval / time_step", steps, "a whole number of steps per window"),
    ):
        if abs(ratio - round(ratio)) > 1e-9 * max(1.0, ratio) or round(ratio) < 1:
            raise ValueError(f"montanero2007 run {name}: {label} = {ratio:.6g} must be {what}")
    if run["sample_stride"] > round(steps):
        raise ValueError(
            f"montanero2007 run {name}: sample_stride = {run['sample_stride']} exceeds the "
            f"{round(steps)} steps of a window"
        )
    if not 0 <= run["steady_from"] < run["duration"]:
        raise ValueError(
            f"montanero2007 run {name}: steady_from = {run['steady_from']} must lie in "
            f"[0, duration = {run['duration']})"
        )
    if run["realizations"] < 2:
        raise ValueError(f"montanero2007 run {name}: needs >= 2 realizations for error bars")
    # the engine front's own checks, on the arguments its jobs will get (numpy only)
    from kinetic.dsmc.arguments import check_settings, check_windows

    arguments = engine_arguments(run, seed=0, first=0, count=int(run["realizations"]), label=name)
    try:
        check_settings(**{key: arguments[key] for key in _SETTINGS_KEYS}, kernel="hard_spheres")
        check_windows(**{key: arguments[key] for key in _WINDOW_KEYS})
    except (TypeError, ValueError) as error:
        raise type(error)(
            f"montanero2007 run {name}: {error} (histogram_start is steady_from rounded up "
            "to a window boundary)"
            if "histogram_start" in str(error)
            else f"montanero2007 run {name}: {error}"
        ) from error


_SETTINGS_KEYS = (
    "n_particles",
    "restitution",
    "time_step",
    "dimension",
    "reduced_field",
    "force_step",
    "selection",
    "splitting",
)
"""``simulate_homogeneous``'s arguments that ``check_settings`` judges (and the kernel)."""

_WINDOW_KEYS = ("duration", "sample_interval", "time_step", "sample_stride", "histogram_start")
"""``simulate_homogeneous``'s arguments that ``check_windows`` judges."""


def dsmc_groups(section: Mapping[str, Any], backend: str) -> dict[str, list[str]]:
    """With the ``cuda`` backend, the runs of each family share one job
    (``simulate_batches``): {family: its run names, in plan order}; none on the cpu,
    where a run's realizations are cut into jobs of their own. A ``cuda`` run is one
    batch of every realization (``run_batches``), a few seconds to minutes of GPU time
    against the 4 s a job's process takes to start (``kinetic.cost``)."""
    if backend != "cuda":
        return {}
    groups: dict[str, list[str]] = {}
    for name, run in run_plan(section).items():
        groups.setdefault(str(run["family"]), []).append(name)
    return groups


def group_rule(group: str) -> str:
    """The rule of one group's job (``montanero2007_simulate_dsmc_scan``: one job, a file
    per run)."""
    return f"montanero2007_simulate_dsmc_{group}"


def group_name(group: str) -> str:
    """The group's job under the results root's logs/ (its log and benchmark)."""
    return f"montanero2007/dsmc/{group}"


def group_files(names: Sequence[str]) -> list[str]:
    """The files of a group's runs, relative to the results root: each run's one batch."""
    from kinetic import batches

    return [f"montanero2007/dsmc/{name}/{batches.batch_name(0)}.nc" for name in names]


def single_runs(section: Mapping[str, Any], backend: str) -> list[str]:
    """The runs cut into jobs of their own (every run on the cpu, none on ``cuda``)."""
    grouped = {name for names in dsmc_groups(section, backend).values() for name in names}
    return [name for name in run_plan(section) if name not in grouped]


def check(config: Mapping[str, Any]) -> None:
    """Stop before any job on a plan the schema cannot judge (:func:`run_plan` raises)."""
    if config.get("montanero2007"):
        run_plan(config["montanero2007"])


def run_batches(run: Mapping[str, Any], backend: str = "cpu") -> list:
    """The ``kinetic.batches`` plan of one run: ``realizations_per_job`` at a time, or, with
    the ``cuda`` backend, every realization in one job (one launch on the GPU)."""
    from kinetic import batches

    realizations = int(run["realizations"])
    per_job = realizations if backend == "cuda" else int(run["realizations_per_job"])
    return batches.plan(realizations=realizations, realizations_per_job=per_job)


def jobs(config: Mapping[str, Any]) -> list[Job]:
    """The simulation jobs of the config's montanero2007 section (``kinetic.studies``):
    every run of :func:`run_plan` cut into batches, each ``simulate_batch`` of its
    realizations, stamped with the run's name, family and setting; with the ``cuda``
    backend one job for each family (:func:`dsmc_groups`), whose runs get the arguments,
    seeds and stamps of their own jobs."""
    from kinetic import cost
    from kinetic.seeds import derive_seed

    section = config.get("montanero2007")
    if not section:
        return []
    backend = config.get("backend", "cpu")
    groups = dsmc_groups(section, backend)
    grouped = {name for names in groups.values() for name in names}
    points: dict[str, dict[str, Any]] = {}  # run name -> its group job's point
    found = []
    plan = run_plan(section)
    for name, run in plan.items():
        seed = derive_seed(config["seed"], f"montanero2007/{name}")
        parameters = {"run": name, "family": run["family"], "setting": run.get("setting", "")}
        cut = run_batches(run, backend)
        if name in grouped:
            (job,) = cut
            points[name] = {
                "run": engine_run(run),
                "seed": seed,
                "first": job.first_realization,
                "count": job.n_realizations,
                "label": f"montanero2007 {name}",
                **backend_arguments(config),
                "parameters": parameters,
            }
            continue
        found += run_jobs(
            document="montanero2007",
            rule="montanero2007_simulate_dsmc",
            run=f"montanero2007/dsmc/{name}",
            front="kinetic.studies.montanero2007_front:simulate_batch",
            engines=("dsmc",),
            cut=cut,
            arguments=lambda job, batch, name=name, run=run, seed=seed: {
                "run": engine_run(run),
                "seed": seed,
                "first": job.first_realization,
                "count": job.n_realizations,
                "label": f"montanero2007 {name} {batch}",
                **backend_arguments(config),
            },
            estimate=lambda job, run=run: cost.dsmc_homogeneous(
                **{**run, "realizations": job.n_realizations, **backend_arguments(config)}
            ),
            parameters=parameters,
        )
    for group, names in groups.items():
        group_points = [points[name] for name in names]
        found.append(
            points_job(
                document="montanero2007",
                rule=group_rule(group),
                group=group_name(group),
                outputs=group_files(names),
                front="kinetic.studies.montanero2007_front:simulate_batches",
                points=group_points,
                label=f"montanero2007 dsmc {group} ({len(names)} runs)",
                estimate=cost.dsmc_homogeneous_points(
                    [{**plan[name], "realizations": points[name]["count"]} for name in names],
                    **backend_arguments(config),
                ),
                engines=("dsmc",),
            )
        )
    return found
