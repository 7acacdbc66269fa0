# One aggregate target per paper: `snakemake visco2008` builds every registered artefact
# of that paper. Included last, after every rule file has registered its targets.

localrules:
    all,
    visco2008,
    montanero2007,
    krauth2025,
    costantini2010,



def visco2008_artefacts(wildcards):
    return paper_targets("visco2008")


def montanero2007_artefacts(wildcards):
    return paper_targets("montanero2007")


def krauth2025_artefacts(wildcards):
    return paper_targets("krauth2025")


def costantini2010_artefacts(wildcards):
    return paper_targets("costantini2010")


rule visco2008:
    input:
        visco2008_artefacts,


rule montanero2007:
    input:
        montanero2007_artefacts,


rule krauth2025:
    # Figs 4.1, 4.6, 4.10, 4.11, 4.13, chaos, the pin, pressure and error-vs-time tables
    input:
        krauth2025_artefacts,


rule costantini2010:
    # Figs 1-7, Table 1, error against CPU time, DSMC convergence
    input:
        costantini2010_artefacts,
