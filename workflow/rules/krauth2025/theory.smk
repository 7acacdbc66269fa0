# krauth2025 theory: the exact pin densities beside the samples (Eq. 4.7 on a line, the
# ring-to-line mapping on a ring), on the samplers' bins and on fine grids. The sampling
# jobs and the figures compute none of it.


def krauth2025_line_lengths():
    """{file token: length} of the line lengths of the pins runs (looked up, not parsed)."""
    pins = krauth2025_pins()
    return {f"{pins[key]:g}": float(pins[key]) for _, key in krauth2025_study.LINE_RUNS}


def krauth2025_line_theory_files():
    """One exact-density file per line length of the pins runs."""
    return [
        results_file(f"krauth2025/theory/line_L{token}.nc")
        for token in sorted(krauth2025_line_lengths())
    ]


def krauth2025_line_theory(wildcards):
    """Arguments of kinetic.theory.krauth2025.line_dataset for one length."""
    pins = krauth2025_pins()
    lengths = krauth2025_line_lengths()
    if wildcards.length not in lengths:
        raise WorkflowError(f"no krauth2025 pin run at length {wildcards.length}: {sorted(lengths)}")
    length = lengths[wildcards.length]
    return {
        "n_pins": pins["n_pins"],
        "length": length,
        "sigma": pins["sigma"],
        "bins": krauth2025_study.line_bins(pins, length),
    }


def krauth2025_ring_theory(wildcards):
    """Arguments of kinetic.theory.krauth2025.ring_dataset."""
    ring = config["krauth2025"]["ring"]
    return {
        "n_pins": ring["n_pins"],
        "length": ring["length"],
        "sigma": ring["sigma"],
        "bins": krauth2025_study.ring_bins(ring),
    }


rule krauth2025_theory_line:
    input:
        code=script_code("krauth2025_theory"),
    output:
        results_file("krauth2025/theory/line_L{length}.nc"),
    log:
        log_file("krauth2025/theory/line_L{length}.log"),
    params:
        curves=krauth2025_line_theory,
    wildcard_constraints:
        length="[0-9.]+",
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
