# Shared by every document: config validation, the results root, the target registry,
# seeds, code inputs, planned resources, and the helpers of report.smk and targets.smk.
import os
from pathlib import Path

from snakemake.exceptions import WorkflowError

from kinetic.config import ConfigError, claim_root, results_root, validate_config
from kinetic.seeds import derive_seed
from kinetic.sources import STAMPS, code_stamps, front_sources, script_sources

from kinetic import DOCUMENTS, studies

try:
    validate_config(
        config, Path(workflow.basedir) / "workflow/schemas/config.schema.yaml"
    )
    studies.check(config)  # what the schema cannot judge, study by study
except (ConfigError, ValueError) as error:
    raise WorkflowError(str(error)) from None

RESULTS = results_root(config)
"""This config's results root (config key ``results``): every file the build writes lies
under it, so that builds of two configs never overwrite each other's results."""


def results_file(path):
    """``path`` (relative, wildcards allowed) under this config's results root."""
    return f"{RESULTS}/{path}"


def log_file(path):
    """``path`` under the logs folder of this config's results root."""
    return f"{RESULTS}/logs/{path}"


BATCH = r"batch[0-9]{4}"


"""Wildcard constraint of {batch}, the stem of one job's file of a run
(<results>/<document>/<engine>/<run>/batchNNNN.nc, kinetic.batches.batch_name), in every
document."""


def drop_default_submission_limit(scheduler):
    """Run without Snakemake's default cap of 100 job submissions a second.

    With any cap, every scheduling pass starts a timer that runs another pass one timespan
    later, and that pass starts another: each finished job adds a chain, so the passes
    multiply (about 27,000 in a 7-minute ci build, each re-reading the size of every
    ready job's inputs; 8 % of the build's CPU went to the main process). Our jobs come
    nowhere near 100 a second. A cap given explicitly (any other value) is kept. The
    scheduler exists only once the DAG is built, hence the call from ``onstart``.
    """
    limiter = getattr(scheduler, "job_rate_limiter", None)
    if limiter is not None and (limiter.max_jobs, limiter.timespan) == (100, 1):
        scheduler.job_rate_limiter = None


onstart:
    # the build holds Snakemake's lock: temporary files under its results root are orphans
    # of writers killed in an earlier build (kinetic.io writes to .<name>.<pid>.tmp, then
    # renames); the marker tells builds of configs whose roots contain this one to keep out
    import sys
    from kinetic.io import remove_orphans
    from kinetic.sources import forget_earlier_codes

    changes = claim_root(RESULTS, config)
    if changes:
        shown = "\n  ".join(changes[:8]) + ("\n  ..." if len(changes) > 8 else "")
        print(
            f"note: {RESULTS} was last built by a config that differs in {len(changes)} "
            f"setting(s):\n  {shown}\nthe jobs they change are rebuilt here, replacing "
            "those files; a config of its own keeps both under a `results` root of its own",
            file=sys.stderr,
        )
    for orphan in remove_orphans(RESULTS):
        print(f"removed {orphan}, left by a killed job", file=sys.stderr)
    drop_default_submission_limit(getattr(workflow, "scheduler", None))
    # what this build makes may come from the code the sources hold now: a return to an
    # earlier code reruns it (kinetic.sources._refresh_stamp; every job does it too)
    forget_earlier_codes(STAMPS)


# ---------------------------------------------------------------- target registry
# Rule files register each figure/table they can build: provide(id, file, ...).
TARGETS = {}


def provide(target_id, *paths):
    """Register the files of one figure or table under its id, e.g. 'visco2008/fig03'."""
    TARGETS[target_id] = list(paths)


def figure_files(paper, name):
    """The PDF and its PNG twin: <results>/<paper>/<name>.pdf|png."""
    return [results_file(f"{paper}/{name}.pdf"), results_file(f"{paper}/{name}.png")]


def table_files(paper, name):
    """The CSV and its Markdown twin: <results>/<paper>/<name>.csv|md."""
    return [results_file(f"{paper}/{name}.csv"), results_file(f"{paper}/{name}.md")]


def requested_target_ids():
    """The ids selected by config['targets'] ('all' means every registered one)."""
    wanted = config["targets"]
    if wanted == "all":
        return sorted(TARGETS)
    missing = [target for target in wanted if target not in TARGETS]
    if missing:
        raise WorkflowError(
            f"config key targets asks for {missing}, which this checkout cannot build yet; "
            f"available: {sorted(TARGETS)}"
        )
    return list(wanted)


def all_targets(wildcards):
    """Input function of rule all."""
    return [path for target in requested_target_ids() for path in TARGETS[target]]


def fails_on_checks(document):
    """Whether a failed check of ``document`` stops the build (config key fail_on_checks):
    the ``fail`` param of the rule that writes the document's checks.csv."""
    return document in config["fail_on_checks"]


def paper_targets(paper):
    """Every registered file of one paper (input of the per-paper rule)."""
    return [
        path
        for target, paths in sorted(TARGETS.items())
        if target.split("/")[0] == paper
        for path in paths
    ]


# ---------------------------------------------------------------- seeds and code inputs
def job_seed(key):
    """Seed of the job named ``key``, derived from the root seed (kinetic.rng)."""
    return derive_seed(config["seed"], key)


