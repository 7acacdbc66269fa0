# visco2008: every rule of the document, in the order its pipelines run them (theory, then
# simulations and joins, then analyses, figures, tables and checks); the helpers they call
# are in common.smk.


# ======================================================================================
# theory: exact curves and solutions, tabulated once (figures compute none)
# ======================================================================================
# visco2008 theory: the curves of the paper's equations on the config's grids (one netCDF
# per family under <results>/visco2008/theory/) and the deterministic solution of Eq. 28
# drawn beside the cloning data. Figures read these files; they compute no theory.


rule visco2008_theory:
    input:
        code=script_code("visco2008_theory"),
    output:
        results_file("visco2008/theory/{family}.nc"),
    log:
        log_file("visco2008/theory/{family}.log"),
    wildcard_constraints:
        family="|".join(VISCO2008_THEORY_FAMILIES),
    params:
        family=lambda wildcards: wildcards.family,
        grid=visco2008_theory_grid,
        parameters=visco2008_theory_grid,
    script:
        "../../scripts/visco2008_theory.py"


rule visco2008_theory_cloning_reference:
    input:
        code=script_code("visco2008_theory"),
    output:
        results_file("visco2008/cloning/reference.nc"),
    log:
        log_file("visco2008/cloning_reference.log"),
    benchmark:
        log_file("benchmarks/visco2008/cloning_reference.tsv")
    threads: 1
    params:
        family="cloning_reference",
        grid=visco2008_cloning_reference_grid,
        parameters=visco2008_cloning_reference_parameters,
    script:
        "../../scripts/visco2008_theory.py"


# ======================================================================================
# simulations (visco2008_simulate_<what>) and their joins (visco2008_aggregate_<what>)
# ======================================================================================
# visco2008 simulations: molecular dynamics (kinetic.edmd, §IV.B), homogeneous DSMC
# (kinetic.dsmc, Figs 1 and 12) and the cloning Monte Carlo (kinetic.cloning, §IV.A).
# Every run is cut into jobs of independent realizations (kinetic.batches: one
# <results>/visco2008/<engine>/<run>/batchNNNN.nc per job); realization k of a run always
# uses stream k of the run's seed, so the data do not depend on the cut and a stopped run
# resumes job by job. One aggregate per run joins its jobs and computes nothing else; the
# analyses of the joined runs are in the analysis rules.


rule visco2008_simulate_md:
    input:
        code=job_code("visco2008_simulate_md"),
    output:
        results_file("visco2008/md/{run}/{batch}.nc"),
    log:
        log_file("visco2008/md/{run}/{batch}.log"),
    benchmark:
        log_file("benchmarks/visco2008/md/{run}/{batch}.tsv")
    wildcard_constraints:
        run=visco2008_md_runs(),
        batch=BATCH,
    threads: 1
    resources:
        runtime=planned_runtime,
        mem_mb=planned_mem_mb,
    params:
        front=job_param("visco2008_simulate_md", "front"),
        job=job_param("visco2008_simulate_md", "arguments"),
        parameters=job_param("visco2008_simulate_md", "parameters"),
    script:
        "../../scripts/simulate.py"


rule visco2008_aggregate_md:
    input:
        batches=visco2008_md_batch_files,
        code=script_code("aggregate"),
    output:
        results_file("visco2008/md/{run}.nc"),
    log:
        log_file("visco2008/md/{run}.log"),
    wildcard_constraints:
        run=visco2008_md_runs(),
    script:
        "../../scripts/aggregate.py"


rule visco2008_simulate_dsmc:
    input:
        code=job_code("visco2008_simulate_dsmc"),
    output:
        results_file("visco2008/dsmc/{run}/{batch}.nc"),
    log:
        log_file("visco2008/dsmc/{run}/{batch}.log"),
    benchmark:
        log_file("benchmarks/visco2008/dsmc/{run}/{batch}.tsv")
    wildcard_constraints:
        run="|".join(VISCO2008_DSMC_RUNS),
        batch=BATCH,
    threads: 1
    resources:
        runtime=planned_runtime,
        mem_mb=planned_mem_mb,
    params:
        front=job_param("visco2008_simulate_dsmc", "front"),
        job=job_param("visco2008_simulate_dsmc", "arguments"),
        parameters=job_param("visco2008_simulate_dsmc", "parameters"),
    script:
        "../../scripts/simulate.py"


