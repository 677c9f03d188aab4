# SPDX-License-Identifier: GPL-2.0-or-later
"""Batch trials of a servo scenario, in this process or on a Dask cluster.

    import icgp.batch
    from dask.distributed import Client, LocalCluster
    with icgp.batch.local_cluster(4) as cluster, Client(cluster) as client:
        batch = icgp.batch.trials("scenarios/textured_pbvs.yaml", 200, trackers=["icgp", "visp"], client=client)
    print(batch.table)
    batch.write_summary_json("summary.json")

Trial i of a batch is the same run wherever it runs (its start and noise follow from the
scenario's seed and i), so the results do not depend on the batching, the order or the
number of workers: they equal `icgp servo SCENARIO --trials N` trial for trial.

On a cluster, every worker needs the icgp package and the scenario's files (the scenario
file, its models and tracker configuration) at the same absolute paths, and its own model
cache or a shared one (model files are written atomically, and a lock lets one process
generate a model while the others wait for it).
"""
import math
import os
import signal
import sys
import threading
import time
from dataclasses import dataclass
from pathlib import Path

from . import _icgp
from ._icgp.servo import Scenario

TRACKERS = ("icgp", "visp", "oracle", "image_oracle")

# Every trial on one core: two trials on two cores must not fight over both. OpenMP (ViSP and
# the tracker use it) reads this when icgp's extension loads, so it is set when a worker
# process starts: local_cluster does, and so does Dask's nanny by default
# (distributed.nanny.pre-spawn-environ) for workers started with dask-worker. Measured on two
# cores other jobs also used: 8 small_pbvs oracle trials in one process took 11.5-19.5 s with
# OpenMP's default two threads, 4.0-4.5 s with one. LP_NUM_THREADS (llvmpipe's render
# threads) made no measurable difference (0 or 2: 38.9 and 39.1 s for 24 textured_pbvs trials
# on two workers).
WORKER_ENVIRONMENT = {"OMP_NUM_THREADS": "1"}

# Batches per worker by default: a worker that draws slow trials, or the last batch, holds up
# the end by at most an eighth of a worker's share; a task costs milliseconds.
BATCHES_PER_WORKER = 8

# Dask's statistical profiler samples each worker's task thread every 10 ms. A trial spends its
# time in C++ with the GIL released, where the profile sees one Python frame and learns
# nothing, while the sampling costs the trial: on two cores, 24 textured_pbvs trials on two
# workers took 9.69 s a loop with it, 8.50 s without (back to back). Workers of local_cluster run
# without it; workers started with dask-worker get the same from
# DASK_DISTRIBUTED__WORKER__PROFILE__ENABLED=False.
WORKER_CONFIG = {"distributed.worker.profile.enabled": False}


@dataclass
class Trials:
    """What trials() returns: each run, the per-tracker summaries and their table."""

    scenario: Scenario
    results: list  # TrialResults, ordered by (tracker as given, trial)
    summaries: list  # a TrialsSummary per tracker
    table: str  # the text `icgp servo --trials` prints
    trials_requested: int
    trials_done: int  # trials every tracker finished (all of them unless interrupted)
    interrupted: bool = False  # Ctrl-C stopped the batch; the summaries hold the trials done
    elapsed: float = 0.0  # wall-clock seconds

    def write_summary_json(self, path):
        """Writes the summary JSON of `icgp servo --summary`."""
        _icgp.servo.write_summary_json(self.summaries, os.fspath(path))


def local_cluster(workers, **options):
    """A dask LocalCluster for trials: `workers` processes of one thread each, in the environment
    that keeps each trial on one core (WORKER_ENVIRONMENT), without the statistical profiler
    (WORKER_CONFIG). `options` go to LocalCluster."""
    import dask
    from dask.distributed import LocalCluster

    options.setdefault("dashboard_address", None)
    env = dict(WORKER_ENVIRONMENT, **options.pop("env", {}))
    # Ctrl-C reaches the workers too (one process group): they start with SIGINT ignored, and
    # the client stops the batch (trials() returns the trials done) and closes them.
    in_main_thread = threading.current_thread() is threading.main_thread()
    previous = signal.signal(signal.SIGINT, signal.SIG_IGN) if in_main_thread else None
    try:
        # The nannies hand the configuration of their creation to the workers they start.
        with dask.config.set(WORKER_CONFIG):
            return LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, env=env, **options)
    finally:
        if in_main_thread:
            signal.signal(signal.SIGINT, previous)


