"""The driver of ``python -m kinetic.bench cuda`` (no section is timed here): a missing
package stops it before any GPU work, and ``--sections`` runs what it names, in the
order named."""

import os
import sys

os.environ.setdefault("NUMBA_ENABLE_CUDASIM", "1")

import pytest

pytest.importorskip("numba.cuda")

from kinetic.bench import cuda as bench

pytestmark = [
    pytest.mark.cuda,
    # the simulator runs the uint64 random streams in numpy, which warns when they wrap
    pytest.mark.filterwarnings("ignore:overflow encountered:RuntimeWarning"),
]


def test_preflight_names_a_missing_package_before_any_section(monkeypatch):
    """jsonschema missing (as on the H100 machine of revision 2984f74): ``run`` raises at
    once, naming it, and no section starts."""
    started = []
    monkeypatch.setattr(bench, "SECTIONS", {"memory_bound": lambda quick: started.append(1)})
    for name in [m for m in sys.modules if m == "kinetic.config" or m.startswith("jsonschema")]:
        monkeypatch.delitem(sys.modules, name)
    monkeypatch.setitem(sys.modules, "jsonschema", None)
    with pytest.raises(ImportError, match="jsonschema"):
        bench.run(sections=["memory_bound"])
    assert started == []


def test_sections_run_in_the_order_named_and_unknown_ones_are_refused(monkeypatch):
    order = []
    fake = {name: (lambda quick, name=name: order.append(name) or {}) for name in "abc"}
    monkeypatch.setattr(bench, "SECTIONS", fake)
    monkeypatch.setattr(bench, "_device", lambda: {})
    report = bench.run(sections=["c", "a"])
    assert order == ["c", "a"]
    assert list(report["sections"]) == ["c", "a"]
    order.clear()
    bench.run()
    assert order == ["a", "b", "c"]
    with pytest.raises(ValueError, match="unknown sections"):
        bench.run(sections=["d"])


def test_a_failing_section_keeps_what_it_measured(monkeypatch):
    """A section that fails after some cases (as ``inhomogeneous_speed`` did on the H100,
    after 85 s of GPU runs) reports them under ``partial``; the next section starts
    empty."""

    def failing(quick):
        cases = []
        bench._keep(gpu=cases)
        cases.append({"rate": 1.0})
        raise RuntimeError("late failure")

    def fine(quick):
        return {"partial_seen": dict(bench._PARTIAL)}

    monkeypatch.setattr(bench, "SECTIONS", {"failing": failing, "fine": fine})
    monkeypatch.setattr(bench, "_device", lambda: {})
    report = bench.run()
    failed = report["sections"]["failing"]
    assert "late failure" in failed["error"]
    assert failed["partial"] == {"gpu": [{"rate": 1.0}]}
    assert report["sections"]["fine"]["partial_seen"] == {}


def test_grouped_cloning_case_counts_every_points_events(monkeypatch):
    """``cloning_speed``'s grouped-job case (``resident_threads``), at a tiny size under
    the simulator: every point's collisions, over the wall time of the one call."""
    monkeypatch.setattr(bench, "_paper_lambdas", lambda kernel: [1.0, -0.5])
    case = bench._cloning_grouped(8, 4.0, realizations=2)  # one would need blocks of 10
    assert case["points"] == 2 and case["realizations"] == 4
    assert case["events"] > 0
    assert case["events_per_second"] == case["events"] / case["wall_seconds"]
    assert case["path"] == "grouped" and case["planned_seconds"] > 0


def test_maxwell_z_score_at_lambda_zero_is_zero_not_a_division_by_zero():
    """Maxwell molecules at λ = 0 give μ = 0 with no spread (every weight 1): the H100 run
    of revision 5836ea7 lost ``cloning_physics`` to that division."""
    assert bench._z_score(0.0, 0.0) == 0.0
    assert bench._z_score(0.1, 0.0) is None
    assert bench._z_score(-0.003, 0.0015) == pytest.approx(-2.0)


def test_dsmc_case_rates_its_collisions_on_the_engines_clock():
    """``dsmc_speed``/``dsmc_scaling`` cases report the rates on the engine's clock (the
    steps, without the host's Maxwellian starts), which a short run on a GPU spends as
    long on as on its steps, beside the wall-clock ones."""
    case = bench._dsmc(64, 2, 2.0, "cuda")
    assert 0 < case["engine_seconds"] <= case["wall_seconds"]
    assert case["collisions"] > 0
    assert case["engine_collisions_per_second"] == case["collisions"] / case["engine_seconds"]
    steps = 2.0 / 0.1
    assert case["engine_particle_steps_per_second"] == pytest.approx(
        64 * 2 * steps / case["engine_seconds"]
    )
    assert case["engine_collisions_per_second"] >= case["collisions_per_second"]
    # the rate's other side: candidate pairs per collision at the realization's majorant
    assert 0 < case["acceptance"] <= 1
    assert (case["splitting"], case["force_step"], case["time_step"]) == ("strang", "exact", 0.1)


