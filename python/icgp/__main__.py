# SPDX-License-Identifier: GPL-2.0-or-later
"""python -m icgp servo SCENARIO --trials N [--seed S] [--tracker T | --compare]
                       [--scheduler tcp://HOST:PORT | --jobs J] [--summary J] [--out DIR]

Batch trials of a servo scenario as `icgp servo --trials` runs them, here or on Dask workers:
the same lines per finished run, table and summary JSON, and the same exit status (0 every
run succeeded, 1 an error, 2 some runs did not succeed, 130 interrupted). The icgp program
runs this for its --scheduler and --jobs options.
"""
import argparse
import os
import sys

from . import Error
from . import _icgp, batch

EXIT_ERROR = 1
EXIT_NOT_ACHIEVED = 2
EXIT_INTERRUPTED = 130
MAX_TRIALS = 10000  # the icgp program's limit
SCHEDULER_TIMEOUT_S = 10  # seconds to connect to --scheduler; one that is up answers in well under a second


class CommandOutcome(Exception):
    """The work is done and written; the program ends with `status` and this line."""

    def __init__(self, status, reason):
        super().__init__(reason)
        self.status = status


class UsageError(Exception):
    """A bad argument: exit status 1, as the icgp program's command-line errors."""


class Parser(argparse.ArgumentParser):
    def error(self, message):
        raise UsageError(message)


def int_in(low, high):
    def parse(text):
        try:
            value = int(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"expected an integer in [{low}, {high}], got '{text}'") from None
        if not low <= value <= high:
            raise argparse.ArgumentTypeError(f"expected an integer in [{low}, {high}], got {value}")
        return value

    return parse


def parser():
    main = Parser(prog="python -m icgp", description="icgp's Python package as a program")
    commands = main.add_subparsers(dest="command", required=True, parser_class=Parser)
    servo = commands.add_parser("servo", help="batch trials of a servo scenario, here or on Dask workers")
    servo.add_argument("scenario", help="scenario file (YAML, see scenarios/)")
    servo.add_argument("--tracker", choices=batch.TRACKERS, help="tracker instead of the scenario's")
    servo.add_argument("--trials", type=int_in(1, MAX_TRIALS), default=1, help="runs from random starts")
    servo.add_argument("--seed", type=int_in(0, 0xFFFFFFFF), default=0, help="seed (default, 0: the scenario's)")
    servo.add_argument("--compare", action="store_true", help="oracle, visp and icgp on identical trials")
    servo.add_argument("--summary", help="summary JSON (default: OUT/summary.json)")
    servo.add_argument("--out", help="folder of the default summary (default: out/servo/<scenario name>)")
    servo.add_argument("--sweep", metavar="FIELD=V1,V2,...", help="the trials at each value of a numeric field")
    workers = servo.add_mutually_exclusive_group()
    workers.add_argument("--scheduler", help="run on the Dask cluster of this scheduler (tcp://HOST:PORT)")
    workers.add_argument("--jobs", type=int_in(1, 1024), help="run on this many local worker processes")
    return main


def connect(options):
    """The Dask client of --scheduler or --jobs, with the local cluster it started (or None)."""
    try:
        from dask.distributed import Client
    except ImportError as e:
        raise UsageError(f"--scheduler and --jobs need Dask's distributed package (Debian: python3-distributed): {e}")
    if options.jobs:
        cluster = batch.local_cluster(options.jobs)
        return Client(cluster), cluster
    try:
        return Client(options.scheduler, timeout=SCHEDULER_TIMEOUT_S), None
    except (OSError, ValueError, TypeError) as e:
        raise UsageError(f"--scheduler {options.scheduler}: cannot connect to a Dask scheduler there: {e}") from None


def servo(options):
    if options.compare and options.tracker:
        raise UsageError("--tracker and --compare: give one (--compare runs oracle, visp and icgp)")
    if options.trials == 1 and not options.compare and not options.sweep and (options.scheduler or options.jobs):
        raise UsageError("--scheduler and --jobs run batch trials: give --trials N with N > 1, --compare or --sweep")
    scenario = batch.load(options.scenario, options.seed or None)
    print(f"scenario {scenario.name}" + (f": {scenario.description}" if scenario.description else ""), file=sys.stderr)
    out = options.out or os.path.join("out", "servo", scenario.name)
    summary = options.summary or os.path.join(out, "summary.json")
    trackers = ["oracle", "visp", "icgp"] if options.compare else [options.tracker] if options.tracker else None

    sweep = _icgp.servo.parse_sweep(options.sweep) if options.sweep else None
    client = cluster = None
    if options.scheduler or options.jobs:
        client, cluster = connect(options)
    try:
        if sweep:
            field, values = sweep
            json = options.summary or os.path.join(out, "sweep.json")
            table, interrupted = batch.sweep(options.scenario, field, values, options.trials, options.seed or None,
                                             trackers, client, json, out)
            sys.stdout.write(table)
            print(f"wrote {json}, {os.path.join(out, 'sweep.png')}", flush=True)
            if interrupted:
                raise CommandOutcome(EXIT_INTERRUPTED, f"interrupted: the values swept are in {json}")
            return
        try:
            result = batch.trials(scenario, options.trials, trackers=trackers, client=client)
        except KeyboardInterrupt:
            raise CommandOutcome(EXIT_INTERRUPTED, "interrupted before the first trial ended: nothing written")
    finally:
        if client is not None:
            client.close()
        if cluster is not None:
            cluster.close()

    sys.stdout.write(result.table)
    result.write_summary_json(summary)
    print(f"wrote {summary}", flush=True)
    if result.interrupted:
        raise CommandOutcome(EXIT_INTERRUPTED, f"interrupted: {result.trials_done} of {options.trials} trials done, "
                                               f"in the table and {summary}")
    failed = ", ".join(f"{s.tracker} {s.trials - s.converged} of {s.trials}"
                       for s in result.summaries if s.converged < s.trials)
    if failed:
        raise CommandOutcome(EXIT_NOT_ACHIEVED, f"servo: runs that did not succeed: {failed}")


def main(argv=None):
    try:
        options = parser().parse_args(argv)
        servo(options)
    except CommandOutcome as e:
        print(f"icgp: {e}", file=sys.stderr)
        return e.status
    except (UsageError, Error, ValueError, OSError) as e:
        print(f"icgp: error: {e}", file=sys.stderr)
        return EXIT_ERROR
    except KeyboardInterrupt:
        print("icgp: interrupted", file=sys.stderr)
        return EXIT_INTERRUPTED
    except Exception as e:  # a worker's failure (dask's KilledWorker, ...): one line, as every error
        print(f"icgp: error: {type(e).__name__}: {e}", file=sys.stderr)
        return EXIT_ERROR
    return 0


if __name__ == "__main__":
    sys.exit(main())
