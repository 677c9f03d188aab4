# SPDX-License-Identifier: GPL-2.0-or-later
"""icgp.batch: trials on a Dask LocalCluster equal the sequential run and the icgp program's
`icgp servo --trials`, trial for trial; `icgp servo --jobs` runs them end to end."""
import json
import os
import pickle
import re
import subprocess
from pathlib import Path

import pytest

import icgp
import icgp.batch
from icgp._icgp import servo

SOURCE = Path(os.environ["ICGP_SOURCE_DIR"])
SCENARIO = SOURCE / "tests" / "servo" / "data" / "small_pbvs.yaml"
ICGP = os.environ["ICGP"]
TRIALS = 4  # batch_size 3 still splits them into two batches
# Wall-clock timings: they differ from run to run of the same trial.
TIMING_KEYS = {"median_track_ms", "steps_per_s"}


def icgp_servo(*args, timeout=600):
    return subprocess.run([ICGP, "servo", str(SCENARIO), *args], capture_output=True, text=True, timeout=timeout)


def trial_lines(stderr):
    """The per-run lines without their progress part ("[k/N, elapsed, ETA]")."""
    return sorted(re.sub(r" \[\d+/\d+, elapsed .*\]$", "", line) for line in stderr.splitlines()
                  if line.startswith("trial "))


def without_timings(table):
    """The table with its track ms and steps/s columns blanked."""
    rows = table.splitlines()
    return rows[:1] + [re.sub(r"\s+\S+\s+\S+\s+(\d+)$", r" - - \1", row) for row in rows[1:]]


def summary_without_timings(path):
    data = json.loads(Path(path).read_text())
    for summary in data if isinstance(data, list) else [data]:
        for key in TIMING_KEYS:
            summary.pop(key)
    return data


@pytest.fixture(scope="module")
def sequential():
    return icgp.batch.trials(SCENARIO, TRIALS, trackers=["oracle"], progress=False)


@pytest.fixture(scope="module")
def client():
    from dask.distributed import Client

    with icgp.batch.local_cluster(2) as cluster, Client(cluster) as c:
        yield c


@pytest.fixture(scope="module")
def cli(tmp_path_factory):
    summary = tmp_path_factory.mktemp("cli") / "summary.json"
    run = icgp_servo("--trials", str(TRIALS), "--tracker", "oracle", "--summary", str(summary))
    # The ground truth in the loop reaches the goal from every seeded start of this scenario.
    assert run.returncode == 0, run.stderr
    data = json.loads(summary.read_text())
    assert data["converged"] == TRIALS and data["success_rate"] == 1, data
    return run, summary


def test_the_sequential_run_is_every_trial_in_order(sequential):
    assert [r.trial for r in sequential.results] == list(range(TRIALS))
    assert sequential.trials_done == TRIALS and not sequential.interrupted
    assert [s.trials for s in sequential.summaries] == [TRIALS]
    assert all(r.tracker == "oracle (ground truth)" for r in sequential.results)
    assert all(r.succeeded for r in sequential.results)


@pytest.mark.parametrize("batch_size", [None, 3])
def test_a_cluster_gives_the_sequential_results(sequential, client, batch_size):
    distributed = icgp.batch.trials(SCENARIO, TRIALS, trackers=["oracle"], client=client, batch_size=batch_size,
                                    progress=False)
    assert distributed.results == sequential.results
    assert [r.trial for r in distributed.results] == list(range(TRIALS))
    assert without_timings(distributed.table) == without_timings(sequential.table)
    for a, b in zip(distributed.summaries, sequential.summaries):
        assert {k: v for k, v in a.as_dict().items() if k not in TIMING_KEYS} == \
               {k: v for k, v in b.as_dict().items() if k not in TIMING_KEYS}


def test_local_workers_keep_a_trial_on_one_core_without_the_profiler(client):
    import dask

    environments = client.run(lambda: os.environ.get("OMP_NUM_THREADS"))
    profilers = client.run(lambda: dask.config.get("distributed.worker.profile.enabled"))
    assert len(environments) == 2 and set(environments.values()) == {"1"}
    assert set(profilers.values()) == {False}


def test_the_table_json_and_trials_are_the_programs(sequential, cli, tmp_path):
    run, cli_summary = cli
    assert without_timings(sequential.table) == without_timings(run.stdout.split("wrote ")[0])
    summary = tmp_path / "python.json"
    sequential.write_summary_json(summary)
    assert summary_without_timings(summary) == summary_without_timings(cli_summary)
    # Each trial's final errors, as the program prints them.
    assert sorted(icgp.batch.trial_line(r, TRIALS) for r in sequential.results) == trial_lines(run.stderr)


def test_jobs_runs_the_trials_on_local_workers(cli, tmp_path):
    run, cli_summary = cli
    summary = tmp_path / "jobs.json"
    jobs = icgp_servo("--trials", str(TRIALS), "--tracker", "oracle", "--jobs", "2", "--summary", str(summary))
    assert jobs.returncode == run.returncode, jobs.stderr
    assert f"wrote {summary}" in jobs.stdout
    assert without_timings(jobs.stdout.split("wrote ")[0]) == without_timings(run.stdout.split("wrote ")[0])
    assert summary_without_timings(summary) == summary_without_timings(cli_summary)
    assert trial_lines(jobs.stderr) == trial_lines(run.stderr)


