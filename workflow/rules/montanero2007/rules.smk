# montanero2007: every rule of the document, in the order its pipelines run them
# (simulations and joins, then analyses, figures, tables and checks); the helpers they call
# are in common.smk.


# ======================================================================================
# simulations (montanero2007_simulate_<what>) and their joins
# (montanero2007_aggregate_<what>)
# ======================================================================================
# montanero2007 simulations: DSMC of the heat-flux-forced granular gas (kinetic.dsmc).
#
#   <results>/montanero2007/dsmc/<run>/batchNNNN.nc   one job: realizations of one run
#   <results>/montanero2007/dsmc/<run>.nc              its batches joined (what figures read)
#
# Run names come from kinetic.studies.montanero2007.run_plan(config["montanero2007"]).
# With backend: cuda every run is one batch, and the runs of one family share a job
# (montanero2007_simulate_dsmc_<family>, below): the same files.


rule montanero2007_simulate_dsmc:
    input:
        code=job_code("montanero2007_simulate_dsmc"),
    output:
        results_file("montanero2007/dsmc/{run}/{batch}.nc"),
    log:
        log_file("montanero2007/dsmc/{run}/{batch}.log"),
    benchmark:
        log_file("benchmarks/montanero2007/dsmc/{run}/{batch}.tsv")
    wildcard_constraints:
        run=montanero2007_single_run_names(),
        batch=r"batch[0-9]{4}",
    threads: 1
    resources:
        runtime=planned_runtime,
        mem_mb=planned_mem_mb,
        gpu=planned_gpus,
    params:
        front=job_param("montanero2007_simulate_dsmc", "front"),
        job=job_param("montanero2007_simulate_dsmc", "arguments"),
        parameters=job_param("montanero2007_simulate_dsmc", "parameters"),
    script:
        "../../scripts/simulate.py"


# With backend: cuda, the runs of one family (scan, field, bias, hcs, error, extreme) share
# one job, one process after the other on the GPU
# (kinetic.studies.montanero2007_front.simulate_batches): one rule per family, the same files as
# the per-run rule writes.
for group, group_runs in montanero2007_dsmc_groups().items():

    rule:
        name:
            montanero2007_study.group_rule(group)
        input:
            code=job_code(montanero2007_study.group_rule(group)),
        output:
            [results_file(path) for path in montanero2007_study.group_files(group_runs)],
        log:
            log_file(f"{montanero2007_study.group_name(group)}.log"),
        benchmark:
            log_file(f"benchmarks/{montanero2007_study.group_name(group)}.tsv")
        threads: 1
        resources:
            runtime=planned_runtime,
            mem_mb=planned_mem_mb,
            gpu=planned_gpus,
        params:
            front=job_param(montanero2007_study.group_rule(group), "front"),
            job=job_param(montanero2007_study.group_rule(group), "arguments"),
            parameters=job_param(montanero2007_study.group_rule(group), "parameters"),
        script:
            "../../scripts/simulate.py"


rule montanero2007_aggregate_dsmc:
    input:
        batches=montanero2007_run_batches,
        code=script_code("aggregate"),
    output:
        results_file("montanero2007/dsmc/{run}.nc"),
    log:
        log_file("montanero2007/dsmc/{run}.log"),
    wildcard_constraints:
        run=montanero2007_run_names(),
    script:
        "../../scripts/aggregate.py"


# ======================================================================================
# analyses named after what they compute, figures, tables and checks
# ======================================================================================
# montanero2007 figures and tables: Figs 1-7, Table 1, the error-against-run-time study,
# the extreme cases and the checks, from the runs of the simulation rules.
#
#   <results>/montanero2007/figNN.pdf|png, table1.csv|md, error_vs_time.*, extreme.*, checks.*


for _number in range(1, 8):
    provide(
        f"montanero2007/fig0{_number}", *figure_files("montanero2007", f"fig0{_number}")
    )


provide("montanero2007/table1", *table_files("montanero2007", "table1"))


provide(
    "montanero2007/error_vs_time",
    *figure_files("montanero2007", "error_vs_time"),
    *table_files("montanero2007", "error_vs_time"),
    *table_files("montanero2007", "error_targets"),
)


provide(
    "montanero2007/extreme",
    *figure_files("montanero2007", "extreme"),
    *table_files("montanero2007", "extreme"),
)


provide("montanero2007/checks", *table_files("montanero2007", "checks"))


rule montanero2007_fig01:
    input:
        runs=montanero2007_field_pair,
        code=script_code("montanero2007_fig01"),
    output:
        pdf=results_file("montanero2007/fig01.pdf"),
        png=report(
            results_file("montanero2007/fig01.png"),
            caption="../../report/montanero2007_fig01.rst",
            category="montanero2007",
        ),
    log:
        log_file("montanero2007/fig01.log"),
    script:
        "../../scripts/montanero2007_fig01.py"


rule montanero2007_fig02:
    input:
        runs=montanero2007_fig02_runs,
        code=script_code("montanero2007_fig02"),
    output:
        pdf=results_file("montanero2007/fig02.pdf"),
        png=report(
            results_file("montanero2007/fig02.png"),
            caption="../../report/montanero2007_fig02.rst",
            category="montanero2007",
        ),
    log:
        log_file("montanero2007/fig02.log"),
    script:
        "../../scripts/montanero2007_fig02.py"


rule montanero2007_fig03:
    input:
        runs=montanero2007_scan_runs,
        partners=montanero2007_scan_partners,
        template=caption_template("montanero2007_fig03"),
        code=script_code("montanero2007_fig03"),
    output:
        pdf=results_file("montanero2007/fig03.pdf"),
        png=report(
            results_file("montanero2007/fig03.png"),
            caption=rendered_caption("montanero2007", "fig03"),
            category="montanero2007",
        ),
        caption=results_file("montanero2007/fig03.caption.rst"),
    log:
        log_file("montanero2007/fig03.log"),
    script:
        "../../scripts/montanero2007_fig03.py"


