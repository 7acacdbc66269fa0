# montanero2007: the helpers of its rules (paths, input functions, params), included before
# its rule files, which hold only rules and the targets they register.

import functools
import re

from kinetic import batches
from kinetic.studies import montanero2007 as montanero2007_study
from kinetic.studies.montanero2007 import alpha_key, field_partner
from kinetic.theory.montanero2007 import FIG07_QUOTED_SHARES
from kinetic.studies.montanero2007 import run_batches, run_plan

# ---------------------------------------------------------------- for the simulation rules


@functools.cache
def montanero2007_runs():
    """{run name: parameters} of the config's plan (the protocol merged with each family's
    overrides), computed once."""
    return run_plan(config["montanero2007"])


def montanero2007_jobs(name):
    """kinetic.batches plan of one run (kinetic.studies.montanero2007.run_batches)."""
    return run_batches(montanero2007_runs()[name], config["backend"])


def montanero2007_batch_files(name):
    """The batch files of one run (all its realizations)."""
    return [
        results_file(f"montanero2007/dsmc/{name}/{batches.batch_name(job.index)}.nc")
        for job in montanero2007_jobs(name)
    ]


def montanero2007_run_file(name):
    """One run, its batches joined (rule montanero2007_aggregate_dsmc)."""
    return results_file(f"montanero2007/dsmc/{name}.nc")


def montanero2007_run_batches(wildcards):
    return montanero2007_batch_files(wildcards.run)


def montanero2007_run_names():
    """Wildcard constraint: the run names of the plan, nothing else."""
    return "|".join(sorted(montanero2007_runs()))


def montanero2007_single_run_names():
    """Wildcard constraint of montanero2007_simulate_dsmc: the runs cut into jobs of their
    own (every run on the cpu; with backend: cuda none, each family's runs share a job).
    """
    names = montanero2007_study.single_runs(config["montanero2007"], config["backend"])
    return "|".join(re.escape(name) for name in sorted(names)) if names else "(?!)"


def montanero2007_dsmc_groups():
    """{family: its run names} of every grouped-runs rule (cuda only)."""
    return montanero2007_study.dsmc_groups(config["montanero2007"], config["backend"])


# ---------------------------------------------------------------- for the analysis rules


def montanero2007_runs_of(family):
    """The joined runs of one family, in plan order."""
    return [
        montanero2007_run_file(name)
        for name, run in montanero2007_runs().items()
        if run["family"] == family
    ]


def montanero2007_scan(alphas):
    """The joined scan runs at these restitution coefficients."""
    return [montanero2007_run_file(alpha_key(alpha)) for alpha in alphas]


def montanero2007_error_study_particles():
    """N of the error study's runs (its overrides, else the protocol's)."""
    section = config["montanero2007"]
    overrides = section["error_study"]["overrides"]
    return overrides.get("n_particles", section["protocol"]["n_particles"])


def montanero2007_field_pair(wildcards):
    """Fig 1: the scan run and its larger-field partner at the same restitution."""
    alpha = config["montanero2007"]["figures"]["fig01_alpha"]
    field = config["montanero2007"]["field_check"]
    files = montanero2007_scan([alpha])
    if field["restitution"] == alpha:
        files.append(montanero2007_run_file(f"field_{alpha_key(alpha)}"))
    return files


def montanero2007_field_partners(alphas):
    """The joined larger-field partner of each scan run at these restitutions: the
    O(eps*^2) bias and the extrapolation eps* -> 0 of Figs 3, 4, 7 and Table 1."""
    section = config["montanero2007"]
    return [montanero2007_run_file(field_partner(section, alpha)) for alpha in alphas]


def montanero2007_scan_partners(wildcards):
    return montanero2007_field_partners(config["montanero2007"]["alphas"])


def montanero2007_fig07_partners(wildcards):
    """The partners of the restitutions whose eps* -> 0 share Fig. 7's caption quotes."""
    return montanero2007_field_partners(FIG07_QUOTED_SHARES)


def montanero2007_error_inputs(wildcards):
    """Error study: the paper-protocol scan runs and every error setting."""
    study = config["montanero2007"]["error_study"]
    return montanero2007_scan(study["alphas"]) + montanero2007_runs_of("error")


def montanero2007_extreme_inputs(wildcards):
    """Extreme cases: the protocol-field scan runs of extreme.alphas and the extreme runs."""
    extreme = config["montanero2007"]["extreme"]
    return montanero2007_scan(extreme["alphas"]) + montanero2007_runs_of("extreme")


def montanero2007_check_inputs(wildcards):
    """Checks: every scan run, the larger-field runs (field and bias: the claims of linear
    response are checked at eps* -> 0) and the HCS runs."""
    return (
        montanero2007_runs_of("scan")
        + montanero2007_runs_of("field")
        + montanero2007_runs_of("bias")
        + montanero2007_runs_of("hcs")
    )


def montanero2007_figure_runs(key):
    """Joined scan runs listed by the config key figures.<key>."""
    return montanero2007_scan(config["montanero2007"]["figures"][key])


def montanero2007_fig02_runs(wildcards):
    return montanero2007_figure_runs("fig02_alphas")


def montanero2007_fig05_runs(wildcards):
    return montanero2007_figure_runs("fig05_alphas")


def montanero2007_fig06_runs(wildcards):
    return montanero2007_figure_runs("fig06_alphas")


def montanero2007_fig07_runs(wildcards):
    return montanero2007_figure_runs("fig07_alphas")


def montanero2007_scan_runs(wildcards):
    return montanero2007_runs_of("scan")
