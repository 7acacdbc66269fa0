# krauth2025 simulations: the random clothes-pins of section 4.4.1 (kinetic.samplers:
# direct-pin and naive-pin on a washing line, Markov chains on a ring, snapshots) and the
# hard disks in a box of sections 4.1-4.4 (kinetic.edmd event-disks, direct-disks and
# markov-disks, the chaos run). Each job writes one netCDF file holding its histograms and
# their standard errors; the exact curves beside them come from theory.smk.

def krauth2025_pins():
    return config["krauth2025"]["pins"]


def krauth2025_line_files():
    pins = krauth2025_pins()
    return [
        results_file(f"krauth2025/pins/{method}_L{pins[key]:g}.nc")
        for method, key in job_plan.LINE_RUNS
    ]


def krauth2025_line_length(method, token):
    """The config length of a line run whose path carries ``token`` (looked up among the
    runs of kinetic.plan.LINE_RUNS, not parsed); ``method`` None: any sampler."""
    pins = krauth2025_pins()
    lengths = {
        (run_method, f"{pins[key]:g}"): float(pins[key])
        for run_method, key in job_plan.LINE_RUNS
        if method in (None, run_method)
    }
    matches = {value for (_, known), value in lengths.items() if known == token}
    if not matches:
        raise ValueError(
            f"no krauth2025 pin run {method or ''} at length {token}: the config asks for "
            f"{sorted(lengths)}"
        )
    return matches.pop()


def krauth2025_line_bins(length):
    """Bins of the line histograms over [sigma, length - sigma): width about bin_width."""
    pins = krauth2025_pins()
    return max(1, round((length - 2 * pins["sigma"]) / pins["bin_width"]))


def krauth2025_ring_bins():
    """Bins of the ring histogram over [0, length): width about bin_width."""
    ring = config["krauth2025"]["ring"]
    return max(1, round(ring["length"] / ring["bin_width"]))


def krauth2025_line_job(wildcards):
    """Keyword arguments of kinetic.samplers.sample_line for one line file."""
    pins = krauth2025_pins()
    length = krauth2025_line_length(wildcards.method, wildcards.length)
    return {
        "method": wildcards.method,
        "n_pins": pins["n_pins"],
        "length": length,
        "sigma": pins["sigma"],
        "samples": pins[f"{wildcards.method}_samples"],
        "realizations": pins["realizations"],
        "bins": krauth2025_line_bins(length),
        "seed": job_seed(f"krauth2025/pins/{wildcards.method}_L{wildcards.length}"),
    }


def krauth2025_ring_job(wildcards):
    ring = config["krauth2025"]["ring"]
    keys = ("n_pins", "length", "sigma", "step", "sweeps", "burn_in", "realizations")
    job = {key: ring[key] for key in keys}
    job["bins"] = krauth2025_ring_bins()
    job["seed"] = job_seed("krauth2025/pins/ring")
    return job


def krauth2025_snapshots_job(wildcards):
    pins = krauth2025_pins()
    return {
        "n_pins": pins["n_pins"],
        "length": pins["length"],
        "sigma": pins["sigma"],
        "count": pins["snapshots"],
        "seed": job_seed("krauth2025/pins/snapshots"),
    }


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
        code=simulation_code("krauth2025_simulate_line", "samplers"),
    output:
        results_file("krauth2025/pins/{method}_L{length}.nc"),
    log:
        log_file("krauth2025/pins/{method}_L{length}.log"),
    benchmark:
        log_file("benchmarks/krauth2025/pins/{method}_L{length}.tsv")
    params:
        job=krauth2025_line_job,
    wildcard_constraints:
        method="naive|direct",
        length="[0-9.]+",
    resources:
        runtime=planned_runtime,
        mem_mb=planned_mem_mb,
    script:
        "../../scripts/krauth2025_simulate_line.py"


rule krauth2025_simulate_ring:
    input:
        code=simulation_code("krauth2025_simulate_ring", "samplers"),
    output:
        results_file("krauth2025/pins/ring.nc"),
    log:
        log_file("krauth2025/pins/ring.log"),
    benchmark:
        log_file("benchmarks/krauth2025/pins/ring.tsv")
    params:
        job=krauth2025_ring_job,
    resources:
        runtime=planned_runtime,
        mem_mb=planned_mem_mb,
    script:
        "../../scripts/krauth2025_simulate_ring.py"


