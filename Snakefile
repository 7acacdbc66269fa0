# kinetic: every figure and table of four kinetic-theory documents, from this repository alone.
#
#   snakemake --cores all                      every available artefact (config/config.yaml)
#   snakemake --cores all visco2008            one document
#   snakemake --cores 1 results/visco2008/fig03.pdf   one figure, and only what it needs
#   snakemake --cores all --configfile config/ci.yaml  the whole workflow in minutes
#
# This file is a table of contents. Each document's rules live in
# workflow/rules/<document>/rules.smk, in the order its pipelines run them: theory
# (<document>_theory...) where the document has theory files of its own, simulations and
# their joins (<document>_simulate_<what>, <document>_aggregate_<what>), then analyses,
# figures, tables and checks (<document>_figNN, ...); the helpers those rules call live in
# the folder's common.smk. workflow/rules/common.smk holds what every document shares.

from snakemake.utils import min_version

min_version("9.0")


# A config file given with --configfile is the whole truth: the default is read only when
# none is given (the schemas fill in, visibly, every key a file leaves out), so a key absent
# from the user's file never keeps the default config's value.
if not workflow.overwrite_configfiles:

    configfile: f"{workflow.basedir}/config/config.yaml"


report: "workflow/report/workflow.rst"


include: "workflow/rules/common.smk"
include: "workflow/rules/visco2008/common.smk"
include: "workflow/rules/visco2008/rules.smk"
include: "workflow/rules/montanero2007/common.smk"
include: "workflow/rules/montanero2007/rules.smk"
include: "workflow/rules/krauth2025/common.smk"
include: "workflow/rules/krauth2025/rules.smk"
include: "workflow/rules/costantini2010/common.smk"
include: "workflow/rules/costantini2010/rules.smk"
include: "workflow/rules/report.smk"
include: "workflow/rules/targets.smk"
include: "workflow/rules/budget.smk"


rule all:
    default_target: True
    input:
        all_targets,
