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