def test_storage_section_times_both_storages_on_each_case_and_finds_the_same_numbers(
    monkeypatch,
):
    """``dsmc_storage`` (never run on a GPU yet) runs each case with the velocities stored
    both ways, one after the other, reports their rate ratio and that they gave the same
    numbers, and leaves the engine's storage as it found it."""
    from kinetic.dsmc import gpu as dsmc_gpu

    monkeypatch.setattr(bench, "SCALING_SHAPES", [(64, 2)])  # one shape: the loop is the same
    compiled = []
    run = bench._dsmc

    def small(n, realizations, duration, backend, **extra):
        if n == 2000:  # the section's compile run: the same types, fewer particles
            compiled.append(dsmc_gpu.STORAGE)
            n = 64
        extra.pop("sample_stride", None)  # 20 steps, a window of 2, not the section's 10
        return run(n, realizations, min(duration, 2.0), backend, **extra)

    monkeypatch.setattr(bench, "_dsmc", small)
    report = bench.dsmc_storage(quick=False)
    assert dsmc_gpu.STORAGE == "components"
    assert compiled == ["components", "particles"]
    cases = report["gpu"]
    assert [c["storage"] for c in cases] == ["components", "particles"] * 2
    assert [(c["n_particles"], c["splitting"]) for c in cases[::2]] == [(64, "strang"), (64, "lie")]
    for ratio in report["particles_over_components"]:
        assert ratio["same_numbers"]
        assert ratio["ratio"] > 0
    # each kernel's registers for each storage on a GPU; the simulator compiles none
    assert set(report["registers_per_thread"]) == {"_collide_sparse", "_force", "_observe"}


def test_cloning_case_rates_its_events_on_the_engines_clock():
    """``cloning_speed``'s cases report the event rate on the engine's clock (the launches
    and the GPU, without the host's initial populations and the final sort that counts
    the distinct clones) beside the wall-clock one."""
    case = bench._cloning("hard_spheres", 1.0, 8, 4.0, 2)
    assert 0 < case["engine_seconds"] <= case["wall_seconds"]
    assert case["events"] > 0
    assert case["engine_events_per_second"] == case["events"] / case["engine_seconds"]
    assert case["engine_events_per_second"] >= case["events_per_second"]


def test_paper_job_is_the_first_montanero2007_run_on_either_backend():
    """``dsmc_paper_job`` times paper.yaml's first montanero2007 run: on ``cuda`` the first
    point of its family's job (every realization), on the cpu its first batch; the same
    run and seed, ``simulate_batch``'s arguments, and the plan of the run as a job of its
    own."""
    from kinetic import cost
    from kinetic.studies import montanero2007

    gpu, front, planned = bench._paper_job("cuda")
    cpu, cpu_front, _ = bench._paper_job("cpu")
    assert front is cpu_front is montanero2007.simulate_batch
    assert gpu["run"] == cpu["run"] and gpu["seed"] == cpu["seed"]
    assert gpu["run"]["n_particles"] == 200_000 and gpu["run"]["time_step"] == 0.003
    assert gpu["backend"] == "cuda" and "backend" not in cpu
    first = next(iter(montanero2007.run_plan(bench._paper_config()["montanero2007"]).values()))
    assert gpu["first"] == 0 and gpu["count"] == first["realizations"] > cpu["count"]
    assert "parameters" not in gpu  # simulate_batch's arguments only
    assert planned > cost.GPU_JOB_STARTUP_SECONDS


