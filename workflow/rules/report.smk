# Workflow tables for `snakemake --report`: the config the build ran with (validated, with
# every default filled in) and, per simulation job, the estimated cost, the resources it
# asked for and what its benchmark file measured (kinetic.plan.job_table). With
# targets: all, the job table waits for every simulation job; otherwise it lists the jobs
# whose outputs exist.
provide("workflow/config", results_file("workflow/config.yaml"))
provide("workflow/jobs", results_file("workflow/jobs.csv"))


localrules:
    workflow_config,
    workflow_jobs,
    workflow_agreement,


rule workflow_config:
    input:
        code=script_code("workflow_config"),
    output:
        report(
            results_file("workflow/config.yaml"),
            caption="../report/workflow_config.rst",
            category="configuration and jobs",
        ),
    log:
        log_file("workflow/config.log"),
    params:
        config=workflow_config,
    script:
        "../scripts/workflow_config.py"


rule workflow_jobs:
    input:
        workflow_job_outputs,
        code=script_code("workflow_jobs"),
    output:
        report(
            results_file("workflow/jobs.csv"),
            caption="../report/workflow_jobs.rst",
            category="configuration and jobs",
        ),
    log:
        log_file("workflow/jobs.log"),
    params:
        config=workflow_config,
    script:
        "../scripts/workflow_jobs.py"


provide(
    "workflow/agreement",
    results_file("workflow/agreement.csv"),
    results_file("workflow/agreement.rst"),
)


rule workflow_agreement:
    # The number of checks passed, failed and reported per document: the report's front
    # page (workflow/report/workflow.rst includes the reStructuredText twin).
    input:
        tables=workflow_agreement_tables,
        code=script_code("workflow_agreement"),
    output:
        csv=report(
            results_file("workflow/agreement.csv"),
            caption="../report/workflow_agreement.rst",
            category="configuration and jobs",
        ),
        rst=results_file("workflow/agreement.rst"),
    log:
        log_file("workflow/agreement.log"),
    script:
        "../scripts/workflow_agreement.py"
