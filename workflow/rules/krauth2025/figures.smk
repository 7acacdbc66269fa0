# krauth2025 figures and tables: Figs 4.1, 4.6, 4.10, 4.11, 4.13, the chaos figure and
# table, the velocities figure, the pins and pressure tables and the error-against-time
# study, from the files of simulate.smk.


provide("krauth2025/fig04_10", *figure_files("krauth2025", "fig04_10"))


provide("krauth2025/fig04_11", *figure_files("krauth2025", "fig04_11"))


provide("krauth2025/fig04_13", *figure_files("krauth2025", "fig04_13"))


provide("krauth2025/pins_table", *table_files("krauth2025", "pins_table"))


rule krauth2025_fig04_10:
    input:
        snapshots=results_file("krauth2025/pins/snapshots.nc"),
        code=script_code("krauth2025_fig04_10"),
    output:
        pdf=results_file("krauth2025/fig04_10.pdf"),
        png=report(
            results_file("krauth2025/fig04_10.png"),
            caption="../../report/krauth2025_fig04_10.rst",
            category="krauth2025",
        ),
    log:
        log_file("krauth2025/fig04_10.log"),
    script:
        "../../scripts/krauth2025_fig04_10.py"


rule krauth2025_fig04_11:
    input:
        lines=krauth2025_line_files(),
        theory=krauth2025_line_theory_files(),
        code=script_code("krauth2025_fig04_11"),
    output:
        pdf=results_file("krauth2025/fig04_11.pdf"),
        png=report(
            results_file("krauth2025/fig04_11.png"),
            caption="../../report/krauth2025_fig04_11.rst",
            category="krauth2025",
        ),
    log:
        log_file("krauth2025/fig04_11.log"),
    script:
        "../../scripts/krauth2025_fig04_11.py"


rule krauth2025_fig04_13:
    input:
        ring=results_file("krauth2025/pins/ring.nc"),
        theory=results_file("krauth2025/theory/ring.nc"),
        code=script_code("krauth2025_fig04_13"),
    output:
        pdf=results_file("krauth2025/fig04_13.pdf"),
        png=report(
            results_file("krauth2025/fig04_13.png"),
            caption="../../report/krauth2025_fig04_13.rst",
            category="krauth2025",
        ),
    log:
        log_file("krauth2025/fig04_13.log"),
    script:
        "../../scripts/krauth2025_fig04_13.py"


rule krauth2025_pins_table:
    input:
        lines=krauth2025_line_files(),
        theory=krauth2025_line_theory_files(),
        code=script_code("krauth2025_pins_table"),
    output:
        csv=results_file("krauth2025/pins_table.csv"),
        md=results_file("krauth2025/pins_table.md"),
    log:
        log_file("krauth2025/pins_table.log"),
    script:
        "../../scripts/krauth2025_pins_table.py"


provide("krauth2025/fig04_01", *figure_files("krauth2025", "fig04_01"))


provide(
    "krauth2025/chaos",
    *figure_files("krauth2025", "chaos"),
    *table_files("krauth2025", "chaos_table"),
)


provide("krauth2025/fig04_06", *figure_files("krauth2025", "fig04_06"))


provide("krauth2025/velocities", *figure_files("krauth2025", "velocities"))


provide("krauth2025/pressure_table", *table_files("krauth2025", "pressure_table"))


rule krauth2025_fig04_01:
    input:
        chaos=results_file("krauth2025/disks/chaos.nc"),
        code=script_code("krauth2025_fig04_01"),
    output:
        pdf=results_file("krauth2025/fig04_01.pdf"),
        png=report(
            results_file("krauth2025/fig04_01.png"),
            caption="../../report/krauth2025_fig04_01.rst",
            category="krauth2025",
        ),
    log:
        log_file("krauth2025/fig04_01.log"),
    params:
        panels=krauth2025_snapshot_panels,
    script:
        "../../scripts/krauth2025_fig04_01.py"