rule visco2008_aggregate_dsmc:
    input:
        batches=visco2008_dsmc_batch_files,
        code=script_code("visco2008_aggregate_dsmc"),
    output:
        results_file("visco2008/dsmc/{run}.nc"),
    log:
        log_file("visco2008/dsmc/{run}.log"),
    wildcard_constraints:
        run="|".join(VISCO2008_DSMC_RUNS),
    script:
        "../../scripts/visco2008_aggregate_dsmc.py"


rule visco2008_simulate_cloning:
    input:
        # the engine and the collision rate it scales time by (kinetic.cloning.rates)
        code=job_code("visco2008_simulate_cloning"),
    output:
        results_file("visco2008/cloning/{study}/{kernel}/{point}/{size}/{batch}.nc"),
    log:
        log_file("visco2008/cloning/{study}/{kernel}/{point}/{size}/{batch}.log"),
    benchmark:
        log_file(
            "benchmarks/visco2008/cloning/{study}/{kernel}/{point}/{size}/{batch}.tsv"
        )
    wildcard_constraints:
        study="scan|error_vs_time",
        kernel="|".join(cloning_plan.KERNEL_SETTINGS),
        point=r"lam[+-][0-9]+\.[0-9]{3}",
        size=visco2008_cloning_single_sizes(),
        batch=BATCH,
    threads: 1
    resources:
        runtime=planned_runtime,
        mem_mb=planned_mem_mb,
        gpu=planned_gpus,
    params:
        front=job_param("visco2008_simulate_cloning", "front"),
        job=job_param("visco2008_simulate_cloning", "arguments"),
        parameters=job_param("visco2008_simulate_cloning", "parameters"),
    script:
        "../../scripts/simulate.py"


# With backend: cuda, the points of a study, kernel and population of the GPU's resident
# kernel (kinetic.studies.visco2008_cloning.grouped) share one job and the same launches
# (kinetic.cloning.simulate_points): one rule per study and kernel, one job per N_c, the
# same files as the per-point rule writes.
for study, kernel, points, sizes in visco2008_cloning_groups():

    rule:
        name:
            cloning_plan.group_rule(study, kernel)
        input:
            code=job_code(cloning_plan.group_rule(study, kernel)),
        output:
            [
                results_file(
                    f"visco2008/cloning/{study}/{kernel}/{point}/{{size}}/batch0000.nc"
                )
                for point in points
            ],
        log:
            log_file(f"visco2008/cloning/{study}/{kernel}/{{size}}.log"),
        benchmark:
            log_file(f"benchmarks/visco2008/cloning/{study}/{kernel}/{{size}}.tsv")
        wildcard_constraints:
            size="|".join(sizes),
        threads: 1
        resources:
            runtime=planned_runtime,
            mem_mb=planned_mem_mb,
            gpu=planned_gpus,
        params:
            front=job_param(cloning_plan.group_rule(study, kernel), "front"),
            job=job_param(cloning_plan.group_rule(study, kernel), "arguments"),
            parameters=job_param(cloning_plan.group_rule(study, kernel), "parameters"),
        script:
            "../../scripts/simulate.py"


# ======================================================================================
# analyses named after what they compute, figures, tables and checks
# ======================================================================================
# visco2008 analyses, figures and tables: the cloning scan's table (its 1/N_c
# extrapolations) and the cloning error study's table from the joined runs of the
# simulation rules; Figs 1-12 and Table I (with the MD runs' cumulants) from those and the
# theory files of the theory rules, plus the cloning and MD error-against-time studies.
# Figures only read files under <results>/.


for _number in ("01", "02", "03", "04", "05", "06", "07", "08", "09", "10", "11", "12"):
    provide(f"visco2008/fig{_number}", *figure_files("visco2008", f"fig{_number}"))


provide("visco2008/table1", *table_files("visco2008", "table1"))


provide(
    "visco2008/cloning",
    results_file("visco2008/cloning.csv"),
    results_file("visco2008/cloning.md"),
    results_file("visco2008/cloning.nc"),
    *figure_files("visco2008", "cloning_velocity_density"),
    *figure_files("visco2008", "cloning_extrapolation"),
)


provide(
    "visco2008/cloning_error_vs_time",
    *figure_files("visco2008", "cloning_error_vs_time"),
    *table_files("visco2008", "cloning_error_vs_time"),
)


provide(
    "visco2008/md_error_vs_time",
    *figure_files("visco2008", "md_error_vs_time"),
    *table_files("visco2008", "md_error_vs_time"),
)


