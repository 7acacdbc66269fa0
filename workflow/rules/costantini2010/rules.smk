# costantini2010: every rule of the document, in the order its pipelines run them
# (simulations and joins, then analyses, figures, tables and checks); the helpers they call
# are in common.smk.


# ======================================================================================
# simulations (costantini2010_simulate_<engine>)
# ======================================================================================
# costantini2010: runs of the cooling gas in the stationary representation, by inhomogeneous
# DSMC (kinetic.dsmc.simulate_cooling_modes) and MD (kinetic.edmd.simulate_cooling_modes).
#
#   <results>/costantini2010/<engine>/<run>/batchNNNN.nc   one job: realizations of one run
#   <results>/costantini2010/<engine>/<run>.nc             the run's correlations
#
# Every run is cut into jobs of realizations (kinetic.batches). No rule joins them alone:
# the mode time series are the bulk of a job's file and nothing but the correlations reads
# them, so costantini2010_correlations (the first analysis rule) reads a run's jobs and
# writes C(tau), the tail fit, nu*, nu_bar*, zeta* and T(tau)
# (kinetic.analysis.costantini2010) where the other documents keep the joined run. Run
# names are the keys of kinetic.studies.costantini2010.runs(config): wildcards are looked
# up, never parsed.


rule costantini2010_simulate_dsmc:
    input:
        code=job_code("costantini2010_simulate_dsmc"),
    output:
        results_file("costantini2010/{engine}/{run}/{batch}.nc"),
    log:
        log_file("costantini2010/{engine}/{run}/{batch}.log"),
    benchmark:
        log_file("benchmarks/costantini2010/{engine}/{run}/{batch}.tsv")
    wildcard_constraints:
        engine="dsmc",
        run=costantini2010_dsmc_single_runs(),
        batch=BATCH,
    threads: 1
    resources:
        runtime=planned_runtime,
        mem_mb=planned_mem_mb,
        gpu=planned_gpus,
    params:
        front=job_param("costantini2010_simulate_dsmc", "front"),
        job=job_param("costantini2010_simulate_dsmc", "arguments"),
        parameters=job_param("costantini2010_simulate_dsmc", "parameters"),
    script:
        "../../scripts/simulate.py"


# With backend: cuda, the grid's DSMC runs of one N (every alpha: the same particles, cells
# and step) share one job and the same launches (kinetic.dsmc.simulate_cooling_modes_points):
# one rule per N, the same files as the per-run rule writes.
for group, group_runs in costantini2010_dsmc_groups().items():

    rule:
        name:
            costantini2010_study.group_rule(group)
        input:
            code=job_code(costantini2010_study.group_rule(group)),
        output:
            [
                results_file(path)
                for path in costantini2010_study.group_files(
                    config["costantini2010"], group_runs
                )
            ],
        log:
            log_file(f"{costantini2010_study.group_name(group)}.log"),
        benchmark:
            log_file(f"benchmarks/{costantini2010_study.group_name(group)}.tsv")
        threads: 1
        resources:
            runtime=planned_runtime,
            mem_mb=planned_mem_mb,
            gpu=planned_gpus,
        params:
            front=job_param(costantini2010_study.group_rule(group), "front"),
            job=job_param(costantini2010_study.group_rule(group), "arguments"),
            parameters=job_param(costantini2010_study.group_rule(group), "parameters"),
        script:
            "../../scripts/simulate.py"


rule costantini2010_simulate_md:
    input:
        code=job_code("costantini2010_simulate_md"),
    output:
        results_file("costantini2010/{engine}/{run}/{batch}.nc"),
    log:
        log_file("costantini2010/{engine}/{run}/{batch}.log"),
    benchmark:
        log_file("benchmarks/costantini2010/{engine}/{run}/{batch}.tsv")
    wildcard_constraints:
        engine="md",
        run="[^/]+",
        batch=BATCH,
    threads: 1
    resources:
        runtime=planned_runtime,
        mem_mb=planned_mem_mb,
    params:
        front=job_param("costantini2010_simulate_md", "front"),
        job=job_param("costantini2010_simulate_md", "arguments"),
        parameters=job_param("costantini2010_simulate_md", "parameters"),
    script:
        "../../scripts/simulate.py"


# ======================================================================================
# analyses named after what they compute, figures, tables and checks
# ======================================================================================
# costantini2010: each run's correlations (C(tau), nu*, nu_bar*, T(tau): rule
# costantini2010_correlations, from the jobs of the simulation rules), then figures and
# tables from those only.
#   fig01  T(tau) for several cell sizes and Lambda against MD and T_s, with the
#          recollision diagnostic           fig02  C(tau): homogeneous vs inhomogeneous DSMC vs MD
#   fig03  C(tau) for each N                fig04/05  nu*, nu_bar* against 1/N (table1 fits)
#   fig06  nu*, nu_bar* against alpha       fig07  nu_bar*/nu* against alpha
#   table1 one row per (method, alpha, N, Lambda), the 1/N -> 0 rows and theory
#   checks the document's claims against the runs
#   error_vs_time  error of nu*, nu_bar* against CPU time; convergence  DSMC cell side and step