rule montanero2007_fig04:
    input:
        runs=montanero2007_scan_runs,
        partners=montanero2007_scan_partners,
        template=caption_template("montanero2007_fig04"),
        code=script_code("montanero2007_fig04"),
    output:
        pdf=results_file("montanero2007/fig04.pdf"),
        png=report(
            results_file("montanero2007/fig04.png"),
            caption=rendered_caption("montanero2007", "fig04"),
            category="montanero2007",
        ),
        caption=results_file("montanero2007/fig04.caption.rst"),
    log:
        log_file("montanero2007/fig04.log"),
    script:
        "../../scripts/montanero2007_fig04.py"


rule montanero2007_fig05:
    input:
        runs=montanero2007_fig05_runs,
        template=caption_template("montanero2007_fig05"),
        code=script_code("montanero2007_phi"),
    output:
        pdf=results_file("montanero2007/fig05.pdf"),
        png=report(
            results_file("montanero2007/fig05.png"),
            caption=rendered_caption("montanero2007", "fig05"),
            category="montanero2007",
        ),
        caption=results_file("montanero2007/fig05.caption.rst"),
    log:
        log_file("montanero2007/fig05.log"),
    params:
        rebin=config["montanero2007"]["figures"]["phi_rebin"],
        cx2_max=config["montanero2007"]["figures"]["phi_cx2_max"],
    script:
        "../../scripts/montanero2007_phi.py"


rule montanero2007_fig06:
    input:
        runs=montanero2007_fig06_runs,
        template=caption_template("montanero2007_fig06"),
        code=script_code("montanero2007_phi"),
    output:
        pdf=results_file("montanero2007/fig06.pdf"),
        png=report(
            results_file("montanero2007/fig06.png"),
            caption=rendered_caption("montanero2007", "fig06"),
            category="montanero2007",
        ),
        caption=results_file("montanero2007/fig06.caption.rst"),
    log:
        log_file("montanero2007/fig06.log"),
    params:
        rebin=config["montanero2007"]["figures"]["phi_rebin"],
        cx2_max=config["montanero2007"]["figures"]["phi_cx2_max"],
    script:
        "../../scripts/montanero2007_phi.py"


rule montanero2007_fig07:
    input:
        runs=montanero2007_fig07_runs,
        partners=montanero2007_fig07_partners,
        template=caption_template("montanero2007_fig07"),
        code=script_code("montanero2007_fig07"),
    output:
        pdf=results_file("montanero2007/fig07.pdf"),
        png=report(
            results_file("montanero2007/fig07.png"),
            caption=rendered_caption("montanero2007", "fig07"),
            category="montanero2007",
        ),
        caption=results_file("montanero2007/fig07.caption.rst"),
    log:
        log_file("montanero2007/fig07.log"),
    params:
        cx2_max=config["montanero2007"]["figures"]["phi_cx2_max"],
    script:
        "../../scripts/montanero2007_fig07.py"


rule montanero2007_table1:
    input:
        runs=montanero2007_scan_runs,
        partners=montanero2007_scan_partners,
        code=script_code("montanero2007_table1"),
    output:
        csv=results_file("montanero2007/table1.csv"),
        md=results_file("montanero2007/table1.md"),
    log:
        log_file("montanero2007/table1.log"),
    script:
        "../../scripts/montanero2007_table1.py"


rule montanero2007_error_vs_time:
    input:
        runs=montanero2007_error_inputs,
        code=script_code("montanero2007_error_vs_time"),
    output:
        pdf=results_file("montanero2007/error_vs_time.pdf"),
        png=report(
            results_file("montanero2007/error_vs_time.png"),
            caption="../../report/montanero2007_error_vs_time.rst",
            category="montanero2007",
        ),
        csv=results_file("montanero2007/error_vs_time.csv"),
        md=results_file("montanero2007/error_vs_time.md"),
        targets_csv=results_file("montanero2007/error_targets.csv"),
        targets_md=results_file("montanero2007/error_targets.md"),
    log:
        log_file("montanero2007/error_vs_time.log"),
    params:
        n_reference=montanero2007_error_study_particles(),
        target_errors=config["montanero2007"]["error_study"]["target_errors"],
    script:
        "../../scripts/montanero2007_error_vs_time.py"


rule montanero2007_extreme:
    input:
        runs=montanero2007_extreme_inputs,
        code=script_code("montanero2007_extreme"),
    output:
        pdf=results_file("montanero2007/extreme.pdf"),
        png=report(
            results_file("montanero2007/extreme.png"),
            caption="../../report/montanero2007_extreme.rst",
            category="montanero2007",
        ),
        csv=results_file("montanero2007/extreme.csv"),
        md=results_file("montanero2007/extreme.md"),
    log:
        log_file("montanero2007/extreme.log"),
    script:
        "../../scripts/montanero2007_extreme.py"


rule montanero2007_checks:
    # Fails (after writing the table to its log) when a check fails and the config's
    # fail_on_checks lists montanero2007.
    input:
        runs=montanero2007_check_inputs,
        code=script_code("montanero2007_checks"),
    output:
        csv=report(
            results_file("montanero2007/checks.csv"),
            caption="../../report/checks.rst",
            category="montanero2007",
            subcategory="checks",
        ),
        md=results_file("montanero2007/checks.md"),
    log:
        log_file("montanero2007/checks.log"),
    params:
        checks=config["montanero2007"]["checks"],
        fail=fails_on_checks("montanero2007"),
    script:
        "../../scripts/montanero2007_checks.py"