rule visco2008_cloning_table:
    input:
        batches=visco2008_cloning_scan_batches,
        code=script_code("visco2008_cloning_table"),
    output:
        csv=results_file("visco2008/cloning.csv"),
        md=results_file("visco2008/cloning.md"),
        nc=results_file("visco2008/cloning.nc"),
    log:
        log_file("visco2008/cloning_table.log"),
    script:
        "../../scripts/visco2008_cloning_table.py"


rule visco2008_cloning_kernel_table:
    # the scan of one kernel as cloning.nc holds it (the same points and extrapolations):
    # what a figure of one kernel reads
    input:
        batches=visco2008_cloning_kernel_batches,
        code=script_code("visco2008_cloning_table"),
    output:
        nc=visco2008_cloning_kernel_scan("{kernel}"),
    log:
        log_file("visco2008/cloning/scan/{kernel}.log"),
    wildcard_constraints:
        kernel="|".join(visco2008_cloning()["kernels"]),
    script:
        "../../scripts/visco2008_cloning_table.py"


rule visco2008_cloning_error_table:
    input:
        batches=visco2008_cloning_error_batches,
        reference=results_file("visco2008/cloning/reference.nc"),
        code=script_code("visco2008_cloning_error_table"),
    output:
        csv=results_file("visco2008/cloning_error_vs_time.csv"),
        md=results_file("visco2008/cloning_error_vs_time.md"),
        nc=results_file("visco2008/cloning/error_vs_time.nc"),
    log:
        log_file("visco2008/cloning_error_table.log"),
    script:
        "../../scripts/visco2008_cloning_error_table.py"


rule visco2008_cloning_error_vs_time:
    input:
        curves=results_file("visco2008/cloning/error_vs_time.nc"),
        table=results_file("visco2008/cloning_error_vs_time.csv"),
        code=script_code("visco2008_cloning_error_vs_time"),
    output:
        pdf=results_file("visco2008/cloning_error_vs_time.pdf"),
        png=report(
            results_file("visco2008/cloning_error_vs_time.png"),
            caption="../../report/visco2008_cloning_error_vs_time.rst",
            category="visco2008",
            subcategory="cloning Monte Carlo",
        ),
    log:
        log_file("visco2008/cloning_error_vs_time.log"),
    script:
        "../../scripts/visco2008_cloning_error_vs_time.py"


rule visco2008_cloning_extrapolation:
    input:
        scan=visco2008_cloning_kernel_scan("hard_disks"),
        reference=results_file("visco2008/cloning/reference.nc"),
        code=script_code("visco2008_cloning_extrapolation"),
    output:
        pdf=results_file("visco2008/cloning_extrapolation.pdf"),
        png=report(
            results_file("visco2008/cloning_extrapolation.png"),
            caption="../../report/visco2008_cloning_extrapolation.rst",
            category="visco2008",
            subcategory="cloning Monte Carlo",
        ),
    log:
        log_file("visco2008/cloning_extrapolation.log"),
    script:
        "../../scripts/visco2008_cloning_extrapolation.py"


rule visco2008_cloning_velocity_density:
    input:
        scan=visco2008_cloning_kernel_scan("hard_disks"),
        code=script_code("visco2008_cloning_velocity_density"),
    output:
        pdf=results_file("visco2008/cloning_velocity_density.pdf"),
        png=report(
            results_file("visco2008/cloning_velocity_density.png"),
            caption="../../report/visco2008_cloning_velocity_density.rst",
            category="visco2008",
            subcategory="cloning Monte Carlo",
        ),
    log:
        log_file("visco2008/cloning_velocity_density.log"),
    script:
        "../../scripts/visco2008_cloning_velocity_density.py"


rule visco2008_fig01:
    input:
        md=visco2008_md_all_data,
        dsmc=visco2008_fig01_dsmc,
        curves=visco2008_theory("free_flights"),
        template=caption_template("visco2008_fig01"),
        code=script_code("visco2008_fig01"),
    output:
        pdf=results_file("visco2008/fig01.pdf"),
        png=report(
            results_file("visco2008/fig01.png"),
            caption=rendered_caption("visco2008", "fig01"),
            category="visco2008",
        ),
        caption=results_file("visco2008/fig01.caption.rst"),
    log:
        log_file("visco2008/fig01.log"),
    script:
        "../../scripts/visco2008_fig01.py"


rule visco2008_fig02:
    input:
        md=visco2008_md_all_data,
        curves=visco2008_theory("free_paths"),
        template=caption_template("visco2008_fig02"),
        code=script_code("visco2008_fig02"),
    output:
        pdf=results_file("visco2008/fig02.pdf"),
        png=report(
            results_file("visco2008/fig02.png"),
            caption=rendered_caption("visco2008", "fig02"),
            category="visco2008",
        ),
        caption=results_file("visco2008/fig02.caption.rst"),
    log:
        log_file("visco2008/fig02.log"),
    script:
        "../../scripts/visco2008_fig02.py"


