"""kinetic.cost and kinetic.plan: resource requests, the budget check, the summary."""

import math
from pathlib import Path

import numpy as np
import pytest

from kinetic import cost, plan
from kinetic.cloning.arguments import default_control_interval
from kinetic.cost import Estimate
from kinetic.studies import Job

REPOSITORY = Path(__file__).resolve().parents[2]


def _job(seconds, memory_mb=0.0, document="d", output="results/x.nc", benchmark=None):
    estimate = Estimate(seconds, memory_mb, "work")
    return Job(document, "rule", output, "m:f", {"seed": 1}, estimate, (), benchmark=benchmark)


def test_requests_carry_the_safety_factors_and_double_on_every_retry():
    estimate = Estimate(600.0, 500.0, "work")
    # the first job after an edit also compiles an engine (at most the slowest one)
    compilation = max(cost.COMPILE_SECONDS.values())
    seconds = cost.JOB_OVERHEAD_SECONDS + cost.RUNTIME_SAFETY * (600.0 + compilation)
    minutes = math.ceil(seconds / 60.0)
    assert cost.runtime_minutes(estimate) == minutes
    assert cost.runtime_minutes(estimate, attempt=3) == 4 * minutes
    megabytes = cost.BASE_MEMORY_MB + cost.MEMORY_SAFETY * 500.0
    assert cost.mem_mb(estimate) == 100 * math.ceil(megabytes / 100)
    assert cost.mem_mb(estimate, attempt=2) == 2 * cost.mem_mb(estimate)
    tiny = Estimate(0.1, 0.0, "work")
    assert cost.runtime_minutes(tiny) == cost.MIN_RUNTIME_MINUTES


def test_cloning_cost_grows_like_e_to_the_lambda_through_the_transient():
    """The transient needed for a member to keep a few collisions is e^λ mean free times."""

    def seconds(lam):
        transient = max(10.0, 2 * math.exp(lam) * math.sqrt(2))
        return cost.cloning_batch(
            lam=lam,
            population=1000,
            duration=100.0,
            transient=transient,
            n_blocks=10,
            n_realizations=4,
        ).cpu_seconds

    assert seconds(20.0) / seconds(19.0) == pytest.approx(math.e, rel=1e-3)
    assert seconds(30.0) / 3600 > 1e5  # hundreds of thousands of CPU-hours


def test_costs_scale_with_the_work():
    one = cost.edmd_periodic(
        n_particles=1000, density=0.01, realizations=1, equilibration=10, duration=100
    )
    four = cost.edmd_periodic(
        n_particles=1000, density=0.01, realizations=4, equilibration=10, duration=100
    )
    assert four.cpu_seconds == pytest.approx(4 * one.cpu_seconds)
    # a collision costs more in a larger system and in a more dilute one
    big = cost.edmd_periodic(
        n_particles=10**6, density=0.01, realizations=1, equilibration=10, duration=100
    )
    dilute = cost.edmd_periodic(
        n_particles=1000, density=0.001, realizations=1, equilibration=10, duration=100
    )
    assert big.cpu_seconds > 1000 * one.cpu_seconds
    assert dilute.cpu_seconds > one.cpu_seconds
    assert big.memory_mb == pytest.approx(1000 * one.memory_mb)
    # montanero2007's paper protocol: ~20 s per realization of 60 τ at N = 2e5
    paper = cost.dsmc_homogeneous(
        n_particles=200_000, duration=60, time_step=0.003, realizations=1, sample_stride=50
    )
    assert 10 < paper.cpu_seconds < 40


def test_limits_refuse_with_the_estimate_and_the_key():
    jobs = [_job(100.0), _job(20 * 3600.0, output="results/long.nc")]
    with pytest.raises(plan.BudgetError, match=r"results/long.nc: estimated 20 CPU-hours"):
        plan.check_limits(jobs, {"max_job_cpu_hours": 12})
    plan.check_limits(jobs, {"max_job_cpu_hours": 21})
    heavy = [_job(1.0, memory_mb=40_000.0, output="results/heavy.nc")]
    message = r"heavy.nc: would ask for 81 GB .*max_job_memory_gb"
    with pytest.raises(plan.BudgetError, match=message):
        plan.check_limits(heavy, {"max_job_memory_gb": 16})
    with pytest.raises(plan.BudgetError, match=r"max_total_cpu_hours = 5"):
        plan.check_limits([_job(3 * 3600.0)] * 2, {"max_total_cpu_hours": 5})