def sweep_without_timings(path):
    data = json.loads(Path(path).read_text())
    for row in data["rows"]:
        for key in TIMING_KEYS:
            row.pop(key)
    return data


def test_a_sweep_on_local_workers_gives_the_sweep_of_one_process(tmp_path):
    # The C++ program sweeps in its own process; with --jobs, Python's package on 2 Dask
    # workers, each reading the scenario again with the value set over the file's.
    args = ["--sweep", "camera.latency_ms=0,100", "--trials", "2", "--tracker", "oracle"]
    here = icgp_servo(*args, "--out", str(tmp_path / "here"))
    jobs = icgp_servo(*args, "--jobs", "2", "--out", str(tmp_path / "jobs"))
    assert here.returncode == 0, here.stderr
    assert jobs.returncode == 0, jobs.stderr
    swept = sweep_without_timings(tmp_path / "here" / "sweep.json")
    assert [row["value"] for row in swept["rows"]] == [0, 100]
    assert all(row["trials"] == 2 for row in swept["rows"])
    assert sweep_without_timings(tmp_path / "jobs" / "sweep.json") == swept
    assert (tmp_path / "jobs" / "sweep.png").stat().st_size > 0


def test_a_scenario_read_with_a_field_set_keeps_it_across_processes():
    scenario = servo.load_scenario(SCENARIO, {"camera.latency_ms": 50})
    assert scenario.overrides == {"camera.latency_ms": 50.0}
    assert pickle.loads(pickle.dumps(scenario)).overrides == {"camera.latency_ms": 50.0}
    assert icgp.batch.load(scenario, seed=9).overrides == {"camera.latency_ms": 50.0}
    with pytest.raises(icgp.Error, match="control.law: holds 'pbvs', not a number"):
        servo.load_scenario(SCENARIO, {"control.law": 1})


def test_jobs_exits_2_naming_the_tracker_whose_runs_did_not_succeed(tmp_path):
    scenario = SOURCE / "tests" / "servo" / "data" / "too_short.yaml"
    run = subprocess.run([ICGP, "servo", str(scenario), "--trials", "2", "--jobs", "2", "--out", str(tmp_path)],
                         capture_output=True, text=True, timeout=300)
    assert run.returncode == 2, run.stderr
    assert run.stderr.endswith("icgp: servo: runs that did not succeed: oracle (ground truth) 2 of 2\n")
    assert f"wrote {tmp_path / 'summary.json'}" in run.stdout


def test_an_unreachable_scheduler_is_a_clear_error():
    run = icgp_servo("--trials", "2", "--tracker", "oracle", "--scheduler", "tcp://127.0.0.1:9", timeout=120)
    assert run.returncode == 1
    assert "icgp: error: --scheduler tcp://127.0.0.1:9: cannot connect to a Dask scheduler there" in run.stderr


@pytest.mark.parametrize("args, message", [
    (["--trials", "1", "--jobs", "2"], "--jobs runs batch trials: give --trials N with N > 1, --compare or --sweep"),
    (["--trials", "4", "--jobs", "2", "--video", "v.avi"],
     "--jobs runs trials on workers; --video and --display show a single run"),
    (["--trials", "4", "--jobs", "2", "--scheduler", "tcp://127.0.0.1:9"], "--scheduler excludes --jobs"),
    (["--trials", "4", "--jobs", "0"], "--jobs"),
])
def test_worker_options_are_refused_where_they_do_not_apply(args, message):
    run = icgp_servo(*args, timeout=60)
    assert run.returncode == 1
    assert message in run.stderr


def test_a_trial_result_survives_pickling(sequential):
    result = sequential.results[3]
    copy = pickle.loads(pickle.dumps(result))
    assert copy == result
    assert copy.as_dict() == result.as_dict()  # timings too
    assert copy.trial == 3 and copy.seed == sequential.scenario.seed + 3


def test_an_icgp_trial_is_the_same_run_every_time(sequential):
    scenario = sequential.scenario
    first = servo.run_trial(scenario, "icgp", 1)
    again = pickle.loads(pickle.dumps(servo.run_trial(scenario, "icgp", 1)))
    assert first == again
    assert first.tracker.startswith("icgp") and first.steps > 0
    assert first != sequential.results[1]  # another tracker


def test_bad_arguments_name_themselves(sequential):
    with pytest.raises(ValueError, match="tracker: expected 'icgp', 'visp', 'oracle', 'image_oracle' or None"):
        servo.run_trial(sequential.scenario, "kalman", 0)
    with pytest.raises(ValueError, match="trial: expected an index >= 0, got -1"):
        servo.run_trial(sequential.scenario, "oracle", -1)
    with pytest.raises(ValueError, match="results: no trials to summarise"):
        servo.summarise([], sequential.scenario)
    with pytest.raises(ValueError, match="results: trial 0 of oracle .ground truth. twice"):
        servo.summarise(sequential.results[:1] * 2, sequential.scenario)
    with pytest.raises(ValueError, match="n: expected an integer >= 1, got 0"):
        icgp.batch.trials(SCENARIO, 0)
    with pytest.raises(ValueError, match="trackers: expected one of icgp, visp, oracle, image_oracle, got 'kalman'"):
        icgp.batch.trials(SCENARIO, 2, trackers=["kalman"])
    with pytest.raises(icgp.Error):
        icgp.batch.trials(SOURCE / "tests" / "servo" / "data" / "malformed.yaml", 2)