rule visco2008_fig03:
    input:
        curves=visco2008_theory("large_deviations"),
        code=script_code("visco2008_fig03"),
    output:
        pdf=results_file("visco2008/fig03.pdf"),
        png=report(
            results_file("visco2008/fig03.png"),
            caption="../../report/visco2008_fig03.rst",
            category="visco2008",
        ),
    log:
        log_file("visco2008/fig03.log"),
    script:
        "../../scripts/visco2008_fig03.py"


rule visco2008_fig04:
    input:
        scan=visco2008_cloning_kernel_scan("maxwell"),
        closures=visco2008_theory("closures"),
        code=script_code("visco2008_fig04"),
    output:
        pdf=results_file("visco2008/fig04.pdf"),
        png=report(
            results_file("visco2008/fig04.png"),
            caption="../../report/visco2008_fig04.rst",
            category="visco2008",
        ),
    log:
        log_file("visco2008/fig04.log"),
    script:
        "../../scripts/visco2008_fig04.py"


rule visco2008_fig05:
    input:
        scan=visco2008_cloning_kernel_scan("hard_disks"),
        closures=visco2008_theory("closures"),
        reference=results_file("visco2008/cloning/reference.nc"),
        template=caption_template("visco2008_fig05"),
        code=script_code("visco2008_fig05"),
    output:
        pdf=results_file("visco2008/fig05.pdf"),
        png=report(
            results_file("visco2008/fig05.png"),
            caption=rendered_caption("visco2008", "fig05"),
            category="visco2008",
        ),
        caption=results_file("visco2008/fig05.caption.rst"),
    log:
        log_file("visco2008/fig05.log"),
    script:
        "../../scripts/visco2008_fig05.py"


rule visco2008_fig06:
    input:
        scan=visco2008_cloning_kernel_scan("hard_disks"),
        closures=visco2008_theory("closures"),
        reference=results_file("visco2008/cloning/reference.nc"),
        template=caption_template("visco2008_fig06"),
        code=script_code("visco2008_fig06"),
    output:
        pdf=results_file("visco2008/fig06.pdf"),
        png=report(
            results_file("visco2008/fig06.png"),
            caption=rendered_caption("visco2008", "fig06"),
            category="visco2008",
        ),
        caption=results_file("visco2008/fig06.caption.rst"),
    log:
        log_file("visco2008/fig06.log"),
    script:
        "../../scripts/visco2008_fig06.py"


rule visco2008_fig07:
    input:
        scan=visco2008_cloning_kernel_scan("hard_disks"),
        closures=visco2008_theory("closures"),
        reference=results_file("visco2008/cloning/reference.nc"),
        code=script_code("visco2008_fig07"),
    output:
        pdf=results_file("visco2008/fig07.pdf"),
        png=report(
            results_file("visco2008/fig07.png"),
            caption="../../report/visco2008_fig07.rst",
            category="visco2008",
        ),
    log:
        log_file("visco2008/fig07.log"),
    script:
        "../../scripts/visco2008_fig07.py"


rule visco2008_fig08:
    input:
        scan=visco2008_cloning_kernel_scan("hard_disks"),
        closures=visco2008_theory("closures"),
        reference=results_file("visco2008/cloning/reference.nc"),
        template=caption_template("visco2008_fig08"),
        code=script_code("visco2008_fig08"),
    output:
        pdf=results_file("visco2008/fig08.pdf"),
        png=report(
            results_file("visco2008/fig08.png"),
            caption=rendered_caption("visco2008", "fig08"),
            category="visco2008",
        ),
        caption=results_file("visco2008/fig08.caption.rst"),
    log:
        log_file("visco2008/fig08.log"),
    script:
        "../../scripts/visco2008_fig08.py"


rule visco2008_fig09:
    input:
        md=visco2008_md_figure_data,
        curves=visco2008_theory("large_deviations"),
        finite=visco2008_theory("finite_time"),
        template=caption_template("visco2008_fig09"),
        code=script_code("visco2008_fig09"),
    output:
        pdf=results_file("visco2008/fig09.pdf"),
        png=report(
            results_file("visco2008/fig09.png"),
            caption=rendered_caption("visco2008", "fig09"),
            category="visco2008",
        ),
        caption=results_file("visco2008/fig09.caption.rst"),
    log:
        log_file("visco2008/fig09.log"),
    params:
        windows=visco2008_md_ldf_windows,
        min_count=visco2008_md_ldf_min_count,
    script:
        "../../scripts/visco2008_fig09.py"


