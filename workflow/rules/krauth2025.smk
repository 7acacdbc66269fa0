# krauth2025 §4.4.1, random clothes-pins: Fig 4.10 (direct-pin configurations), Fig 4.11
# (pin density on a washing line: naive-pin and direct-pin against Eq. 4.7), Fig 4.13 (pins
# on a ring: pair density from Markov chains against the ring-to-line mapping) and the
# table of wall and bulk densities. Each sampling job writes one netCDF file holding its
# histograms, their standard errors and the exact densities; figures only read them.

provide("krauth2025/fig04_10", *figure_files("krauth2025", "fig04_10"))
provide("krauth2025/fig04_11", *figure_files("krauth2025", "fig04_11"))
provide("krauth2025/fig04_13", *figure_files("krauth2025", "fig04_13"))
provide("krauth2025/pins_table", *table_files("krauth2025", "pins_table"))

# the line samples of Fig 4.11 and the table: (method, length key of config pins)
KRAUTH2025_LINE_RUNS = [("direct", "length"), ("naive", "naive_length"), ("direct", "naive_length")]


def krauth2025_pins():
    return config["krauth2025"]["pins"]


def krauth2025_line_files():
    pins = krauth2025_pins()
    return [
        f"results/krauth2025/pins/{method}_L{pins[key]:g}.nc"
        for method, key in KRAUTH2025_LINE_RUNS
    ]


def krauth2025_line_job(wildcards):
    """Keyword arguments of kinetic.samplers.sample_line for one line file."""
    pins = krauth2025_pins()
    length = float(wildcards.length)
    known = {(m, float(pins[key])) for m, key in KRAUTH2025_LINE_RUNS}
    if (wildcards.method, length) not in known:
        raise ValueError(
            f"no krauth2025 pin run {wildcards.method} at length {length}: the config asks "
            f"for {sorted(known)}"
        )
    return {
        "method": wildcards.method,
        "n_pins": pins["n_pins"],
        "length": length,
        "sigma": pins["sigma"],
        "samples": pins[f"{wildcards.method}_samples"],
        "batches": pins["batches"],
        "bins": max(1, round((length - 2 * pins["sigma"]) / pins["bin_width"])),
        "seed": job_seed(f"krauth2025/pins/{wildcards.method}_L{wildcards.length}"),
    }


def krauth2025_ring_job(wildcards):
    ring = config["krauth2025"]["ring"]
    keys = ("n_pins", "length", "sigma", "step", "sweeps", "burn_in", "chains")
    job = {key: ring[key] for key in keys}
    job["bins"] = max(1, round(ring["length"] / ring["bin_width"]))
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
    from kinetic.samplers import MAX_NAIVE_STARTS, naive_acceptance
    from kinetic.theory.krauth2025 import check_pins

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
    starts = (
        pins["naive_samples"]
        * pins["batches"]
        / naive_acceptance(pins["n_pins"], pins["naive_length"], pins["sigma"])
    )
    if starts > MAX_NAIVE_STARTS:
        raise WorkflowError(
            f"config krauth2025.pins: naive-pin on naive_length = {pins['naive_length']} "
            f"would start about {starts:.2g} configurations; lengthen the line or lower "
            f"naive_samples"
        )


krauth2025_check_config()
KRAUTH2025_SOURCES = engine_sources("samplers") + package_files("theory/krauth2025")


rule krauth2025_line:
    input:
        sources=KRAUTH2025_SOURCES,
        warm=numba_warm("samplers"),
    output:
        "results/krauth2025/pins/{method}_L{length}.nc",
    log:
        "logs/krauth2025/pins/{method}_L{length}.log",
    benchmark:
        "logs/benchmarks/krauth2025/pins/{method}_L{length}.tsv"
    params:
        job=krauth2025_line_job,
    wildcard_constraints:
        method="naive|direct",
        length="[0-9.]+",
    resources:
        runtime=planned_runtime,
        mem_mb=planned_mem_mb,
    script:
        "../scripts/krauth2025_line.py"


rule krauth2025_ring:
    input:
        sources=KRAUTH2025_SOURCES,
        warm=numba_warm("samplers"),
    output:
        "results/krauth2025/pins/ring.nc",
    log:
        "logs/krauth2025/pins/ring.log",
    benchmark:
        "logs/benchmarks/krauth2025/pins/ring.tsv"
    params:
        job=krauth2025_ring_job,
    resources:
        runtime=planned_runtime,
        mem_mb=planned_mem_mb,
    script:
        "../scripts/krauth2025_ring.py"