def test_document_section_times_each_family_job_in_a_process_of_its_own(monkeypatch):
    """``montanero2007_document`` runs each family job of paper.yaml on cuda as Snakemake
    would, a process a job that writes every run's file, after one process that fills the
    cache; here two of the jobs, shrunk to a few particles and steps, under the
    simulator, and a third that its plan puts past the deadline is skipped, not run."""
    import dataclasses

    from kinetic.studies import montanero2007

    real = montanero2007.jobs

    def shrunk(config):
        assert config["backend"] == "cuda"
        out = []
        for job in real(config)[:3]:
            points = []
            for point in job.arguments["points"][:2]:
                run = dict(point["run"]) | {"n_particles": 40, "sample_stride": 2}
                run |= {"sample_interval": 0.012, "duration": 0.024, "steady_from": 0.012}
                points.append({**point, "run": run, "count": 2})
            outputs = job.outputs[: len(points)]
            out.append(
                dataclasses.replace(
                    job, arguments={**job.arguments, "points": points}, outputs=outputs
                )
            )
        late = dataclasses.replace(out[2].estimate, cpu_seconds=1e6)
        return [*out[:2], dataclasses.replace(out[2], estimate=late)]

    monkeypatch.setattr(montanero2007, "jobs", shrunk)
    report = bench.montanero2007_document(quick=False)
    (compiled,) = report["compile"]  # the one front's first run, shrunk further
    assert "error" not in compiled, compiled["error"]
    assert compiled["front"] == "kinetic.studies.montanero2007_front:simulate_batches"
    assert compiled["files"] == 1 and compiled["engine_seconds"] > 0
    assert report["rules"] == [
        job.rule for job in shrunk(bench._paper_config() | {"backend": "cuda"})
    ]
    ran, late = report["jobs"][:2], report["jobs"][2]
    for row in ran:
        assert "error" not in row, row["error"]
        assert row["files"] == min(2, row["runs"]) and row["engine_seconds"] > 0
        assert row["process_seconds"] > row["engine_seconds"]
    assert "skipped" in late and not report["complete"]
    assert report["timed_seconds"] == sum(row["process_seconds"] for row in ran)


def test_document_rules_name_jobs_or_are_refused_before_any_work(monkeypatch):
    """``KINETIC_DOCUMENT_RULES`` keeps the jobs whose rule ends in one of its names; a
    name that ends no GPU job's rule of the document stops the section before any
    process starts (a typo would otherwise time nothing, after the compilation)."""
    config = bench._paper_config() | {"backend": "cuda"}
    every = bench._document_jobs("costantini2010", config)
    monkeypatch.setenv("KINETIC_DOCUMENT_RULES", "dsmc,grid_n3000")
    kept = bench._document_jobs("costantini2010", config)
    rules = {job.rule for job in kept}
    assert rules == {"costantini2010_simulate_dsmc", "costantini2010_simulate_dsmc_grid_n3000"}
    assert kept == [job for job in every if job.rule in rules]  # in the plan's order
    monkeypatch.setenv("KINETIC_DOCUMENT_RULES", "scan,hsc")
    with pytest.raises(ValueError, match="hsc"):
        bench.montanero2007_document(quick=False)
    monkeypatch.setenv("KINETIC_DOCUMENT_RULES", "grid_n1000")
    with pytest.raises(ValueError, match="grid_n1000"):
        bench.visco2008_document(quick=False)


@pytest.mark.parametrize("document", ["montanero2007", "visco2008", "costantini2010"])
def test_compile_jobs_keep_each_fronts_types_and_shrink_the_work(document):
    """The job that fills the cache before a document's timed jobs is, for each front,
    its first job cut to one run with the same settings but smaller numbers (the fronts
    cast them to the engine's types, so the same kernels): 2 realizations, and fewer
    particles, clones, steps or samples than the run it comes from."""
    import importlib

    study = importlib.import_module(f"kinetic.studies.{document}")
    jobs = [job for job in study.jobs(bench._paper_config() | {"backend": "cuda"}) if job.gpus]
    firsts = {}
    for job in jobs:
        firsts.setdefault(job.front, job)

    def flat(point):  # montanero2007's points hold the run's settings in "run"
        return {k: v for k, v in point.items() if k != "run"} | point.get("run", {})

    for job in firsts.values():
        small = bench._compile_job(document, job)
        before = flat(job.arguments.get("points", [job.arguments])[0])
        (after,) = [flat(p) for p in small.arguments.get("points", [small.arguments])]
        assert set(after) == set(before) and small.front == job.front
        changed = [key for key in before if after[key] != before[key]]
        for key in changed:  # only numbers change, and only downwards
            assert isinstance(before[key], int | float) and isinstance(after[key], int | float)
            assert after[key] < before[key], key
        realizations = after.get("count", after.get("n_realizations"))
        assert realizations == 2 and changed


