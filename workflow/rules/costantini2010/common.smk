# costantini2010: the helpers of its rules (paths, input functions, params), included before
# its rule files, which hold only rules and the targets they register.

import re

from kinetic.studies import costantini2010 as costantini2010_study

# ---------------------------------------------------------------- for the simulation rules

COSTANTINI2010_PACKAGES = {"dsmc": "dsmc", "md": "edmd"}


"""Package of each engine wildcard."""


def costantini2010_runs():
    """Every run of the study by name."""
    return costantini2010_study.runs(config["costantini2010"])


def costantini2010_run(wildcards):
    """The run named by the {run} wildcard, checked against the {engine} wildcard."""
    run = costantini2010_runs().get(wildcards.run)
    if run is None or run.engine != wildcards.engine:
        raise WorkflowError(
            f"the config asks for no costantini2010 {wildcards.engine} run {wildcards.run!r}"
        )
    return run


def costantini2010_dsmc_single_runs():
    """Wildcard constraint of costantini2010_simulate_dsmc: the DSMC runs cut into jobs of
    their own (every one on the cpu; on cuda those outside the grid's groups)."""
    names = costantini2010_study.single_dsmc_runs(
        config["costantini2010"], config["backend"]
    )
    return "|".join(re.escape(name) for name in names) if names else "(?!)"


def costantini2010_dsmc_groups():
    """{group name: its runs} of every grouped-runs rule (cuda only)."""
    return costantini2010_study.dsmc_groups(config["costantini2010"], config["backend"])


def costantini2010_batch_files(wildcards):
    """Input of costantini2010_correlations (the rule): every job's file of the run."""
    run = costantini2010_run(wildcards)
    return [
        results_file(costantini2010_study.batch_file(run, job))
        for job in costantini2010_study.batch_plan(
            config["costantini2010"], run, config.get("backend", "cpu")
        )
    ]


def costantini2010_analysis(wildcards):
    """Settings of kinetic.analysis.costantini2010.analyse_run, in engine time units where
    the analysis wants them (the transient)."""
    study = config["costantini2010"]
    return {
        "transient": study["transient"]
        * costantini2010_study.mean_free_time(study["density"]),
        "max_lag": study["max_lag"],
        "blocks_per_realization": study["blocks_per_realization"],
        "fit_start": study["fit_start"],
        "fit_stop": study["fit_stop"],
    }


# ---------------------------------------------------------------- for the analysis rules
def costantini2010_files(runs):
    return [results_file(costantini2010_study.run_file(run)) for run in runs]


def costantini2010_figure_inputs(wildcards):
    """Figs 1 and 2: the runs at the figure's (N, alpha)."""
    return costantini2010_files(
        costantini2010_study.figure_runs(config["costantini2010"])
    )


def costantini2010_fig02_inputs(wildcards):
    """Fig 2: the figure runs without the fine cells."""
    return costantini2010_files(
        costantini2010_study.correlation_runs(config["costantini2010"])
    )


def costantini2010_fig03_inputs(wildcards):
    """Fig 3: the grid runs at the figure's alpha, every N."""
    study = config["costantini2010"]
    alpha = study["figures"]["restitution"]
    return costantini2010_files(
        run for run in costantini2010_study.grid_runs(study) if run.restitution == alpha
    )


def costantini2010_table_inputs(wildcards):
    """Table 1: every grid run, and the figure runs with the production cells."""
    return costantini2010_files(
        costantini2010_study.table_runs(config["costantini2010"])
    )


def costantini2010_grid_inputs(wildcards):
    """Figs 4-7: MD and the production DSMC at every (N, alpha) of the config."""
    return costantini2010_files(
        costantini2010_study.grid_runs(config["costantini2010"])
    )


def costantini2010_error_inputs(wildcards):
    """Error against CPU time: DSMC and MD at the figure's N and error_restitution."""
    study = config["costantini2010"]
    n, alpha = study["figures"]["particles"], study["error_restitution"]
    return costantini2010_files(
        run
        for run in costantini2010_study.grid_runs(study)
        if run.restitution == alpha and run.n_particles == n
    )


def costantini2010_convergence_inputs(wildcards):
    return costantini2010_files(
        costantini2010_study.convergence_runs(config["costantini2010"])
    )


def costantini2010_settings(*keys):
    """A params function: the config section's ``keys`` only, those the rule's script
    reads, so that a change of any other setting does not rerun the rule; a dotted key
    (``figures.particles``) takes one entry of a subsection, nested as in the config."""

    def settings(wildcards):
        chosen = {}
        for key in keys:
            *path, leaf = key.split(".")
            source, target = config["costantini2010"], chosen
            for part in path:
                source, target = source[part], target.setdefault(part, {})
            target[leaf] = source[leaf]
        return chosen

    return settings


def costantini2010_caption(name):
    return f"../../report/costantini2010_{name}.rst"