def test_wall_time_is_bounded_by_the_longest_job_and_the_total_over_the_cores():
    seconds = [7.0, 5.0, 4.0, 4.0, 3.0, 3.0, 2.0, 2.0, 1.0]
    for cores in (1, 2, 3, 64):
        wall = plan.wall_seconds(seconds, cores)
        lower = max(max(seconds), sum(seconds) / cores)
        assert lower <= wall <= 4 / 3 * lower + 1e-12
    assert plan.wall_seconds(seconds, 1) == sum(seconds)
    assert plan.wall_seconds([], 4) == 0.0


def test_summary_rows_add_up_per_document():
    jobs = [_job(3600.0, document="a"), _job(7200.0, document="a"), _job(1800.0, document="b")]
    rows = {row["document"]: row for row in plan.summary_rows(jobs, cores=(1, 1024))}
    assert rows["a"]["jobs"] == 2 and rows["b"]["jobs"] == 1 and rows["total"]["jobs"] == 3
    assert rows["total"]["cpu_hours"] == pytest.approx(3.5)
    overhead = cost.JOB_OVERHEAD_SECONDS / 3600
    assert rows["total"]["wall_hours_1"] == pytest.approx(3.5 + 3 * overhead)
    assert rows["total"]["wall_hours_1024"] == pytest.approx(2.0 + overhead)
    assert "| total | 3 |" in plan.summary_table(jobs)


def test_jobs_killed_for_time_or_memory_are_told_which_resource_to_raise():
    log = (
        "Error in rule visco2008_simulate_cloning:\n"
        "    message: SLURM-job '17' failed, SLURM status is: 'TIMEOUT'. Detailed failure "
        "reason unavailable (status command is not 'sacct').\n"
        "    jobid: 3\n"
        "    output: results/visco2008/cloning/scan/a/batch0000.nc\n"
        "    log: logs/visco2008/cloning/scan/a/batch0.log (check log file(s) for error details)\n"
        "\n"
        "Error in rule montanero2007_simulate_dsmc:\n"
        "    message: SLURM-job '18' failed, SLURM status is: 'OUT_OF_MEMORY'.\n"
        "    output: results/montanero2007/dsmc/alpha030/batch0000.nc\n"
        "\n"
        "Error in rule visco2008_fig01:\n"
        "    message: SLURM-job '19' failed, SLURM status is: 'FAILED'.\n"
    )
    hints = plan.resource_hints(log).splitlines()
    assert len(hints) == 2
    assert "visco2008_simulate_cloning (results/visco2008/cloning/scan/a/batch0000.nc)" in hints[0]
    assert "raise its runtime" in hints[0]
    assert "logs/visco2008/cloning/scan/a/batch0.log" in hints[0]
    assert "montanero2007_simulate_dsmc" in hints[1] and "raise its mem_mb" in hints[1]
    assert plan.resource_hints("nothing failed") == ""


def test_overruns_compare_the_cpu_time_a_job_used_with_its_request(tmp_path):
    """A job that waited for a core (wall time above its request, CPU time below) is not an
    overrun; one whose CPU time exceeds the request is; without a CPU sample the wall time
    stands in."""
    limit = cost.requested_seconds(Estimate(10.0, 0.0, "work"))
    header = "s\th:m:s\tmax_rss\tmax_vms\tmax_uss\tmax_pss\tio_in\tio_out\tmean_load\tcpu_time\n"
    cases = {"waited": (limit + 50, limit - 1), "overran": (limit + 50, limit + 1)}
    cases["unsampled"] = (limit + 50, "NA")
    jobs = []
    for name, (wall, cpu) in cases.items():
        (tmp_path / f"{name}.tsv").write_text(
            header + f"{wall}\t0:00:00\t10\t0\t0\t0\t0\t0\t0\t{cpu}\n"
        )
        jobs.append(_job(10.0, output=name, benchmark=f"{name}.tsv"))
    checked, overruns = plan.benchmark_overruns(tmp_path, jobs)
    assert checked == 3
    assert [line.split(":")[0] for line in overruns] == ["overran", "unsampled"]


