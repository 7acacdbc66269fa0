# krauth2025 simulations: the random clothes-pins of section 4.4.1 (kinetic.samplers:
# direct-pin and naive-pin on a washing line, Markov chains on a ring, snapshots) and the
# hard disks in a box of sections 4.1-4.4 (kinetic.edmd event-disks, direct-disks and
# markov-disks, the chaos run). Each job writes one netCDF file holding its histograms and
# their standard errors; the exact curves beside them come from theory.smk.

from kinetic.studies import krauth2025 as krauth2025_study


def krauth2025_pins():
    return config["krauth2025"]["pins"]


def krauth2025_line_files():
    """The washing-line samples (kinetic.studies.krauth2025.LINE_RUNS)."""
    pins = krauth2025_pins()
    return [
        results_file(f"krauth2025/pins/{krauth2025_study.line_name(method, pins[key])}.nc")
        for method, key in krauth2025_study.LINE_RUNS
    ]


def krauth2025_check_config():
    """Stop before any job on values the schema cannot judge alone: lines and rings too
    short for their pins, or a naive-pin run that would take forever."""
    from kinetic.theory.krauth2025 import check_naive_starts, check_pins

    pins, ring = krauth2025_pins(), config["krauth2025"]["ring"]
    try:
        for key in ("length", "naive_length"):
            check_pins(pins["n_pins"], pins[key], pins["sigma"])
        check_pins(ring["n_pins"], ring["length"], ring["sigma"])
    except ValueError as error:
        raise WorkflowError(f"config krauth2025: {error}") from None
    if ring["step"] > ring["length"] / 2:
        raise WorkflowError(
            f"config krauth2025.ring.step = {ring['step']} exceeds half the ring length"
        )
    try:
        samples = pins["naive_samples"] * pins["realizations"]
        check_naive_starts(pins["n_pins"], pins["naive_length"], pins["sigma"], samples)
    except ValueError as error:
        raise WorkflowError(f"config krauth2025.pins (naive_length): {error}") from None


krauth2025_check_config()


rule krauth2025_simulate_line:
    input:
        code=job_code("krauth2025_simulate_line"),
    output:
        results_file("krauth2025/pins/{method}_L{length}.nc"),
    log:
        log_file("krauth2025/pins/{method}_L{length}.log"),
    benchmark:
        log_file("benchmarks/krauth2025/pins/{method}_L{length}.tsv")
    params:
        front=job_front,
        job=job_arguments,
        parameters=job_parameters,
    wildcard_constraints:
        method="naive|direct",
        length="[0-9.]+",
    resources:
        runtime=planned_runtime,
        mem_mb=planned_mem_mb,
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
    params:
        front=job_front,
        job=job_arguments,
        parameters=job_parameters,
    resources:
        runtime=planned_runtime,
        mem_mb=planned_mem_mb,
    script:
        "../../scripts/simulate.py"


rule krauth2025_simulate_pin_snapshots:
    input:
        code=job_code("krauth2025_simulate_pin_snapshots"),
    output:
        results_file("krauth2025/pins/snapshots.nc"),
    log:
        log_file("krauth2025/pins/snapshots.log"),
    params:
        front=job_front,
        job=job_arguments,
        parameters=job_parameters,
    resources:
        runtime=planned_runtime,
        mem_mb=planned_mem_mb,
    script:
        "../../scripts/simulate.py"


# ------------------------------------------------------------------ hard disks in a box
# Fig 4.1 (event-disks snapshots), the chaos of section 4.1.2, Figs 4.5/4.6 (y-density by
# Eq. 4.3 and from snapshots, against direct-disks and markov-disks: the equal-probability
# check) and the pressure table of section 4.4.3 (Eqs. 4.9, 4.10, 4.13, 4.14).

def krauth2025_disks():
    return config["krauth2025"]["disks"]


def krauth2025_check_disks():
    """Stop before any job on a box that cannot hold the disks."""
    from kinetic.studies.krauth2025 import check_disks

    try:
        check_disks(krauth2025_disks())
    except ValueError as error:
        raise WorkflowError(f"config krauth2025.disks: {error}") from None


krauth2025_check_disks()


rule krauth2025_simulate_md:
    input:
        code=job_code("krauth2025_simulate_md"),
    output:
        results_file("krauth2025/disks/md.nc"),
    log:
        log_file("krauth2025/disks/md.log"),
    benchmark:
        log_file("benchmarks/krauth2025/disks/md.tsv")
    params:
        front=job_front,
        job=job_arguments,
        parameters=job_parameters,
    resources:
        runtime=planned_runtime,
        mem_mb=planned_mem_mb,
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
    params:
        front=job_front,
        job=job_arguments,
        parameters=job_parameters,
    wildcard_constraints:
        method="direct|markov",
    resources:
        runtime=planned_runtime,
        mem_mb=planned_mem_mb,
    script:
        "../../scripts/simulate.py"


rule krauth2025_simulate_chaos:
    input:
        code=job_code("krauth2025_simulate_chaos"),
    output:
        results_file("krauth2025/disks/chaos.nc"),
    log:
        log_file("krauth2025/disks/chaos.log"),
    params:
        front=job_front,
        job=job_arguments,
        parameters=job_parameters,
    resources:
        runtime=planned_runtime,
        mem_mb=planned_mem_mb,
    script:
        "../../scripts/simulate.py"