def test_visco2008_document_runs_a_cloning_job_through_the_workflows_job(monkeypatch):
    """``visco2008_document`` runs a cloning job as the workflow does (``run_job``: the
    job's front, its files), after the compile process of its one front; here the error
    study's job cut to its λ = 1 point of 25 clones over a few intervals, under the
    simulator (where every thread of the resident kernel runs Python)."""
    import dataclasses

    from kinetic.studies import visco2008

    real = visco2008.jobs

    def tiny(config):
        job = next(j for j in real(config) if j.gpus and "error_vs_time" in j.rule)
        point = job.arguments["points"][0]
        assert point["lam"] == 1.0
        point = point | {"duration": 1.0, "n_blocks": 2, "transient": 4.0, "n_realizations": 2}
        arguments = {**job.arguments, "points": [point]}
        return [dataclasses.replace(job, arguments=arguments, outputs=job.files[:1])]

    monkeypatch.setattr(visco2008, "jobs", tiny)
    monkeypatch.setitem(bench._SHRINK, "visco2008", lambda point: point)  # already tiny
    report = bench.visco2008_document(quick=False)
    (compiled,) = report["compile"]
    assert "error" not in compiled, compiled["error"]
    (row,) = report["jobs"]
    assert "error" not in row, row["error"]
    assert row["runs"] == row["files"] == 1 and report["complete"]
    assert row["process_seconds"] > row["engine_seconds"] > 0


def test_the_command_refuses_the_simulator_and_writes_nothing(tmp_path, capsys, monkeypatch):
    """``python -m kinetic.bench cuda`` under ``NUMBA_ENABLE_CUDASIM=1`` stops before any
    section, naming the simulator, and writes no report: the simulator's rates are a Python
    interpreter's, not a GPU's. The variable is set here, not only for the file: on a GPU
    (tests/gpu/check-on-gpu.sh runs these tests with it 0) the command would start every
    section."""
    from kinetic.bench.__main__ import main

    monkeypatch.setenv("NUMBA_ENABLE_CUDASIM", "1")  # what ``backends.simulated`` reads

    with pytest.raises(SystemExit) as stopped:
        main(["cuda", "--out", str(tmp_path)])
    assert stopped.value.code == 2
    assert "NUMBA_ENABLE_CUDASIM=1" in capsys.readouterr().err
    assert list(tmp_path.iterdir()) == []


def test_sigterm_keeps_the_running_sections_partial_and_skips_the_rest(monkeypatch):
    """The device script's ``timeout`` sends SIGTERM: the section running then reports what
    it had measured (``partial``), the report is checkpointed, and no later section
    starts."""
    import signal

    def killed(quick):
        cases = []
        bench._keep(gpu=cases)
        cases.append({"rate": 2.0})
        os.kill(os.getpid(), signal.SIGTERM)
        raise AssertionError("not reached: the signal raises first")

    monkeypatch.setattr(bench, "SECTIONS", {"killed": killed, "later": lambda quick: {}})
    monkeypatch.setattr(bench, "_device", lambda: {})
    saved = []
    report = bench.run(checkpoint=lambda report: saved.append(dict(report["sections"])))
    killed_report = report["sections"]["killed"]
    assert killed_report["partial"] == {"gpu": [{"rate": 2.0}]}
    assert "SIGTERM" in killed_report["error"]
    assert "terminated" in report["sections"]["later"]["skipped"]
    assert saved and "killed" in saved[-1]
    assert signal.getsignal(signal.SIGTERM) is signal.SIG_DFL


def test_scaling_headline_cases_are_the_median_of_three_seeds(monkeypatch):
    """``dsmc_scaling``'s Lie cases (the issue's headline rate) run three seeds and report
    the median one with all three rates; the other cases run once (the runs stubbed: the
    section's loop, not the engine, is under test)."""
    runs = []

    def stub(n, realizations, duration, backend, seed=13, **extra):
        runs.append((extra.get("splitting", "strang"), seed))
        return {"seed": seed, "engine_collisions_per_second": [3.0, 1.0, 2.0][(seed - 13) % 3]}

    monkeypatch.setattr(bench, "_dsmc", stub)
    cases = bench.dsmc_scaling(quick=True)["gpu"]
    lie = [case for case in cases if len(case.get("engine_rates", [])) == 3]
    assert len(lie) == 2  # alpha = 1 and 0.5, one shape (quick)
    for case in lie:
        assert case["engine_rates"] == [3.0, 1.0, 2.0] and case["seed"] == 15  # the median
    assert [case.get("engine_rates") for case in cases].count([3.0]) == 2  # Strang: once
    assert ("strang", 14) not in runs and runs.count(("lie", 14)) == 2