def test_cuda_cloning_estimate_uses_the_fronts_control_interval():
    """A cuda cloning job asks for one GPU and costs less than the same realizations on one
    core (the plan takes the front's control interval from kinetic.cloning.arguments,
    without loading the kernels)."""
    arguments = {
        "lam": 1.0,
        "population": 10_000,
        "duration": 1e4,
        "transient": 50.0,
        "n_blocks": 20,
        "n_realizations": 32,
    }
    gpu = cost.cloning_batch(**arguments, backend="cuda")
    cpu = cost.cloning_batch(**arguments)
    assert gpu.gpus == 1 and cpu.gpus == 0
    assert gpu.cpu_seconds < cpu.cpu_seconds / 10


def test_cuda_cloning_estimate_switches_path_where_the_engine_does():
    """Up to the engine's RESIDENT_MAX_POPULATION a realization runs in one thread block,
    above it four launches per control interval; the switch sits where the two paths cost
    about the same (an H100 timed the resident kernel slower than the launches at 10⁴
    clones and 3.7 times faster at 10³; with 256 threads, revision 5836ea7, 1.19 times
    slower at 10⁴): at the switch their estimates are within a factor 2 of each other
    for the control intervals of λ = 1 and -1 (the 256-thread fit puts the resident
    kernel 1.4-1.6 times cheaper at 5000 clones, where no GPU has timed either), and only
    the launched one pays the launches."""
    pytest.importorskip("numba.cuda")
    from kinetic.cloning import gpu
    from kinetic.studies import visco2008_cloning

    assert cost.CLONING_GPU_RESIDENT_MAX_POPULATION == gpu.RESIDENT_MAX_POPULATION
    assert visco2008_cloning.GROUPED_MAX_POPULATION >= gpu.RESIDENT_MAX_POPULATION
    largest = gpu.RESIDENT_MAX_POPULATION
    for lam in (1.0, -1.0):
        arguments = {"lam": lam, "duration": 1e5, "transient": 50.0, "n_blocks": 20}
        resident = cost.cloning_batch(
            **arguments, population=largest, n_realizations=32, backend="cuda"
        )
        launched = cost.cloning_batch(
            **arguments, population=largest + 1, n_realizations=32, backend="cuda"
        )
        intervals = (arguments["duration"] + 50.0) / default_control_interval(lam)
        assert launched.cpu_seconds >= intervals * cost.CLONING_GPU_SECONDS_PER_INTERVAL
        assert 1 / 2 < resident.cpu_seconds / launched.cpu_seconds < 2
    small = cost.cloning_batch(**arguments, population=1000, n_realizations=32, backend="cuda")
    assert small.cpu_seconds < intervals * cost.CLONING_GPU_SECONDS_PER_INTERVAL


def test_cuda_cloning_points_sharing_launches_cost_their_slowest_point():
    """Points in the same launches (kinetic.cloning.simulate_points): one startup, the
    slowest realization's latency, not the sum of the points' jobs."""
    points = [
        {
            "lam": lam,
            "population": 1000,
            "duration": 2e4,
            "transient": 50.0,
            "n_blocks": 20,
            "n_realizations": 32,
        }
        for lam in (-1.0, 0.5, 1.0, 2.0)
    ]
    alone = [cost.cloning_batch(**point, backend="cuda") for point in points]
    together = cost.cloning_points(points)
    assert together.gpus == 1
    slowest = max(estimate.cpu_seconds for estimate in alone)
    events = 4 * 32 * 1000 * (2e4 + 1e3)  # the transient rounded up to a block of 1000
    rate = events / cost.CLONING_GPU_EVENTS_PER_SECOND + cost.GPU_JOB_STARTUP_SECONDS
    assert together.cpu_seconds == pytest.approx(max(slowest, rate))  # 128 blocks: one wave
    assert together.cpu_seconds < sum(estimate.cpu_seconds for estimate in alone) - 15.0


