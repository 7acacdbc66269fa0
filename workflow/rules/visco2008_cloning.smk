# visco2008 Figs 4-8 from the cloning Monte Carlo (results/visco2008/cloning.nc), the
# theory closures (Gaussian Eq. 43, first Sonine Eqs. 47-49, Poisson generating functions)
# and the deterministic solution of Eq. 28; the population's velocity density; the
# error-against-CPU-time figure and table. Figures only read files under results/.

for _number in ("04", "05", "06", "07", "08"):
    provide(f"visco2008/fig{_number}", *figure_files("visco2008", f"fig{_number}"))
provide(
    "visco2008/cloning",
    "results/visco2008/cloning.csv",
    "results/visco2008/cloning.md",
    "results/visco2008/cloning.nc",
    *figure_files("visco2008", "cloning_velocity_density"),
    *figure_files("visco2008", "cloning_extrapolation"),
)
provide(
    "visco2008/cloning_error_vs_time",
    *figure_files("visco2008", "cloning_error_vs_time"),
    *table_files("visco2008", "cloning_error_vs_time"),
)


rule visco2008_fig04:
    input:
        scan="results/visco2008/cloning.nc",
        closures=visco2008_theory("closures"),
        script=figure_script("visco2008_fig04"),
    output:
        pdf="results/visco2008/fig04.pdf",
        png=report(
            "results/visco2008/fig04.png",
            caption="../report/visco2008_fig04.rst",
            category="visco2008",
        ),
    log:
        "logs/visco2008/fig04.log",
    script:
        "../scripts/visco2008_fig04.py"


rule visco2008_fig05:
    input:
        scan="results/visco2008/cloning.nc",
        closures=visco2008_theory("closures"),
        reference="results/visco2008/cloning/reference.nc",
        template=caption_template("visco2008_fig05"),
        script=figure_script("visco2008_fig05"),
    output:
        pdf="results/visco2008/fig05.pdf",
        png=report(
            "results/visco2008/fig05.png",
            caption=rendered_caption("visco2008", "fig05"),
            category="visco2008",
        ),
        caption="results/visco2008/fig05.caption.rst",
    log:
        "logs/visco2008/fig05.log",
    script:
        "../scripts/visco2008_fig05.py"


rule visco2008_fig06:
    input:
        scan="results/visco2008/cloning.nc",
        closures=visco2008_theory("closures"),
        reference="results/visco2008/cloning/reference.nc",
        template=caption_template("visco2008_fig06"),
        script=figure_script("visco2008_fig06"),
    output:
        pdf="results/visco2008/fig06.pdf",
        png=report(
            "results/visco2008/fig06.png",
            caption=rendered_caption("visco2008", "fig06"),
            category="visco2008",
        ),
        caption="results/visco2008/fig06.caption.rst",
    log:
        "logs/visco2008/fig06.log",
    script:
        "../scripts/visco2008_fig06.py"


rule visco2008_fig07:
    input:
        scan="results/visco2008/cloning.nc",
        closures=visco2008_theory("closures"),
        reference="results/visco2008/cloning/reference.nc",
        script=figure_script("visco2008_fig07"),
    output:
        pdf="results/visco2008/fig07.pdf",
        png=report(
            "results/visco2008/fig07.png",
            caption="../report/visco2008_fig07.rst",
            category="visco2008",
        ),
    log:
        "logs/visco2008/fig07.log",
    script:
        "../scripts/visco2008_fig07.py"


rule visco2008_fig08:
    input:
        scan="results/visco2008/cloning.nc",
        closures=visco2008_theory("closures"),
        reference="results/visco2008/cloning/reference.nc",
        template=caption_template("visco2008_fig08"),
        script=figure_script("visco2008_fig08"),
    output:
        pdf="results/visco2008/fig08.pdf",
        png=report(
            "results/visco2008/fig08.png",
            caption=rendered_caption("visco2008", "fig08"),
            category="visco2008",
        ),
        caption="results/visco2008/fig08.caption.rst",
    log:
        "logs/visco2008/fig08.log",
    script:
        "../scripts/visco2008_fig08.py"


rule visco2008_cloning_velocity_density:
    input:
        scan="results/visco2008/cloning.nc",
        script=figure_script("visco2008_cloning_velocity_density"),
    output:
        pdf="results/visco2008/cloning_velocity_density.pdf",
        png=report(
            "results/visco2008/cloning_velocity_density.png",
            caption="../report/visco2008_cloning_velocity_density.rst",
            category="visco2008",
            subcategory="cloning Monte Carlo",
        ),
    log:
        "logs/visco2008/cloning_velocity_density.log",
    script:
        "../scripts/visco2008_cloning_velocity_density.py"


rule visco2008_cloning_extrapolation:
    input:
        scan="results/visco2008/cloning.nc",
        reference="results/visco2008/cloning/reference.nc",
        script=figure_script("visco2008_cloning_extrapolation"),
    output:
        pdf="results/visco2008/cloning_extrapolation.pdf",
        png=report(
            "results/visco2008/cloning_extrapolation.png",
            caption="../report/visco2008_cloning_extrapolation.rst",
            category="visco2008",
            subcategory="cloning Monte Carlo",
        ),
    log:
        "logs/visco2008/cloning_extrapolation.log",
    script:
        "../scripts/visco2008_cloning_extrapolation.py"


rule visco2008_cloning_error_vs_time:
    input:
        curves="results/visco2008/cloning/error_vs_time.nc",
        table="results/visco2008/cloning_error_vs_time.csv",
        script=figure_script("visco2008_cloning_error_vs_time"),
    output:
        pdf="results/visco2008/cloning_error_vs_time.pdf",
        png=report(
            "results/visco2008/cloning_error_vs_time.png",
            caption="../report/visco2008_cloning_error_vs_time.rst",
            category="visco2008",
            subcategory="cloning Monte Carlo",
        ),
    log:
        "logs/visco2008/cloning_error_vs_time.log",
    script:
        "../scripts/visco2008_cloning_error_vs_time.py"