rule visco2008_fig10:
    input:
        md=visco2008_md_all_data,
        curves=visco2008_theory("free_flights"),
        template=caption_template("visco2008_fig10"),
        code=script_code("visco2008_fig10"),
    output:
        pdf=results_file("visco2008/fig10.pdf"),
        png=report(
            results_file("visco2008/fig10.png"),
            caption=rendered_caption("visco2008", "fig10"),
            category="visco2008",
        ),
        caption=results_file("visco2008/fig10.caption.rst"),
    log:
        log_file("visco2008/fig10.log"),
    script:
        "../../scripts/visco2008_fig10.py"


rule visco2008_fig11:
    input:
        curves=visco2008_theory("free_flights"),
        code=script_code("visco2008_fig11"),
    output:
        pdf=results_file("visco2008/fig11.pdf"),
        png=report(
            results_file("visco2008/fig11.png"),
            caption="../../report/visco2008_fig11.rst",
            category="visco2008",
        ),
    log:
        log_file("visco2008/fig11.log"),
    script:
        "../../scripts/visco2008_fig11.py"


rule visco2008_fig12:
    input:
        dsmc=results_file("visco2008/dsmc/maxwell_free_paths.nc"),
        curves=visco2008_theory("free_paths"),
        template=caption_template("visco2008_fig12"),
        code=script_code("visco2008_fig12"),
    output:
        pdf=results_file("visco2008/fig12.pdf"),
        png=report(
            results_file("visco2008/fig12.png"),
            caption=rendered_caption("visco2008", "fig12"),
            category="visco2008",
        ),
        caption=results_file("visco2008/fig12.caption.rst"),
    log:
        log_file("visco2008/fig12.log"),
    script:
        "../../scripts/visco2008_fig12.py"


rule visco2008_md_error_vs_time:
    input:
        md=visco2008_md_all_data,
        code=script_code("visco2008_md_error_vs_time"),
    output:
        pdf=results_file("visco2008/md_error_vs_time.pdf"),
        png=report(
            results_file("visco2008/md_error_vs_time.png"),
            caption="../../report/visco2008_md_error_vs_time.rst",
            category="visco2008",
        ),
        csv=results_file("visco2008/md_error_vs_time.csv"),
        md=results_file("visco2008/md_error_vs_time.md"),
    log:
        log_file("visco2008/md_error_vs_time.log"),
    params:
        window=visco2008_md_error_window,
    script:
        "../../scripts/visco2008_md_error_vs_time.py"


rule visco2008_table1:
    input:
        closures=visco2008_theory("closures"),
        md=visco2008_table1_md,
        template=caption_template("visco2008_table1"),
        code=script_code("visco2008_table1"),
    output:
        csv=results_file("visco2008/table1.csv"),
        md=results_file("visco2008/table1.md"),
        caption=results_file("visco2008/table1.caption.rst"),
    log:
        log_file("visco2008/table1.log"),
    params:
        table_windows=visco2008_md_table_windows,
        extrapolation_windows=visco2008_md_extrapolation_windows,
    script:
        "../../scripts/visco2008_table1.py"


provide("visco2008/checks", *table_files("visco2008", "checks"))


rule visco2008_checks:
    # The document's claims on Table I and the cloning scan (kinetic.analysis.visco2008);
    # a failed check stops the build when the config's fail_on_checks lists visco2008.
    input:
        table=results_file("visco2008/table1.csv"),
        cloning=results_file("visco2008/cloning.csv"),
        reference=results_file("visco2008/cloning/reference.nc"),
        code=script_code("visco2008_checks"),
    output:
        csv=report(
            results_file("visco2008/checks.csv"),
            caption="../../report/checks.rst",
            category="visco2008",
            subcategory="checks",
        ),
        md=results_file("visco2008/checks.md"),
    log:
        log_file("visco2008/checks.log"),
    params:
        checks=config["visco2008"]["checks"],
        fail=fails_on_checks("visco2008"),
        # the errors' degrees of freedom: their realizations less one (Student's bands)
        md_dof=config["visco2008"]["md"]["realizations"] - 1,
        cloning_dof=config["visco2008"]["cloning"]["realizations"] - 1,
    script:
        "../../scripts/visco2008_checks.py"