rule krauth2025_chaos:
    input:
        chaos=results_file("krauth2025/disks/chaos.nc"),
        code=script_code("krauth2025_chaos"),
        template=caption_template("krauth2025_chaos"),
    output:
        pdf=results_file("krauth2025/chaos.pdf"),
        png=report(
            results_file("krauth2025/chaos.png"),
            caption=rendered_caption("krauth2025", "chaos"),
            category="krauth2025",
        ),
        caption=results_file("krauth2025/chaos.caption.rst"),
        csv=results_file("krauth2025/chaos_table.csv"),
        md=results_file("krauth2025/chaos_table.md"),
    log:
        log_file("krauth2025/chaos.log"),
    script:
        "../../scripts/krauth2025_chaos.py"


rule krauth2025_fig04_06:
    input:
        md=results_file("krauth2025/disks/md.nc"),
        direct=results_file("krauth2025/disks/direct.nc"),
        markov=results_file("krauth2025/disks/markov.nc"),
        code=script_code("krauth2025_fig04_06"),
    output:
        pdf=results_file("krauth2025/fig04_06.pdf"),
        png=report(
            results_file("krauth2025/fig04_06.png"),
            caption="../../report/krauth2025_fig04_06.rst",
            category="krauth2025",
        ),
    log:
        log_file("krauth2025/fig04_06.log"),
    script:
        "../../scripts/krauth2025_fig04_06.py"


rule krauth2025_velocities:
    input:
        md=results_file("krauth2025/disks/md.nc"),
        code=script_code("krauth2025_velocities"),
        template=caption_template("krauth2025_velocities"),
    output:
        pdf=results_file("krauth2025/velocities.pdf"),
        png=report(
            results_file("krauth2025/velocities.png"),
            caption=rendered_caption("krauth2025", "velocities"),
            category="krauth2025",
        ),
        caption=results_file("krauth2025/velocities.caption.rst"),
    log:
        log_file("krauth2025/velocities.log"),
    script:
        "../../scripts/krauth2025_velocities.py"


rule krauth2025_pressure_table:
    input:
        md=results_file("krauth2025/disks/md.nc"),
        direct=results_file("krauth2025/disks/direct.nc"),
        code=script_code("krauth2025_pressure_table"),
    output:
        csv=results_file("krauth2025/pressure_table.csv"),
        md=results_file("krauth2025/pressure_table.md"),
    log:
        log_file("krauth2025/pressure_table.log"),
    script:
        "../../scripts/krauth2025_pressure_table.py"


provide(
    "krauth2025/error_vs_time",
    *figure_files("krauth2025", "error_vs_time"),
    *table_files("krauth2025", "error_vs_time"),
)


rule krauth2025_error_vs_time:
    input:
        lines=krauth2025_line_files(),
        ring=results_file("krauth2025/pins/ring.nc"),
        md=results_file("krauth2025/disks/md.nc"),
        direct=results_file("krauth2025/disks/direct.nc"),
        markov=results_file("krauth2025/disks/markov.nc"),
        code=script_code("krauth2025_error_vs_time"),
    output:
        pdf=results_file("krauth2025/error_vs_time.pdf"),
        png=report(
            results_file("krauth2025/error_vs_time.png"),
            caption="../../report/krauth2025_error_vs_time.rst",
            category="krauth2025",
        ),
        csv=results_file("krauth2025/error_vs_time.csv"),
        md=results_file("krauth2025/error_vs_time.md"),
    log:
        log_file("krauth2025/error_vs_time.log"),
    script:
        "../../scripts/krauth2025_error_vs_time.py"


provide("krauth2025/checks", *table_files("krauth2025", "checks"))


rule krauth2025_checks:
    # The lecture's claims on the washing line and the four disks
    # (kinetic.analysis.krauth2025.checks); a failed check stops the build when the
    # config's fail_on_checks lists krauth2025.
    input:
        pins=results_file("krauth2025/pins_table.csv"),
        pressure=results_file("krauth2025/pressure_table.csv"),
        code=script_code("krauth2025_checks"),
    output:
        csv=report(
            results_file("krauth2025/checks.csv"),
            caption="../../report/checks.rst",
            category="krauth2025",
            subcategory="checks",
        ),
        md=results_file("krauth2025/checks.md"),
    log:
        log_file("krauth2025/checks.log"),
    params:
        fail=fails_on_checks("krauth2025"),
    script:
        "../../scripts/krauth2025_checks.py"