rule krauth2025_snapshots:
    input:
        sources=KRAUTH2025_SOURCES,
        warm=numba_warm("samplers"),
    output:
        "results/krauth2025/pins/snapshots.nc",
    log:
        "logs/krauth2025/pins/snapshots.log",
    params:
        job=krauth2025_snapshots_job,
    resources:
        runtime=planned_runtime,
        mem_mb=planned_mem_mb,
    script:
        "../scripts/krauth2025_snapshots.py"


rule krauth2025_fig04_10:
    input:
        snapshots="results/krauth2025/pins/snapshots.nc",
        script=figure_script("krauth2025_fig04_10"),
    output:
        pdf="results/krauth2025/fig04_10.pdf",
        png=report(
            "results/krauth2025/fig04_10.png",
            caption="../report/krauth2025_fig04_10.rst",
            category="krauth2025",
        ),
    log:
        "logs/krauth2025/fig04_10.log",
    script:
        "../scripts/krauth2025_fig04_10.py"


rule krauth2025_fig04_11:
    input:
        lines=krauth2025_line_files(),
        script=figure_script("krauth2025_fig04_11"),
    output:
        pdf="results/krauth2025/fig04_11.pdf",
        png=report(
            "results/krauth2025/fig04_11.png",
            caption="../report/krauth2025_fig04_11.rst",
            category="krauth2025",
        ),
    log:
        "logs/krauth2025/fig04_11.log",
    script:
        "../scripts/krauth2025_fig04_11.py"


rule krauth2025_fig04_13:
    input:
        ring="results/krauth2025/pins/ring.nc",
        script=figure_script("krauth2025_fig04_13"),
    output:
        pdf="results/krauth2025/fig04_13.pdf",
        png=report(
            "results/krauth2025/fig04_13.png",
            caption="../report/krauth2025_fig04_13.rst",
            category="krauth2025",
        ),
    log:
        "logs/krauth2025/fig04_13.log",
    script:
        "../scripts/krauth2025_fig04_13.py"


rule krauth2025_pins_table:
    input:
        lines=krauth2025_line_files(),
        script=figure_script("krauth2025_pins_table"),
    output:
        csv="results/krauth2025/pins_table.csv",
        md="results/krauth2025/pins_table.md",
    log:
        "logs/krauth2025/pins_table.log",
    script:
        "../scripts/krauth2025_pins_table.py"


# ------------------------------------------------------------------ hard disks in a box
# Fig 4.1 (event-disks snapshots), the chaos of section 4.1.2, Figs 4.5/4.6 (y-density by
# Eq. 4.3 and from snapshots, against direct-disks and markov-disks: the equal-probability
# check) and the pressure table of section 4.4.3 (Eqs. 4.9, 4.10, 4.13, 4.14).

provide("krauth2025/fig04_01", *figure_files("krauth2025", "fig04_01"))
provide(
    "krauth2025/chaos",
    *figure_files("krauth2025", "chaos"),
    *table_files("krauth2025", "chaos_table"),
)
provide("krauth2025/fig04_06", *figure_files("krauth2025", "fig04_06"))
provide("krauth2025/velocities", *figure_files("krauth2025", "velocities"))
provide("krauth2025/pressure_table", *table_files("krauth2025", "pressure_table"))


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
        "batches": disks["batches"],
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


def krauth2025_snapshot_panels(wildcards):
    """Events drawn in Fig 4.1 after the start."""
    return krauth2025_disks()["snapshot_events"]


def krauth2025_check_disks():
    """Stop before any job on a box that cannot hold the disks."""
    from kinetic.samplers import disk_configuration
    from kinetic.rng import stream_states

    disks = krauth2025_disks()
    try:
        disk_configuration(
            disks["n_disks"],
            disks["sigma"],
            disks["box"],
            state=stream_states(0, 1)[0],
            max_starts=10**6,
        )
    except ValueError as error:
        raise WorkflowError(f"config krauth2025.disks: {error}") from None


krauth2025_check_disks()
KRAUTH2025_DISK_SOURCES = engine_sources("edmd") + package_files("samplers")


rule krauth2025_md:
    input:
        sources=KRAUTH2025_DISK_SOURCES,
        warm=[numba_warm("edmd"), numba_warm("samplers")],
    output:
        "results/krauth2025/disks/md.nc",
    log:
        "logs/krauth2025/disks/md.log",
    benchmark:
        "logs/benchmarks/krauth2025/disks/md.tsv"
    params:
        job=krauth2025_md_job,
    resources:
        runtime=planned_runtime,
        mem_mb=planned_mem_mb,
    script:
        "../scripts/krauth2025_md.py"


rule krauth2025_disk_sampler:
    input:
        sources=engine_sources("samplers"),
        warm=numba_warm("samplers"),
    output:
        "results/krauth2025/disks/{method}.nc",
    log:
        "logs/krauth2025/disks/{method}.log",
    benchmark:
        "logs/benchmarks/krauth2025/disks/{method}.tsv"
    params:
        job=krauth2025_sampler_job,
    wildcard_constraints:
        method="direct|markov",
    resources:
        runtime=planned_runtime,
        mem_mb=planned_mem_mb,
    script:
        "../scripts/krauth2025_disk_sampler.py"


