# visco2008 figures built on the DSMC engine: Fig. 12 (Maxwell molecules' free paths).
# The hard-disk free-flight times of Fig. 1's DSMC squares are
# results/visco2008/dsmc/free_flight_times.nc (variables time_pdf, time_pdf_sem on
# flight_time), an input of the Fig. 1 rule.

provide("visco2008/fig12", *figure_files("visco2008", "fig12"))


rule visco2008_fig12:
    input:
        dsmc="results/visco2008/dsmc/maxwell_free_paths.nc",
        curves=visco2008_theory("free_paths"),
        template=caption_template("visco2008_fig12"),
        script=figure_script("visco2008_fig12"),
    output:
        pdf="results/visco2008/fig12.pdf",
        png=report(
            "results/visco2008/fig12.png",
            caption=rendered_caption("visco2008", "fig12"),
            category="visco2008",
        ),
        caption="results/visco2008/fig12.caption.rst",
    log:
        "logs/visco2008/fig12.log",
    script:
        "../scripts/visco2008_fig12.py"
