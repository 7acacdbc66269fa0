# visco2008: theory curves, Figs 3 and 11, and Table I (theory rows + the MD rows that the
# MD rules register in VISCO2008_TABLE1_MD).

provide("visco2008/fig03", *figure_files("visco2008", "fig03"))
provide("visco2008/fig11", *figure_files("visco2008", "fig11"))
provide("visco2008/table1", *table_files("visco2008", "table1"))

VISCO2008_THEORY_FAMILIES = [
    "large_deviations",
    "free_flights",
    "free_paths",
    "closures",
    "finite_time",
]


def visco2008_theory(family):
    """Path of one family of visco2008 theory curves (an input of figure rules)."""
    if family not in VISCO2008_THEORY_FAMILIES:
        raise ValueError(f"unknown visco2008 theory family {family!r}")
    return f"results/visco2008/theory/{family}.nc"


def visco2008_theory_grid(wildcards):
    """Keyword arguments of kinetic.theory.tabulate.visco2008_<family> from the config."""
    theory = config["visco2008"]["theory"]
    grids = {
        "large_deviations": {"rate_max": theory["rate_max"], "points": theory["rate_points"]},
        "free_flights": {"time_max": theory["time_max"], "points": theory["time_points"]},
        "free_paths": {"path_max": theory["path_max"], "points": theory["path_points"]},
        "closures": {
            "lambda_min": theory["lambda_min"],
            "lambda_max": theory["lambda_max"],
            "points": theory["lambda_points"],
        },
        # π(n) at the MD's counting windows (Fig. 9): the windows are the MD's, by design
        "finite_time": {
            "windows": config["visco2008"]["md"]["ldf_windows"],
            "rate_max": theory["rate_max"],
        },
    }
    return grids[wildcards.family]


def visco2008_table1_md(wildcards):
    """MD cumulant files registered by the MD rules (none until they exist)."""
    return VISCO2008_TABLE1_MD


def visco2008_table1_extrapolation_windows(wildcards):
    """Windows t of the 1/t fit of Table I's extrapolated rows (for the caption)."""
    return config["visco2008"]["md"]["extrapolation_windows"]


rule visco2008_theory:
    input:
        package_files("theory"),
    output:
        "results/visco2008/theory/{family}.nc",
    log:
        "logs/visco2008/theory/{family}.log",
    params:
        grid=visco2008_theory_grid,
    wildcard_constraints:
        family="|".join(VISCO2008_THEORY_FAMILIES),
    script:
        "../scripts/visco2008_theory.py"


rule visco2008_fig03:
    input:
        curves=visco2008_theory("large_deviations"),
        script=figure_script("visco2008_fig03"),
    output:
        pdf="results/visco2008/fig03.pdf",
        png=report(
            "results/visco2008/fig03.png",
            caption="../report/visco2008_fig03.rst",
            category="visco2008",
        ),
    log:
        "logs/visco2008/fig03.log",
    script:
        "../scripts/visco2008_fig03.py"


rule visco2008_fig11:
    input:
        curves=visco2008_theory("free_flights"),
        script=figure_script("visco2008_fig11"),
    output:
        pdf="results/visco2008/fig11.pdf",
        png=report(
            "results/visco2008/fig11.png",
            caption="../report/visco2008_fig11.rst",
            category="visco2008",
        ),
    log:
        "logs/visco2008/fig11.log",
    script:
        "../scripts/visco2008_fig11.py"


rule visco2008_table1:
    input:
        closures=visco2008_theory("closures"),
        md=visco2008_table1_md,
        template=caption_template("visco2008_table1"),
        script=figure_script("visco2008_table1"),
    output:
        csv="results/visco2008/table1.csv",
        md="results/visco2008/table1.md",
        caption="results/visco2008/table1.caption.rst",
    log:
        "logs/visco2008/table1.log",
    params:
        extrapolation_windows=visco2008_table1_extrapolation_windows,
    script:
        "../scripts/visco2008_table1.py"
