# visco2008 theory: the curves of the paper's equations on the config's grids (one netCDF
# per family under <results>/visco2008/theory/) and the deterministic solution of Eq. 28
# drawn beside the cloning data. Figures read these files; they compute no theory.


rule visco2008_theory:
    input:
        code=script_code("visco2008_theory"),
    output:
        results_file("visco2008/theory/{family}.nc"),
    log:
        log_file("visco2008/theory/{family}.log"),
    wildcard_constraints:
        family="|".join(VISCO2008_THEORY_FAMILIES),
    params:
        grid=visco2008_theory_grid,
    script:
        "../../scripts/visco2008_theory.py"


rule visco2008_theory_cloning_reference:
    input:
        code=script_code("visco2008_theory_cloning_reference"),
    output:
        results_file("visco2008/cloning/reference.nc"),
    log:
        log_file("visco2008/cloning_reference.log"),
    benchmark:
        log_file("benchmarks/visco2008/cloning_reference.tsv")
    threads: 1
    params:
        lambdas=visco2008_cloning_reference_lambdas,
        nodes=visco2008_cloning_reference_nodes,
    script:
        "../../scripts/visco2008_theory_cloning_reference.py"