def trials(scenario, n, seed=None, trackers=None, client=None, batch_size=None, progress=True):
    """Runs trials 0 .. n-1 of `scenario` (a Scenario or its YAML file) with each of `trackers`
    ('icgp', 'visp', 'oracle', 'image_oracle'; default: the scenario's), as `icgp servo --trials n` does.
    `seed` replaces the scenario's seed (the random starts and the noise follow from it).

    Without `client`, in this process: every tracker runs trial i before any runs trial i + 1.
    With a dask.distributed Client: the trials are split into batches of `batch_size` indices
    (default: BATCHES_PER_WORKER batches per worker), one task per batch running every tracker on
    them. `progress` prints a line per finished run on stderr, with the time elapsed and
    left, as the icgp program does. Ctrl-C stops the batch and returns the trials done,
    marked interrupted. Returns a Trials."""
    scenario = load(scenario, seed)
    n = _count(n, "n")
    trackers = _trackers(trackers)
    begin = time.monotonic()
    report = _Progress(n, len(trackers), begin) if progress else None
    if client is None:
        by_trial, interrupted = _run_here(scenario, n, trackers, report)
    else:
        by_trial, interrupted = _run_on(client, scenario, n, trackers, batch_size, report)
    if not by_trial:
        raise KeyboardInterrupt("interrupted before the first trial ended")
    done = sorted(by_trial)
    results = [by_trial[i][k] for k in range(len(trackers)) for i in done]
    summaries = _icgp.servo.summarise(results, scenario, interrupted)
    return Trials(scenario, results, summaries, _icgp.servo.table(summaries), n, len(done), interrupted,
                  time.monotonic() - begin)


def run_batch(scenario, trackers, indices):
    """The task of one batch on a worker: every tracker on each trial of `indices`, a list
    [trial][tracker] of TrialResults."""
    return [[_icgp.servo.run_trial(scenario, tracker, i) for tracker in trackers] for i in indices]


def load(scenario, seed=None, overrides=None):
    """`scenario` (a Scenario or its YAML file) with `seed` (None: its own) and `overrides`
    ({key path: number} set over the file's fields, as `icgp servo --sweep` sets them; None:
    the scenario's own), as trials() runs it."""
    if isinstance(scenario, (str, os.PathLike)):
        # Absolute: workers read it again, maybe from another working directory.
        scenario = _icgp.servo.load_scenario(Path(scenario).absolute(), overrides or {})
    elif not isinstance(scenario, Scenario):
        raise TypeError(f"scenario: expected an icgp.servo.Scenario or a YAML file path, got {type(scenario).__name__}")
    elif overrides is not None:
        scenario = _icgp.servo.load_scenario(Path(scenario.file).absolute(), {**scenario.overrides, **overrides})
    if seed is not None:
        seed = _count(seed, "seed", minimum=0)
        if seed > 0xFFFFFFFF:
            raise ValueError(f"seed: expected an integer in [0, 4294967295], got {seed}")
        # A copy: the caller's stays as it was.
        scenario = _icgp.servo.load_scenario(Path(scenario.file).absolute(), scenario.overrides)
        scenario.seed = seed
    return scenario


def sweep(scenario, field, values, n, seed=None, trackers=None, client=None, json=None, plot_dir=None,
          progress=True):
    """Runs trials() of `scenario` (its YAML file) at each of `values` of the numeric `field`
    (a key path, 'camera.latency_ms'), on the same seeded starts at every value, as `icgp
    servo --sweep` does; every value is read before any runs, so a field or value the
    scenario refuses raises icgp.Error before anything runs. After every value, `json` (when
    given) is written, and at the end the plot in `plot_dir` (when given). A value whose trials
    raise is reported and the next one runs. Ctrl-C stops the sweep after what is done.
    Returns (the table, interrupted)."""
    values = [float(v) for v in values]
    scenarios = [load(scenario, seed, {field: v}) for v in values]
    done = []
    interrupted = False
    for index, (value, at_value) in enumerate(zip(values, scenarios)):
        if progress:
            print(f"{field} = {value:g} (value {index + 1} of {len(values)})", file=sys.stderr, flush=True)
        try:
            result = trials(at_value, n, trackers=trackers, client=client, progress=progress)
            done.append((value, at_value, result.results, "", result.interrupted))
            interrupted = result.interrupted
        except KeyboardInterrupt:
            interrupted = True
        except Exception as e:  # the trials of one value failed: say so, go on
            done.append((value, at_value, [], f"{type(e).__name__}: {e}", False))
            print(f"{field} {value:g}: {type(e).__name__}: {e}", file=sys.stderr, flush=True)
        if json:
            _icgp.servo.write_sweep(field, values, done, json, "")
        if interrupted:
            break
    table = _icgp.servo.write_sweep(field, values, done, json or os.devnull, plot_dir or "")
    return table, interrupted


