# visco2008 analyses, figures and tables: the MD runs' cumulants, the cloning scan's table
# (its 1/N_c extrapolations) and the cloning error study's table from the joined runs of
# simulate.smk; Figs 1-12 and Table I from those and the theory files of theory.smk, plus
# the cloning and MD error-against-time studies. Figures only read files under <results>/.


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


rule visco2008_cumulants_md:
    input:
        data=visco2008_md_data("{run}"),
        code=script_code("visco2008_cumulants_md"),
    output:
        visco2008_md_cumulants("{run}"),
    log:
        log_file("visco2008/md/{run}_cumulants.log"),
    wildcard_constraints:
        run=visco2008_md_runs(),
    params:
        table_windows=visco2008_md_table_windows,
        extrapolation_windows=visco2008_md_extrapolation_windows,
    script:
        "../../scripts/visco2008_cumulants_md.py"


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
        scan=results_file("visco2008/cloning.nc"),
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
        scan=results_file("visco2008/cloning.nc"),
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
        scan=results_file("visco2008/cloning.nc"),
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
        scan=results_file("visco2008/cloning.nc"),
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
        scan=results_file("visco2008/cloning.nc"),
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
        scan=results_file("visco2008/cloning.nc"),
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
        scan=results_file("visco2008/cloning.nc"),
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
        extrapolation_windows=visco2008_table1_extrapolation_windows,
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
        fail=fails_on_checks("visco2008"),
    script:
        "../../scripts/visco2008_checks.py"
