# Budget of the build, before any job: every simulation job's CPU time and memory are
# estimated from the config (kinetic.plan with kinetic.cost, the same estimates the rules
# ask SLURM for); a config with a job above config['limits'] is refused with the estimate,
# and the main process prints the estimated total. Included after every rule file, so the
# rule files' own config checks speak first.
import sys

try:
    job_plan.check_limits(job_plan.plan_jobs(config), config["limits"])
except job_plan.BudgetError as error:
    raise WorkflowError(str(error)) from None

if workflow.is_main_process:
    print(job_plan.summary_line(job_plan.plan_jobs(config)), file=sys.stderr)


def resource_hints_of_logs(logs):
    """kinetic.plan.resource_hints of the run's log file(s) (``log`` of onerror)."""
    paths = [logs] if isinstance(logs, (str, Path)) else list(logs or [])
    return job_plan.resource_hints(
        "\n".join(Path(path).read_text() for path in paths if Path(path).is_file())
    )


onerror:
    # a job SLURM killed for its time or memory: say which resource to raise
    hints = resource_hints_of_logs(log)
    if hints:
        print(hints, file=sys.stderr)