for name in ("fig01", "fig02", "fig03", "fig04", "fig05", "fig06", "fig07"):
    provide(f"costantini2010/{name}", *figure_files("costantini2010", name))


for name in ("error_vs_time", "convergence"):
    provide(
        f"costantini2010/{name}",
        *figure_files("costantini2010", name),
        *table_files("costantini2010", name),
    )


provide(
    "costantini2010/table1",
    *table_files("costantini2010", "table1"),
    *table_files("costantini2010", "extrapolation"),
)


provide(
    "costantini2010/checks",
    *table_files("costantini2010", "checks"),
    *table_files("costantini2010", "amplitudes"),
)


rule costantini2010_correlations:
    input:
        batches=costantini2010_batch_files,
        code=script_code("costantini2010_correlations"),
    output:
        results_file("costantini2010/{engine}/{run}.nc"),
    log:
        log_file("costantini2010/{engine}/{run}.log"),
    wildcard_constraints:
        engine="dsmc|md",
        run="[^/]+",
    params:
        analysis=costantini2010_analysis,
    script:
        "../../scripts/costantini2010_correlations.py"


rule costantini2010_fig01:
    input:
        runs=costantini2010_figure_inputs,
        code=script_code("costantini2010_fig01"),
    output:
        pdf=results_file("costantini2010/fig01.pdf"),
        png=report(
            results_file("costantini2010/fig01.png"),
            caption=costantini2010_caption("fig01"),
            category="costantini2010",
        ),
    log:
        log_file("costantini2010/fig01.log"),
    script:
        "../../scripts/costantini2010_fig01.py"


rule costantini2010_fig02:
    input:
        runs=costantini2010_fig02_inputs,
        code=script_code("costantini2010_fig02"),
    output:
        pdf=results_file("costantini2010/fig02.pdf"),
        png=report(
            results_file("costantini2010/fig02.png"),
            caption=costantini2010_caption("fig02"),
            category="costantini2010",
        ),
    log:
        log_file("costantini2010/fig02.log"),
    params:
        study=costantini2010_settings("density"),
    script:
        "../../scripts/costantini2010_fig02.py"


rule costantini2010_fig03:
    input:
        runs=costantini2010_fig03_inputs,
        code=script_code("costantini2010_fig03"),
    output:
        pdf=results_file("costantini2010/fig03.pdf"),
        png=report(
            results_file("costantini2010/fig03.png"),
            caption=costantini2010_caption("fig03"),
            category="costantini2010",
        ),
    log:
        log_file("costantini2010/fig03.log"),
    params:
        study=costantini2010_settings("density"),
    script:
        "../../scripts/costantini2010_fig03.py"


rule costantini2010_table1:
    input:
        runs=costantini2010_table_inputs,
        code=script_code("costantini2010_table1"),
    output:
        csv=results_file("costantini2010/table1.csv"),
        md=results_file("costantini2010/table1.md"),
        fits=results_file("costantini2010/extrapolation.csv"),
        fits_md=results_file("costantini2010/extrapolation.md"),
        amplitudes=results_file("costantini2010/amplitudes.csv"),
        amplitudes_md=results_file("costantini2010/amplitudes.md"),
    log:
        log_file("costantini2010/table1.log"),
    params:
        study=costantini2010_settings("density", "particles", "restitutions"),
    script:
        "../../scripts/costantini2010_table1.py"


rule costantini2010_transport_table:
    # Table 1 of the grid runs only: what Figs 4-7 draw (MD and the production cells at
    # every N and alpha), without the other runs of Fig. 2 that table1.csv adds
    input:
        runs=costantini2010_grid_inputs,
        code=script_code("costantini2010_table1"),
    output:
        csv=results_file("costantini2010/transport/table1.csv"),
        md=results_file("costantini2010/transport/table1.md"),
        fits=results_file("costantini2010/transport/extrapolation.csv"),
        fits_md=results_file("costantini2010/transport/extrapolation.md"),
        amplitudes=results_file("costantini2010/transport/amplitudes.csv"),
        amplitudes_md=results_file("costantini2010/transport/amplitudes.md"),
    log:
        log_file("costantini2010/transport/table1.log"),
    params:
        study=costantini2010_settings("density", "particles", "restitutions"),
    script:
        "../../scripts/costantini2010_table1.py"