rule krauth2025_chaos_run:
    input:
        sources=KRAUTH2025_DISK_SOURCES,
        warm=[numba_warm("edmd"), numba_warm("samplers")],
    output:
        "results/krauth2025/disks/chaos.nc",
    log:
        "logs/krauth2025/disks/chaos.log",
    params:
        job=krauth2025_chaos_job,
    resources:
        runtime=planned_runtime,
        mem_mb=planned_mem_mb,
    script:
        "../scripts/krauth2025_chaos_run.py"


rule krauth2025_fig04_01:
    input:
        chaos="results/krauth2025/disks/chaos.nc",
        script=figure_script("krauth2025_fig04_01"),
    output:
        pdf="results/krauth2025/fig04_01.pdf",
        png=report(
            "results/krauth2025/fig04_01.png",
            caption="../report/krauth2025_fig04_01.rst",
            category="krauth2025",
        ),
    log:
        "logs/krauth2025/fig04_01.log",
    params:
        panels=krauth2025_snapshot_panels,
    script:
        "../scripts/krauth2025_fig04_01.py"


rule krauth2025_chaos:
    input:
        chaos="results/krauth2025/disks/chaos.nc",
        script=figure_script("krauth2025_chaos"),
        template=caption_template("krauth2025_chaos"),
    output:
        pdf="results/krauth2025/chaos.pdf",
        png=report(
            "results/krauth2025/chaos.png",
            caption=rendered_caption("krauth2025", "chaos"),
            category="krauth2025",
        ),
        caption="results/krauth2025/chaos.caption.rst",
        csv="results/krauth2025/chaos_table.csv",
        md="results/krauth2025/chaos_table.md",
    log:
        "logs/krauth2025/chaos.log",
    script:
        "../scripts/krauth2025_chaos.py"


rule krauth2025_fig04_06:
    input:
        md="results/krauth2025/disks/md.nc",
        direct="results/krauth2025/disks/direct.nc",
        markov="results/krauth2025/disks/markov.nc",
        script=figure_script("krauth2025_fig04_06"),
    output:
        pdf="results/krauth2025/fig04_06.pdf",
        png=report(
            "results/krauth2025/fig04_06.png",
            caption="../report/krauth2025_fig04_06.rst",
            category="krauth2025",
        ),
    log:
        "logs/krauth2025/fig04_06.log",
    script:
        "../scripts/krauth2025_fig04_06.py"


rule krauth2025_velocities:
    input:
        md="results/krauth2025/disks/md.nc",
        script=figure_script("krauth2025_velocities"),
        template=caption_template("krauth2025_velocities"),
    output:
        pdf="results/krauth2025/velocities.pdf",
        png=report(
            "results/krauth2025/velocities.png",
            caption=rendered_caption("krauth2025", "velocities"),
            category="krauth2025",
        ),
        caption="results/krauth2025/velocities.caption.rst",
    log:
        "logs/krauth2025/velocities.log",
    script:
        "../scripts/krauth2025_velocities.py"


rule krauth2025_pressure_table:
    input:
        md="results/krauth2025/disks/md.nc",
        direct="results/krauth2025/disks/direct.nc",
        script=figure_script("krauth2025_pressure_table"),
    output:
        csv="results/krauth2025/pressure_table.csv",
        md="results/krauth2025/pressure_table.md",
    log:
        "logs/krauth2025/pressure_table.log",
    script:
        "../scripts/krauth2025_pressure_table.py"


provide(
    "krauth2025/error_vs_time",
    *figure_files("krauth2025", "error_vs_time"),
    *table_files("krauth2025", "error_vs_time"),
)


rule krauth2025_error_vs_time:
    input:
        lines=krauth2025_line_files(),
        ring="results/krauth2025/pins/ring.nc",
        md="results/krauth2025/disks/md.nc",
        direct="results/krauth2025/disks/direct.nc",
        markov="results/krauth2025/disks/markov.nc",
        script=figure_script("krauth2025_error_vs_time"),
    output:
        pdf="results/krauth2025/error_vs_time.pdf",
        png=report(
            "results/krauth2025/error_vs_time.png",
            caption="../report/krauth2025_error_vs_time.rst",
            category="krauth2025",
        ),
        csv="results/krauth2025/error_vs_time.csv",
        md="results/krauth2025/error_vs_time.md",
    log:
        "logs/krauth2025/error_vs_time.log",
    script:
        "../scripts/krauth2025_error_vs_time.py"
