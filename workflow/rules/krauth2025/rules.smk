# krauth2025: every rule of the document, in the order its pipelines run them (simulations
# and joins, then theory, then analyses, figures, tables and checks); the helpers they call
# are in common.smk.


# ======================================================================================
# simulations (krauth2025_simulate_<what>; one job a run, so no joins)
# ======================================================================================
# krauth2025 simulations: the random clothes-pins of section 4.4.1 (kinetic.samplers:
# direct-pin and naive-pin on a washing line, Markov chains on a ring, snapshots) and the
# hard disks in a box of sections 4.1-4.4 (kinetic.edmd event-disks, direct-disks and
# markov-disks, the chaos run). Each job writes one netCDF file holding its histograms and
# their standard errors over all its realizations (the runs take minutes, so no batches);
# the exact curves beside them come from the theory rules.


rule krauth2025_simulate_line:
    input:
        code=job_code("krauth2025_simulate_line"),
    output:
        results_file("krauth2025/pins/{method}_L{length}.nc"),
    log:
        log_file("krauth2025/pins/{method}_L{length}.log"),
    benchmark:
        log_file("benchmarks/krauth2025/pins/{method}_L{length}.tsv")
    wildcard_constraints:
        method="naive|direct",
        length="[0-9.]+",
    resources:
        runtime=planned_runtime,
        mem_mb=planned_mem_mb,
    params:
        front=job_param("krauth2025_simulate_line", "front"),
        job=job_param("krauth2025_simulate_line", "arguments"),
        parameters=job_param("krauth2025_simulate_line", "parameters"),
    script:
        "../../scripts/simulate.py"


rule krauth2025_simulate_ring:
    input:
        code=job_code("krauth2025_simulate_ring"),
    output:
        results_file("krauth2025/pins/ring.nc"),
    log:
        log_file("krauth2025/pins/ring.log"),
    benchmark:
        log_file("benchmarks/krauth2025/pins/ring.tsv")
    resources:
        runtime=planned_runtime,
        mem_mb=planned_mem_mb,
    params:
        front=job_param("krauth2025_simulate_ring", "front"),
        job=job_param("krauth2025_simulate_ring", "arguments"),
        parameters=job_param("krauth2025_simulate_ring", "parameters"),
    script:
        "../../scripts/simulate.py"


rule krauth2025_simulate_pin_snapshots:
    input:
        code=job_code("krauth2025_simulate_pin_snapshots"),
    output:
        results_file("krauth2025/pins/snapshots.nc"),
    log:
        log_file("krauth2025/pins/snapshots.log"),
    resources:
        runtime=planned_runtime,
        mem_mb=planned_mem_mb,
    params:
        front=job_param("krauth2025_simulate_pin_snapshots", "front"),
        job=job_param("krauth2025_simulate_pin_snapshots", "arguments"),
        parameters=job_param("krauth2025_simulate_pin_snapshots", "parameters"),
    script:
        "../../scripts/simulate.py"


# ------------------------------------------------------------------ hard disks in a box
# Fig 4.1 (event-disks snapshots), the chaos of section 4.1.2, Figs 4.5/4.6 (y-density by
# Eq. 4.3 and from snapshots, against direct-disks and markov-disks: the equal-probability
# check) and the pressure table of section 4.4.3 (Eqs. 4.9, 4.10, 4.13, 4.14).


rule krauth2025_simulate_md:
    input:
        code=job_code("krauth2025_simulate_md"),
    output:
        results_file("krauth2025/disks/md.nc"),
    log:
        log_file("krauth2025/disks/md.log"),
    benchmark:
        log_file("benchmarks/krauth2025/disks/md.tsv")
    resources:
        runtime=planned_runtime,
        mem_mb=planned_mem_mb,
    params:
        front=job_param("krauth2025_simulate_md", "front"),
        job=job_param("krauth2025_simulate_md", "arguments"),
        parameters=job_param("krauth2025_simulate_md", "parameters"),
    script:
        "../../scripts/simulate.py"


rule krauth2025_simulate_disks:
    input:
        code=job_code("krauth2025_simulate_disks"),
    output:
        results_file("krauth2025/disks/{method}.nc"),
    log:
        log_file("krauth2025/disks/{method}.log"),
    benchmark:
        log_file("benchmarks/krauth2025/disks/{method}.tsv")
    wildcard_constraints:
        method="direct|markov",
    resources:
        runtime=planned_runtime,
        mem_mb=planned_mem_mb,
    params:
        front=job_param("krauth2025_simulate_disks", "front"),
        job=job_param("krauth2025_simulate_disks", "arguments"),
        parameters=job_param("krauth2025_simulate_disks", "parameters"),
    script:
        "../../scripts/simulate.py"


rule krauth2025_simulate_chaos:
    input:
        code=job_code("krauth2025_simulate_chaos"),
    output:
        results_file("krauth2025/disks/chaos.nc"),
    log:
        log_file("krauth2025/disks/chaos.log"),
    resources:
        runtime=planned_runtime,
        mem_mb=planned_mem_mb,
    params:
        front=job_param("krauth2025_simulate_chaos", "front"),
        job=job_param("krauth2025_simulate_chaos", "arguments"),
        parameters=job_param("krauth2025_simulate_chaos", "parameters"),
    script:
        "../../scripts/simulate.py"


# ======================================================================================
# theory: exact curves and solutions, tabulated once (figures compute none)
# ======================================================================================
# krauth2025 theory: the exact pin densities beside the samples (Eq. 4.7 on a line, the
# ring-to-line mapping on a ring), on the samplers' bins and on fine grids. The sampling
# jobs and the figures compute none of it.


rule krauth2025_theory_line:
    input:
        code=script_code("krauth2025_theory"),
    output:
        results_file("krauth2025/theory/line_L{length}.nc"),
    log:
        log_file("krauth2025/theory/line_L{length}.log"),
    wildcard_constraints:
        length="[0-9.]+",
    params:
        curves=krauth2025_line_theory,
    script:
        "../../scripts/krauth2025_theory.py"


rule krauth2025_theory_ring:
    input:
        code=script_code("krauth2025_theory"),
    output:
        results_file("krauth2025/theory/ring.nc"),
    log:
        log_file("krauth2025/theory/ring.log"),
    params:
        curves=krauth2025_ring_theory,
    script:
        "../../scripts/krauth2025_theory.py"


# ======================================================================================
# analyses named after what they compute, figures, tables and checks
# ======================================================================================
# krauth2025 figures and tables: Figs 4.1, 4.6, 4.10, 4.11, 4.13, the chaos figure and
# table, the velocities figure, the pins and pressure tables and the error-against-time
# study, from the files of the simulation rules.


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
        template=caption_template("krauth2025_fig04_11"),
    output:
        pdf=results_file("krauth2025/fig04_11.pdf"),
        png=report(
            results_file("krauth2025/fig04_11.png"),
            caption=rendered_caption("krauth2025", "fig04_11"),
            category="krauth2025",
        ),
        caption=results_file("krauth2025/fig04_11.caption.rst"),
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
        checks=config["krauth2025"]["checks"],
        fail=fails_on_checks("krauth2025"),
    script:
        "../../scripts/krauth2025_checks.py"