rule costantini2010_checks:
    # Fails (after writing the table to its log) when a check fails and the config's
    # fail_on_checks lists costantini2010.
    input:
        runs=costantini2010_table_inputs,
        code=script_code("costantini2010_checks"),
    output:
        csv=report(
            results_file("costantini2010/checks.csv"),
            caption="../../report/checks.rst",
            category="costantini2010",
            subcategory="checks",
        ),
        md=results_file("costantini2010/checks.md"),
    log:
        log_file("costantini2010/checks.log"),
    params:
        study=costantini2010_settings(
            "a2",
            "density",
            "dsmc.fictive_factor",
            "figures.particles",
            "figures.restitution",
        ),
        checks=config["costantini2010"]["checks"],
        fail=fails_on_checks("costantini2010"),
    script:
        "../../scripts/costantini2010_checks.py"


rule costantini2010_fig04:
    # drawn from Table 1 of the grid runs (computed from their correlations) and the theory
    input:
        table=results_file("costantini2010/transport/table1.csv"),
        fits=results_file("costantini2010/transport/extrapolation.csv"),
        amplitudes=results_file("costantini2010/transport/amplitudes.csv"),
        code=script_code("costantini2010_fig04"),
    output:
        pdf=results_file("costantini2010/fig04.pdf"),
        png=report(
            results_file("costantini2010/fig04.png"),
            caption=costantini2010_caption("fig04"),
            category="costantini2010",
        ),
    log:
        log_file("costantini2010/fig04.log"),
    params:
        study=costantini2010_settings("density", "dsmc"),
    script:
        "../../scripts/costantini2010_fig04.py"


rule costantini2010_fig05:
    # drawn from Table 1 of the grid runs (computed from their correlations) and the theory
    input:
        table=results_file("costantini2010/transport/table1.csv"),
        fits=results_file("costantini2010/transport/extrapolation.csv"),
        amplitudes=results_file("costantini2010/transport/amplitudes.csv"),
        code=script_code("costantini2010_fig05"),
    output:
        pdf=results_file("costantini2010/fig05.pdf"),
        png=report(
            results_file("costantini2010/fig05.png"),
            caption=costantini2010_caption("fig05"),
            category="costantini2010",
        ),
    log:
        log_file("costantini2010/fig05.log"),
    params:
        study=costantini2010_settings("density", "dsmc"),
    script:
        "../../scripts/costantini2010_fig05.py"


rule costantini2010_fig06:
    # drawn from Table 1 of the grid runs (computed from their correlations) and the theory
    input:
        table=results_file("costantini2010/transport/table1.csv"),
        code=script_code("costantini2010_fig06"),
    output:
        pdf=results_file("costantini2010/fig06.pdf"),
        png=report(
            results_file("costantini2010/fig06.png"),
            caption=costantini2010_caption("fig06"),
            category="costantini2010",
        ),
    log:
        log_file("costantini2010/fig06.log"),
    params:
        study=costantini2010_settings("density", "dsmc"),
    script:
        "../../scripts/costantini2010_fig06.py"


rule costantini2010_fig07:
    # drawn from Table 1 of the grid runs (computed from their correlations) and the theory
    input:
        table=results_file("costantini2010/transport/table1.csv"),
        code=script_code("costantini2010_fig07"),
    output:
        pdf=results_file("costantini2010/fig07.pdf"),
        png=report(
            results_file("costantini2010/fig07.png"),
            caption=costantini2010_caption("fig07"),
            category="costantini2010",
        ),
    log:
        log_file("costantini2010/fig07.log"),
    params:
        study=costantini2010_settings("density", "dsmc"),
    script:
        "../../scripts/costantini2010_fig07.py"


rule costantini2010_error_vs_time:
    input:
        runs=costantini2010_error_inputs,
        code=script_code("costantini2010_error_vs_time"),
    output:
        pdf=results_file("costantini2010/error_vs_time.pdf"),
        png=report(
            results_file("costantini2010/error_vs_time.png"),
            caption=costantini2010_caption("error_vs_time"),
            category="costantini2010",
        ),
        csv=results_file("costantini2010/error_vs_time.csv"),
        md=results_file("costantini2010/error_vs_time.md"),
    log:
        log_file("costantini2010/error_vs_time.log"),
    script:
        "../../scripts/costantini2010_error_vs_time.py"


rule costantini2010_convergence:
    input:
        runs=costantini2010_convergence_inputs,
        code=script_code("costantini2010_convergence"),
    output:
        pdf=results_file("costantini2010/convergence.pdf"),
        png=report(
            results_file("costantini2010/convergence.png"),
            caption=costantini2010_caption("convergence"),
            category="costantini2010",
        ),
        csv=results_file("costantini2010/convergence.csv"),
        md=results_file("costantini2010/convergence.md"),
    log:
        log_file("costantini2010/convergence.log"),
    params:
        study=costantini2010_settings("density", "dsmc"),
    script:
        "../../scripts/costantini2010_convergence.py"