def test_cuda_cloning_points_share_the_gpu_as_blocks_finish():
    """More resident blocks than the GPU holds: a block starts when one ends, so the job
    costs every realization's latency shared among CLONING_GPU_RESIDENT_BLOCKS (many equal
    realizations), but never less than its slowest one (one long point beside short ones,
    which the others' blocks fill in behind): the H100 run of 5836ea7 timed the grouped
    shape at its slowest realization, not at waves × the slowest."""
    point = {"population": 1000, "duration": 2e3, "transient": 50.0, "n_blocks": 20}
    one = cost._cloning_gpu(1.0, 1000, cost._cloning_elapsed(2e3, 50.0, 20), 1)[0]
    count = 4 * cost.CLONING_GPU_RESIDENT_BLOCKS
    many = cost.cloning_points([{**point, "lam": 1.0, "n_realizations": count}])
    events = count * 1000 * cost._cloning_elapsed(2e3, 50.0, 20)
    assert 4 * one > events / cost.CLONING_GPU_EVENTS_PER_SECOND  # latency-bound
    assert many.cpu_seconds - cost.GPU_JOB_STARTUP_SECONDS == pytest.approx(4 * one)
    long = {**point, "lam": 1.0, "duration": 4e4, "n_realizations": 1}
    short = {**point, "lam": 1.0, "n_realizations": cost.CLONING_GPU_RESIDENT_BLOCKS}
    slowest = cost._cloning_gpu(1.0, 1000, cost._cloning_elapsed(4e4, 50.0, 20), 1)[0]
    mixed = cost.cloning_points([long, short])
    assert slowest > 2 * one  # more than the short ones' share: the slowest decides
    assert mixed.cpu_seconds - cost.GPU_JOB_STARTUP_SECONDS == pytest.approx(slowest)


def test_cloning_blocks_are_cut_as_the_front_cuts_them():
    """cost._cloning_blocks repeats the front's cut of a run into blocks (the transient in at
    most MAX_TRANSIENT_BLOCKS blocks, none shorter than a measured one) without loading
    the kernels."""
    from kinetic.cloning import front

    for duration, transient, n_blocks in [(100.0, 2.5, 4), (100.0, 30.0, 10), (40.0, 3e3, 8)]:
        p = front.validate_parameters(
            kernel="hard_spheres",
            dimension=2,
            lam=0.5,
            population=10,
            duration=duration,
            transient=transient,
            n_blocks=n_blocks,
            n_realizations=2,
            first_realization=0,
            seed=1,
            histogram_half_width=6.0,
            histogram_bins=8,
            backend="cpu",
            control_interval=None,
        )
        blocks = cost._cloning_blocks(duration, transient, n_blocks)
        np.testing.assert_allclose(blocks, front._Plan(p, None).durations, rtol=1e-15)


def test_cuda_cloning_points_above_the_resident_kernel_pay_each_interval_once():
    """Points of more clones than the resident kernel holds share the four launches of
    every interval: the job costs the intervals of the point with the most (the others
    idle through the rest of a block) plus every point's events at the GPU's rate and one
    startup, far less than one job per point."""
    population = cost.CLONING_GPU_RESIDENT_MAX_POPULATION + 1
    points = [
        {
            "lam": lam,
            "population": population,
            "duration": 1e3,
            "transient": 0.0,
            "n_blocks": 10,
            "n_realizations": 32,
        }
        for lam in (-1.0, 1.0, 2.0)
    ]
    together = cost.cloning_points(points)
    intervals = 1e3 / min(default_control_interval(lam) for lam in (-1.0, 1.0, 2.0))
    events = 3 * 32 * population * 1e3
    expected = (
        intervals * cost.CLONING_GPU_SECONDS_PER_INTERVAL
        + events / cost.CLONING_GPU_EVENTS_PER_SECOND
        + cost.GPU_JOB_STARTUP_SECONDS
    )
    assert together.cpu_seconds == pytest.approx(expected, rel=0.01)  # whole intervals
    alone = [cost.cloning_batch(**point, backend="cuda") for point in points]
    assert together.cpu_seconds < sum(estimate.cpu_seconds for estimate in alone)


