# krauth2025: the helpers of its rules (paths, input functions, params), included before
# its rule files, which hold only rules and the targets they register.

from kinetic.studies import krauth2025 as krauth2025_study

# ---------------------------------------------------------------- for the simulation rules


def krauth2025_pins():
    return config["krauth2025"]["pins"]


def krauth2025_line_files():
    """The washing-line samples (kinetic.studies.krauth2025.LINE_RUNS)."""
    pins = krauth2025_pins()
    return [
        results_file(
            f"krauth2025/pins/{krauth2025_study.line_name(method, pins[key])}.nc"
        )
        for method, key in krauth2025_study.LINE_RUNS
    ]


def krauth2025_disks():
    return config["krauth2025"]["disks"]


# ---------------------------------------------------------------- for the theory rules
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
        raise WorkflowError(
            f"no krauth2025 pin run at length {wildcards.length}: {sorted(lengths)}"
        )
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


# ---------------------------------------------------------------- for the analysis rules
def krauth2025_snapshot_panels(wildcards):
    """Events drawn in Fig 4.1 after the start."""
    return krauth2025_disks()["snapshot_events"]
