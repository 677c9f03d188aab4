# SPDX-License-Identifier: GPL-2.0-or-later
"""The Python examples run as their documentation says, with the program's numbers."""
import os
import subprocess
import sys

from conftest import SOURCE_DIR, TEABOX, run_icgp

SUMMARY_LINES = ("frames ", "translation ", "rotation ", "ADD AUC ")


def summary(output):
    return [line for line in output.splitlines() if line.startswith(SUMMARY_LINES)]


def test_track_teabox_finds_the_box_and_prints_the_summary_of_icgp_track(icgp_program, tmp_path):
    example = subprocess.run([sys.executable, SOURCE_DIR / "examples" / "python" / "track_teabox.py",
                              "--plot", tmp_path / "error.png"],
                             capture_output=True, text=True, timeout=600, env=os.environ, cwd=tmp_path)
    assert example.returncode == 0, example.stderr
    assert "found      on frame 0" in example.stdout
    code, out, err = run_icgp(icgp_program, "track", "--sequence", TEABOX, "--init", "detect", "--quiet")
    assert code == 0, err
    assert len(summary(out)) == 4
    assert summary(example.stdout) == summary(out)
    assert (tmp_path / "error.png").stat().st_size > 10000
