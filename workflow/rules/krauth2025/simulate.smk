# krauth2025 simulations: the random clothes-pins of section 4.4.1 (kinetic.samplers:
# direct-pin and naive-pin on a washing line, Markov chains on a ring, snapshots) and the
# hard disks in a box of sections 4.1-4.4 (kinetic.edmd event-disks, direct-disks and
# markov-disks, the chaos run). Each job writes one netCDF file holding its histograms and
# their standard errors; the exact curves beside them come from theory.smk.


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
