# visco2008 artefacts drawn from the molecular dynamics runs of workflow/rules/edmd.smk:
# Figs 1, 2, 9, 10 and the error-against-run-time study of the MD cumulants (the MD rows
# of Table I are registered in edmd.smk through VISCO2008_TABLE1_MD).

provide("visco2008/fig01", *figure_files("visco2008", "fig01"))
provide("visco2008/fig02", *figure_files("visco2008", "fig02"))
provide("visco2008/fig09", *figure_files("visco2008", "fig09"))
provide("visco2008/fig10", *figure_files("visco2008", "fig10"))
provide(
    "visco2008/md_error_vs_time",
    *figure_files("visco2008", "md_error_vs_time"),
    *table_files("visco2008", "md_error_vs_time"),
)


def visco2008_md_figure_data(wildcards):
    """Aggregated MD observers of the run drawn in Figs 1, 2, 9 and 10."""
    return visco2008_md_data(visco2008_md()["figure_run"])


def visco2008_md_all_data(wildcards):
    """Aggregated MD observers of every run (error-against-run-time study)."""
    return [visco2008_md_data(run) for run in visco2008_md()["densities"]]


def visco2008_fig01_dsmc(wildcards):
    """DSMC free-flight-time densities drawn as squares in Fig. 1: those registered in
    VISCO2008_FIG01_DSMC and the hard-disk run of workflow/rules/dsmc.smk if present."""
    files = list(VISCO2008_FIG01_DSMC)
    if "free_flight_times" in globals().get("VISCO2008_DSMC_RUNS", []):
        files.append("results/visco2008/dsmc/free_flight_times.nc")
    return files


def visco2008_md_ldf_windows(wildcards):
    return visco2008_md()["ldf_windows"]


def visco2008_md_ldf_min_count(wildcards):
    return visco2008_md()["ldf_min_count"]


def visco2008_md_error_window(wildcards):
    return visco2008_md()["error_window"]


rule visco2008_fig01:
    input:
        md=visco2008_md_all_data,
        dsmc=visco2008_fig01_dsmc,
        curves=visco2008_theory("free_flights"),
        template=caption_template("visco2008_fig01"),
        script=figure_script("visco2008_fig01"),
    output:
        pdf="results/visco2008/fig01.pdf",
        png=report(
            "results/visco2008/fig01.png",
            caption=rendered_caption("visco2008", "fig01"),
            category="visco2008",
        ),
        caption="results/visco2008/fig01.caption.rst",
    log:
        "logs/visco2008/fig01.log",
    script:
        "../scripts/visco2008_fig01.py"


rule visco2008_fig02:
    input:
        md=visco2008_md_all_data,
        curves=visco2008_theory("free_paths"),
        template=caption_template("visco2008_fig02"),
        script=figure_script("visco2008_fig02"),
    output:
        pdf="results/visco2008/fig02.pdf",
        png=report(
            "results/visco2008/fig02.png",
            caption=rendered_caption("visco2008", "fig02"),
            category="visco2008",
        ),
        caption="results/visco2008/fig02.caption.rst",
    log:
        "logs/visco2008/fig02.log",
    script:
        "../scripts/visco2008_fig02.py"


rule visco2008_fig09:
    input:
        md=visco2008_md_figure_data,
        curves=visco2008_theory("large_deviations"),
        finite=visco2008_theory("finite_time"),
        template=caption_template("visco2008_fig09"),
        script=figure_script("visco2008_fig09"),
    output:
        pdf="results/visco2008/fig09.pdf",
        png=report(
            "results/visco2008/fig09.png",
            caption=rendered_caption("visco2008", "fig09"),
            category="visco2008",
        ),
        caption="results/visco2008/fig09.caption.rst",
    log:
        "logs/visco2008/fig09.log",
    params:
        windows=visco2008_md_ldf_windows,
        min_count=visco2008_md_ldf_min_count,
    script:
        "../scripts/visco2008_fig09.py"


rule visco2008_fig10:
    input:
        md=visco2008_md_all_data,
        curves=visco2008_theory("free_flights"),
        template=caption_template("visco2008_fig10"),
        script=figure_script("visco2008_fig10"),
    output:
        pdf="results/visco2008/fig10.pdf",
        png=report(
            "results/visco2008/fig10.png",
            caption=rendered_caption("visco2008", "fig10"),
            category="visco2008",
        ),
        caption="results/visco2008/fig10.caption.rst",
    log:
        "logs/visco2008/fig10.log",
    script:
        "../scripts/visco2008_fig10.py"


rule visco2008_md_error_vs_time:
    input:
        md=visco2008_md_all_data,
        script=figure_script("visco2008_md_error_vs_time"),
    output:
        pdf="results/visco2008/md_error_vs_time.pdf",
        png=report(
            "results/visco2008/md_error_vs_time.png",
            caption="../report/visco2008_md_error_vs_time.rst",
            category="visco2008",
        ),
        csv="results/visco2008/md_error_vs_time.csv",
        md="results/visco2008/md_error_vs_time.md",
    log:
        "logs/visco2008/md_error_vs_time.log",
    params:
        window=visco2008_md_error_window,
    script:
        "../scripts/visco2008_md_error_vs_time.py"