def test_inhomogeneous_dsmc_runs_sharing_launches_pay_the_longest_runs_steps_once():
    """``cooling_modes_points`` (several α in one cuda job): the fixed cost of a step and
    of a sample for the longest run only, the particle-steps of every run, one startup."""
    points = [
        {
            "n_particles": 3000,
            "density": 0.005,
            "fictive_factor": 10,
            "time_step": 0.1,
            "sample_interval": 0.4,
            "n_samples": n_samples,
            "n_realizations": 16,
        }
        for n_samples in (1000, 3000, 2000)
    ]
    alone = [cost.cooling_modes(engine="dsmc", backend="cuda", **point) for point in points]
    together = cost.cooling_modes_points(points)
    fixed = (
        3000 * 4 * cost.COOLING_DSMC_GPU_TOGETHER_SECONDS_PER_STEP
        + 3000 * cost.COOLING_DSMC_GPU_SECONDS_PER_SAMPLE
    )
    particle_steps = 16 * 30_000 * 6000 * 4
    rate = particle_steps / cost.COOLING_DSMC_GPU_PARTICLE_STEPS_PER_SECOND
    assert together.gpus == 1
    assert together.cpu_seconds == pytest.approx(fixed + rate + cost.GPU_JOB_STARTUP_SECONDS)
    assert together.cpu_seconds < sum(estimate.cpu_seconds for estimate in alone)
    assert together.memory_mb == pytest.approx(sum(estimate.memory_mb for estimate in alone))


def test_the_paper_gpu_layer_runs_cloning_and_the_dsmc_on_one_gpu():
    """config/paper-gpu.yaml over paper.yaml: its own results root, every cloning point,
    montanero2007 family and costantini2010 DSMC run one GPU job, hard-disk populations up
    to 10⁶."""
    from kinetic.config import load_configs

    config = load_configs([REPOSITORY / "config/paper.yaml", REPOSITORY / "config/paper-gpu.yaml"])
    assert config["results"] == "results/paper-gpu"
    jobs = plan.plan_jobs(config)
    on_gpu = {job.rule for job in jobs if job.estimate.gpus}
    cloning = {rule for rule in on_gpu if rule.startswith("visco2008_simulate_cloning")}
    grid = {rule for rule in on_gpu if rule.startswith("costantini2010_simulate_dsmc_grid_")}
    assert grid == {
        f"costantini2010_simulate_dsmc_grid_n{n}" for n in config["costantini2010"]["particles"]
    }
    families = {rule for rule in on_gpu if rule.startswith("montanero2007_simulate_dsmc_")}
    assert families == {
        f"montanero2007_simulate_dsmc_{family}"
        for family in ("scan", "field", "bias", "hcs", "error", "extreme")
    }
    rest = on_gpu - cloning - grid - families
    assert rest == {"costantini2010_simulate_dsmc"}
    assert "visco2008_simulate_cloning" in cloning  # N_c above the resident kernel's
    sizes = {
        job.arguments["population"]
        for job in jobs
        if job.rule == "visco2008_simulate_cloning" and job.arguments["kernel"] == "hard_spheres"
    }
    assert max(sizes) == 10**6


def test_homogeneous_dsmc_runs_sharing_a_job_pay_one_startup():
    """montanero2007's runs of one family in one cuda job (``simulate_batches``): the
    runs' GPU time with one process's startup instead of one each, the largest run's
    memory; on the cpu (no startup counted) the sum of the runs."""
    runs = [
        {"n_particles": 2000, "duration": 6.0, "time_step": 0.003, "realizations": 40},
        {"n_particles": 200000, "duration": 6.0, "time_step": 0.003, "realizations": 100},
        {"n_particles": 500, "duration": 3.0, "time_step": 0.03, "realizations": 800},
    ]
    for backend in ("cuda", "cpu"):
        alone = [cost.dsmc_homogeneous(**run, backend=backend) for run in runs]
        together = cost.dsmc_homogeneous_points(runs, backend=backend)
        startup = cost.GPU_JOB_STARTUP_SECONDS if backend == "cuda" else 0.0
        total = sum(estimate.cpu_seconds for estimate in alone)
        assert together.cpu_seconds == pytest.approx(total - 2 * startup)
        assert together.memory_mb == max(estimate.memory_mb for estimate in alone)
        assert together.gpus == (1 if backend == "cuda" else 0)