rule krauth2025_simulate_pin_snapshots:
    input:
        code=simulation_code("krauth2025_simulate_pin_snapshots", "samplers"),
    output:
        results_file("krauth2025/pins/snapshots.nc"),
    log:
        log_file("krauth2025/pins/snapshots.log"),
    params:
        job=krauth2025_snapshots_job,
    resources:
        runtime=planned_runtime,
        mem_mb=planned_mem_mb,
    script:
        "../../scripts/krauth2025_simulate_pin_snapshots.py"


# ------------------------------------------------------------------ hard disks in a box
# Fig 4.1 (event-disks snapshots), the chaos of section 4.1.2, Figs 4.5/4.6 (y-density by
# Eq. 4.3 and from snapshots, against direct-disks and markov-disks: the equal-probability
# check) and the pressure table of section 4.4.3 (Eqs. 4.9, 4.10, 4.13, 4.14).

def krauth2025_disks():
    return config["krauth2025"]["disks"]


def krauth2025_disk_bins():
    disks = krauth2025_disks()
    return max(1, round((disks["box"][1] - 2 * disks["sigma"]) / disks["bin_width"]))


def krauth2025_md_job(wildcards):
    disks = krauth2025_disks()
    return {
        "n_disks": disks["n_disks"],
        "sigma": disks["sigma"],
        "box": disks["box"],
        "duration": disks["md_duration"],
        "snapshot_interval": disks["snapshot_interval"],
        "bins": krauth2025_disk_bins(),
        "realizations": disks["realizations"],
        "velocity_bins": disks["velocity_bins"],
        "seed": job_seed("krauth2025/disks/md"),
    }


def krauth2025_sampler_job(wildcards):
    disks = krauth2025_disks()
    markov = wildcards.method == "markov"
    return {
        "method": wildcards.method,
        "n_disks": disks["n_disks"],
        "sigma": disks["sigma"],
        "box": disks["box"],
        "samples": disks["markov_sweeps" if markov else "direct_samples"],
        "realizations": disks["sampler_realizations"],
        "bins": krauth2025_disk_bins(),
        "step": disks["markov_step"],
        "burn_in": disks["burn_in"],
        "seed": job_seed(f"krauth2025/disks/{wildcards.method}"),
    }


def krauth2025_chaos_job(wildcards):
    disks = krauth2025_disks()
    return {
        "n_disks": disks["n_disks"],
        "sigma": disks["sigma"],
        "box": disks["box"],
        "events": max(disks["chaos_events"], disks["snapshot_events"]),
        "start": disks["start"],
        "extra_starts": disks["chaos_starts"],
        "seed": job_seed("krauth2025/disks/chaos"),
    }


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
        code=simulation_code("krauth2025_simulate_md", "edmd", "samplers"),
    output:
        results_file("krauth2025/disks/md.nc"),
    log:
        log_file("krauth2025/disks/md.log"),
    benchmark:
        log_file("benchmarks/krauth2025/disks/md.tsv")
    params:
        job=krauth2025_md_job,
    resources:
        runtime=planned_runtime,
        mem_mb=planned_mem_mb,
    script:
        "../../scripts/krauth2025_simulate_md.py"


rule krauth2025_simulate_disks:
    input:
        code=simulation_code("krauth2025_simulate_disks", "samplers"),
    output:
        results_file("krauth2025/disks/{method}.nc"),
    log:
        log_file("krauth2025/disks/{method}.log"),
    benchmark:
        log_file("benchmarks/krauth2025/disks/{method}.tsv")
    params:
        job=krauth2025_sampler_job,
    wildcard_constraints:
        method="direct|markov",
    resources:
        runtime=planned_runtime,
        mem_mb=planned_mem_mb,
    script:
        "../../scripts/krauth2025_simulate_disks.py"


rule krauth2025_simulate_chaos:
    input:
        code=simulation_code("krauth2025_simulate_chaos", "edmd", "samplers"),
    output:
        results_file("krauth2025/disks/chaos.nc"),
    log:
        log_file("krauth2025/disks/chaos.log"),
    params:
        job=krauth2025_chaos_job,
    resources:
        runtime=planned_runtime,
        mem_mb=planned_mem_mb,
    script:
        "../../scripts/krauth2025_simulate_chaos.py"
