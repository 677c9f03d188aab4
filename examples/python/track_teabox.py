#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-2.0-or-later
"""Finds and tracks the teabox of ViSP's teabox-blender sequence from Python, and plots the error.

    python3 examples/python/track_teabox.py [--sequence DIR] [--plot PNG] [--bench ROUNDS]

No pose is given: the tracker detects the box in the frames (Tracker.detect) and tracks on
from there. With icgp's defaults, on the same frames, with the same metrics
(icgp.Evaluation), the summary is the one `icgp track --sequence
tests/data/teabox-blender --init detect` prints. teabox.cao has no texture: the box turned
180 degrees about its long axis has the same outline and surface, detection finds one of
the two (the other is in the result's `equivalents`), and against the ground truth's pose
the tracked one may be that turn away while its ADD-S stays small; the plot shows both.
--bench times the binding against the C++ program: ROUNDS alternating runs of `icgp
track` and of this loop, each over every frame, single-threaded as the program tracks.
"""
import argparse
import csv
import os
import pathlib
import statistics
import subprocess
import tempfile
import time

import matplotlib
import numpy as np

matplotlib.use("Agg")  # headless: the plot goes to a file
import matplotlib.pyplot as plt  # noqa: E402

import icgp  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[2]


def track(sequence, verbose=False):
    """Detects the box and tracks every frame with the defaults, reading each frame just
    before it is used (as `icgp track --init detect` does): until the box is found, each
    frame is searched and counted lost. The ground truth only scores the result. Returns
    the evaluation, each tracked frame's errors, and each track() call's wall-clock ms and
    C++ tracking ms."""
    obj = sequence.objects[0]
    tracker = icgp.Tracker(obj["model"], body=obj["name"])
    evaluation = icgp.Evaluation(obj["model"])
    found = None
    errors, wall_ms, cpp_ms = [], [], []
    for i in range(len(sequence)):
        frame = sequence[i]
        color, depth = frame.color, frame.depth
        cameras = (sequence.K_color, sequence.K_depth, sequence.depth_T_color)
        if found is None:
            detection = tracker.detect(color, depth, *cameras)
            if not detection["found"]:
                if verbose:
                    print(f"frame {frame.index}: not found ({detection['why_not']})")
                evaluation.add(frame.index, np.eye(4), frame.truth(), False, 0.0, 0.0)  # lost, as icgp track counts it
                continue
            found = detection
            if verbose:
                print(f"found      on frame {frame.index}, quality {found['quality']:.3f}, "
                      f"{len(found['equivalents'])} equivalent pose(s) of the symmetric model")
        begin = time.perf_counter()
        result = tracker.track(color, depth, *cameras)
        wall_ms.append(1000.0 * (time.perf_counter() - begin))
        cpp_ms.append(result.ms)
        errors.append(evaluation.add(frame.index, result.pose, frame.truth(), result.tracked, result.ms, result.quality))
    return evaluation, errors, wall_ms, cpp_ms


def print_summary(s, wall_ms):
    print(f"frames     {s['frames']}, tracked {s['tracked']}")
    print(f"translation mean {s['mean_t_mm']:.2f} mm, max {s['max_t_mm']:.2f} mm")
    print(f"rotation   mean {s['mean_r_deg']:.2f} deg, max {s['max_r_deg']:.2f} deg")
    print(f"ADD AUC    {s['add_auc']:.2f} %, ADD-S AUC {s['adds_auc']:.2f} % (threshold 10 cm)")
    median = statistics.median(wall_ms)
    print(f"time       median {median:.2f} ms ({1000.0 / median:.0f} Hz) per track() call from Python")


def plot(errors, path):
    t_mm = [e["t_mm"] for e in errors]
    adds_mm = [e["adds_mm"] for e in errors]
    figure, (top, bottom) = plt.subplots(2, 1, sharex=True, figsize=(8, 5))
    top.plot(t_mm, color="tab:blue")
    top.set_ylabel("translation error (mm)")
    bottom.plot(adds_mm, color="tab:green")
    bottom.set_ylabel("ADD-S (mm)")
    bottom.set_xlabel("tracked frame")
    top.set_title("icgp on teabox-blender (defaults), found and tracked from Python")
    figure.tight_layout()
    figure.savefig(path, dpi=100)


def program_median_ms(program, sequence_dir):
    """The median Tracker::track time of one `icgp track` run, from its per-frame CSV."""
    with tempfile.TemporaryDirectory() as folder:
        table = pathlib.Path(folder) / "track.csv"
        subprocess.run([program, "track", "--sequence", str(sequence_dir), "--init", "detect", "--csv", str(table),
                        "--quiet"],
                       check=True, capture_output=True)
        with open(table) as f:
            return statistics.median(float(row["ms"]) for row in csv.DictReader(f))


def bench(rounds, sequence, program):
    """Median per-frame ms of `icgp track` (its Tracker::track) and of this loop's track()
    calls, in alternating rounds; the binding's own share is the call's time beyond the C++
    tracking inside it."""
    print(f"\n{'round':>5} {'icgp track ms':>14} {'Python track() ms':>18} {'overhead':>9} {'binding alone':>14}")
    ratios = []
    for k in range(rounds):
        program_ms = program_median_ms(program, sequence.path)
        _, _, wall_ms, cpp_ms = track(sequence)
        python_ms = statistics.median(wall_ms)
        binding_ms = statistics.median(w - c for w, c in zip(wall_ms, cpp_ms))
        ratios.append(python_ms / program_ms)
        print(f"{k + 1:>5} {program_ms:>14.3f} {python_ms:>18.3f} {100.0 * (python_ms / program_ms - 1.0):>8.1f}% "
              f"{1000.0 * binding_ms:>11.1f} us", flush=True)
    print(f"median overhead over {rounds} rounds: {100.0 * (statistics.median(ratios) - 1.0):.1f}% "
          "(median per-frame ms of Python's track() calls against the program's)")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--sequence", default=ROOT / "tests" / "data" / "teabox-blender", type=pathlib.Path)
    parser.add_argument("--plot", default=pathlib.Path("out", "python", "track_teabox.png"), type=pathlib.Path,
                        help="the error plot (PNG; default: out/python/track_teabox.png)")
    parser.add_argument("--bench", type=int, default=0, metavar="ROUNDS",
                        help="time the binding against `icgp track` over this many alternating rounds")
    parser.add_argument("--icgp", default=os.environ.get("ICGP", ROOT / "build" / "src" / "icgp"),
                        help="the icgp program, for --bench")
    args = parser.parse_args()

    icgp.set_num_threads(1)  # as `icgp track` times: one thread
    sequence = icgp.Sequence(args.sequence)
    print(f"sequence   {sequence.path} ({sequence.layout}, {len(sequence)} frames)")
    evaluation, errors, wall_ms, _ = track(sequence, verbose=True)
    print_summary(evaluation.summary(), wall_ms)
    args.plot.parent.mkdir(parents=True, exist_ok=True)
    plot(errors, args.plot)
    print(f"wrote      {args.plot}")
    if args.bench:
        bench(args.bench, sequence, str(args.icgp))


if __name__ == "__main__":
    main()
