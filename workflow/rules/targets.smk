# One aggregate target per paper: `snakemake visco2008` builds every registered artefact
# of that paper. Included last, after every rule file has registered its targets.


localrules:
    all,
    visco2008,
    montanero2007,
    krauth2025,
    costantini2010,


rule visco2008:
    input:
        lambda wildcards: paper_targets("visco2008"),


rule montanero2007:
    input:
        lambda wildcards: paper_targets("montanero2007"),


rule krauth2025:
    # Figs 4.1, 4.6, 4.10, 4.11, 4.13, chaos, the pin, pressure and error-vs-time tables
    input:
        lambda wildcards: paper_targets("krauth2025"),


rule costantini2010:
    # Figs 1-7, Table 1, error against CPU time, DSMC convergence
    input:
        lambda wildcards: paper_targets("costantini2010"),
