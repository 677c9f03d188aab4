# SPDX-License-Identifier: GPL-2.0-or-later
"""Batch trials in this process, then on a local Dask cluster, back to back: wall times, their
ratio, the time of a trial, and what 10 000 trials on 50 workers would take.

    PYTHONPATH=build/python python3 examples/python/bench_trials.py \\
        --trials 200 --scenario scenarios/textured_pbvs.yaml --workers 2

The projection assumes workers like these (one core each): a trial takes there what it took
on this cluster's workers, everything included (setup, task hand-off, gathering), spread
over the workers, plus the last batch that one worker still runs when the others are done,
plus the task round trips (measured here; a remote cluster adds its network's).
"""
import argparse
import math
import os
import statistics
import sys
import time

import icgp.batch

PROJECTED_TRIALS = 10000
PROJECTED_WORKERS = 50


def nothing(i):
    return i


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--trials", type=int, default=200)
    parser.add_argument("--scenario", default="scenarios/textured_pbvs.yaml")
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--tracker", choices=icgp.batch.TRACKERS, help="default: the scenario's")
    parser.add_argument("--batch-size", type=int, help="trials per task (default: icgp.batch's)")
    parser.add_argument("--worker-env", action="append", default=[], metavar="NAME=VALUE",
                        help="an environment variable of the workers, over icgp.batch.WORKER_ENVIRONMENT")
    options = parser.parse_args()
    from dask.distributed import Client

    trackers = [options.tracker] if options.tracker else None
    scenario = icgp.batch.load(options.scenario)
    worker_env = dict(icgp.batch.WORKER_ENVIRONMENT, **dict(v.split("=", 1) for v in options.worker_env))
    print(f"scenario {scenario.name}, {options.trials} trials, load average {os.getloadavg()[0]:.1f} on "
          f"{os.cpu_count()} cores; this process: OMP_NUM_THREADS={os.environ.get('OMP_NUM_THREADS', '(unset)')}; "
          f"workers: {worker_env}")

    # A first trial, not counted: the models are in the cache for both runs.
    icgp.batch.trials(scenario, 1, trackers=trackers, progress=False)

    begin = time.monotonic()
    sequential = icgp.batch.trials(scenario, options.trials, trackers=trackers, progress=False)
    sequential_s = time.monotonic() - begin
    loops = [r.steps / r.steps_per_s for r in sequential.results]
    setup_s = sequential_s / len(loops) - statistics.mean(loops)

    begin = time.monotonic()
    with icgp.batch.local_cluster(options.workers, env=worker_env) as cluster, Client(cluster) as client:
        client.wait_for_workers(options.workers)
        start_s = time.monotonic() - begin
        latencies = []
        for i in range(30):
            t = time.monotonic()
            client.submit(nothing, i, pure=False).result()
            latencies.append(time.monotonic() - t)
        latency_s = statistics.median(latencies)
        begin = time.monotonic()
        distributed = icgp.batch.trials(scenario, options.trials, trackers=trackers, client=client,
                                        batch_size=options.batch_size, progress=False)
        distributed_s = time.monotonic() - begin
        batch_size = options.batch_size or math.ceil(options.trials / (icgp.batch.BATCHES_PER_WORKER * options.workers))
    worker_loops = [r.steps / r.steps_per_s for r in distributed.results]

    runs = len(sequential.results)
    print(sequential.table, end="")
    print(f"identical results: {distributed.results == sequential.results}")
    print(f"sequential       {sequential_s:8.1f} s  ({sequential_s / runs:.2f} s a trial; loop median "
          f"{statistics.median(loops):.2f} s, setup {setup_s:.2f} s a trial)")
    print(f"cluster start    {start_s:8.1f} s  ({options.workers} workers; task round trip {1e3 * latency_s:.1f} ms)")
    print(f"distributed      {distributed_s:8.1f} s  (batches of {batch_size}; on a worker {statistics.median(worker_loops):.2f} s "
          f"loop median, {distributed_s * options.workers / runs:.2f} s a trial all included)")
    print(f"ratio            {distributed_s / sequential_s:8.2f}   (distributed / sequential; speed-up "
          f"{sequential_s / distributed_s:.2f} on {options.workers} workers)")

    per_trial = distributed_s * options.workers / options.trials  # a trial index, every tracker on it
    batch = math.ceil(PROJECTED_TRIALS / (icgp.batch.BATCHES_PER_WORKER * PROJECTED_WORKERS))
    spread = PROJECTED_TRIALS * per_trial / PROJECTED_WORKERS
    tail = batch * per_trial
    handoff = math.ceil(PROJECTED_TRIALS / batch) / PROJECTED_WORKERS * latency_s
    print(f"projected        {spread + tail + handoff:8.0f} s  for {PROJECTED_TRIALS} trials on {PROJECTED_WORKERS} "
          f"workers: {PROJECTED_TRIALS} x {per_trial:.2f} s / {PROJECTED_WORKERS} = {spread:.0f} s, + the last batch "
          f"of {batch}: {tail:.0f} s, + task round trips {handoff:.1f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