def _count(value, name, minimum=1):
    if isinstance(value, bool) or not isinstance(value, int) or value < minimum:
        raise ValueError(f"{name}: expected an integer >= {minimum}, got {value!r}")
    return value


def _trackers(trackers):
    if trackers is None:
        return [None]  # the scenario's
    if isinstance(trackers, str):
        trackers = [trackers]
    trackers = list(trackers)
    if not trackers:
        raise ValueError(f"trackers: expected at least one of {', '.join(TRACKERS)}")
    for t in trackers:
        if t not in TRACKERS:
            raise ValueError(f"trackers: expected one of {', '.join(TRACKERS)}, got {t!r}")
    if len(set(trackers)) != len(trackers):
        raise ValueError(f"trackers: each tracker once, got {trackers}")
    return trackers


def _run_here(scenario, n, trackers, report):
    by_trial = {}
    try:
        for i in range(n):
            runs = []
            for tracker in trackers:
                runs.append(_icgp.servo.run_trial(scenario, tracker, i))
                if report:
                    report.run_done(runs[-1])
            by_trial[i] = runs
    except KeyboardInterrupt:
        return by_trial, True
    return by_trial, False


def _run_on(client, scenario, n, trackers, batch_size, report):
    from dask.distributed import as_completed

    if batch_size is None:
        workers = max(1, sum(client.nthreads().values()))
        batch_size = max(1, math.ceil(n / (BATCHES_PER_WORKER * workers)))
    batch_size = _count(batch_size, "batch_size")
    batches = [list(range(start, min(n, start + batch_size))) for start in range(0, n, batch_size)]
    futures = client.map(run_batch, [scenario] * len(batches), [trackers] * len(batches), batches, pure=False)
    by_trial = {}
    try:
        for future in as_completed(futures):
            runs_of_batch = future.result()  # raises the task's exception (icgp.Error, ...)
            for indices_runs in runs_of_batch:
                for run in indices_runs:
                    if report:
                        report.run_done(run)
                by_trial[indices_runs[0].trial] = indices_runs
    except KeyboardInterrupt:
        client.cancel(futures)
        return by_trial, True
    except BaseException:
        client.cancel(futures)
        raise
    return by_trial, False


class _Progress:
    """The icgp program's line per finished run: "trial 3/8 oracle (ground truth): success, ...
    [3/8, elapsed 2 s, ETA 5 s]"."""

    def __init__(self, trials, trackers, begin):
        self.trials = trials
        self.total = trials * trackers
        self.done = 0
        self.begin = begin

    def run_done(self, run):
        self.done += 1
        elapsed = time.monotonic() - self.begin
        left = elapsed / self.done * (self.total - self.done)
        print(f"{trial_line(run, self.trials)} [{self.done}/{self.total}, elapsed {elapsed:.0f} s, ETA {left:.0f} s]",
              file=sys.stderr, flush=True)


def trial_line(run, trials):
    """A finished run as the icgp program prints it (without the progress part)."""
    outcome = "success" if run.succeeded else "settled off target" if run.converged else "not converged"
    stops = f", {run.safety_stops} safety stop(s)" if run.safety_stops > 0 else ""
    lost = f", lost at the end: {run.lost_reason}" if run.lost_reason else ""
    return (f"trial {run.trial + 1}/{trials} {run.tracker}: {outcome}, final {1e3 * run.final_t:.3f} mm "
            f"{run.final_r / (math.pi / 180):.3f} deg, tracker max {1e3 * run.max_track_t:.2f} mm{stops}{lost}")