def code_inputs(paths):
    """The stamps of ``paths`` (source files), as inputs of rules, under the working
    directory's ``kinetic.sources.STAMPS``, one file per source, whose modification time
    moves when the source's code changes but not for an edit of its comments or
    docstrings. Deleting them is safe: they come back with their sources' modification
    times."""
    return code_stamps(paths, workflow.basedir, STAMPS)


def script_code(name):
    """workflow/scripts/<name>.py and every package file it runs (``kinetic.sources``,
    read from its imports), as stamps: inputs of the rules that join, analyse and plot
    results, so an edit of the code of a script or of what it calls reruns exactly the
    rules that run it."""
    script = Path(workflow.basedir) / "workflow" / "scripts" / f"{name}.py"
    return code_inputs([script, *script_sources(script)])


def caption_template(name):
    """The caption template workflow/report/<name>.rst, an input of the figure rule that
    renders it with numbers from the data (kinetic.workflow_support.write_caption), named
    relative to the working directory: Snakemake keeps the names of a job's inputs, and
    an absolute one reran 14 figure rules in a checkout moved elsewhere."""
    template = Path(workflow.basedir) / "workflow" / "report" / f"{name}.rst"
    return os.path.relpath(template, os.getcwd())


def rendered_caption(document, name):
    """The caption a figure rule renders from its data, for report(caption=...).

    Snakemake resolves a relative caption path against the rule file's directory, which is
    the source tree, not the working directory (--directory); the rendered caption lives in
    the working directory's results root, so the path is made absolute here.
    """
    return os.path.abspath(results_file(f"{document}/{name}.caption.rst"))


# ---------------------------------------------------------------- resources of simulation jobs
# Every simulation rule asks for the runtime (minutes) and memory (MB) that kinetic.cost
# estimates for its output from the config (kinetic.plan lists the jobs), doubled on each
# retry. workflow/rules/budget.smk refuses jobs above config['limits'] before any job.
from kinetic import cost as job_cost
from kinetic import plan as job_plan

_PLANNED_JOBS = {}


def planned_jobs():
    """{output path: kinetic.studies.Job} of every simulation job of the config (with the
    results root in the paths), computed once."""
    if not _PLANNED_JOBS:
        _PLANNED_JOBS.update(job_plan.jobs_by_output(config))
    return _PLANNED_JOBS


def job_of(output):
    """The simulation job that writes ``output``."""
    try:
        return planned_jobs()[str(output)]
    except KeyError:
        raise WorkflowError(
            f"no simulation job of the config writes {output}"
        ) from None


def planned_job(wildcards, rulename):
    """The job of ``rulename`` with these wildcards (for resources, which get no output)."""
    return job_of(workflow.get_rule(rulename).output[0].apply_wildcards(wildcards))


def job_code(rulename):
    """Inputs of a simulation rule: the stamps of every package file whose edit changes the
    numbers of one of its jobs (``kinetic.sources.front_sources`` of each job's front and
    engines).
    The simulate script itself only calls the front, with ``params``, which Snakemake
    checks on its own."""
    fronts = {
        (job.front, job.engines)
        for job in planned_jobs().values()
        if job.rule == rulename
    }
    return code_inputs(
        sorted(
            {
                path
                for front, engines in fronts
                for path in front_sources(front, engines)
            }
        )
    )


def job_param(rulename, field):
    """A params function of the simulation rule named ``rulename``, ``field`` of the job its wildcards
    name (``front``, ``arguments`` or ``parameters`` of the kinetic.studies.Job). It takes
    the wildcards only: Snakemake leaves params computed from the output out of its
    params-changed check, and a changed config value must rerun the jobs it changes."""

    def param(wildcards):
        value = getattr(planned_job(wildcards, rulename), field)
        return dict(value) if field != "front" else value

    return param


def planned_runtime(wildcards, attempt, rulename):
    """resources.runtime (minutes) of a simulation job."""
    return job_cost.runtime_minutes(planned_job(wildcards, rulename).estimate, attempt)


def planned_mem_mb(wildcards, attempt, rulename):
    """resources.mem_mb of a simulation job."""
    return job_cost.mem_mb(planned_job(wildcards, rulename).estimate, attempt)


def planned_gpus(wildcards, rulename):
    """resources.gpu of a simulation job: 1 for a backend 'cuda' job (the SLURM executor
    asks for --gpus=1), else 0."""
    return planned_job(wildcards, rulename).gpus


# ---------------------------------------------------------------- the report's tables (report.smk)
def workflow_job_outputs(wildcards):
    """Input function: the simulation outputs the job table reports on."""
    outputs = [job.output for job in job_plan.plan_jobs(config)]
    if config["targets"] == "all":
        return outputs
    return [path for path in outputs if Path(path).exists()]


def workflow_config(wildcards):
    return config


def workflow_agreement_tables(wildcards):
    """Input function: the checks.csv of every document (only those built, unless the
    config builds every target)."""
    files = [
        results_file(f"{document}/checks.csv")
        for document in DOCUMENTS
        if f"{document}/checks" in TARGETS
    ]
    if config["targets"] == "all":
        return files
    return [path for path in files if Path(path).exists()]
