# SPDX-License-Identifier: GPL-2.0-or-later
"""What every Python test reads: the source tree, the icgp program and the coarse models."""
import os
import pathlib
import subprocess

import pytest

SOURCE_DIR = pathlib.Path(os.environ.get("ICGP_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
TEABOX = SOURCE_DIR / "tests" / "data" / "teabox-blender"
# Coarse viewpoint models, so that the tests generate them in about a second.
COARSE = SOURCE_DIR / "tests" / "configs" / "coarse_models.yaml"


@pytest.fixture(scope="session")
def icgp_program():
    """The icgp program of the build under test (CTest sets ICGP)."""
    program = os.environ.get("ICGP")
    if not program:
        pytest.skip("ICGP (the icgp program) is not set: run through CTest")
    return program


def run_icgp(program, *args):
    """Runs the icgp program; returns (exit code, stdout, stderr)."""
    done = subprocess.run([program, *map(str, args)], capture_output=True, text=True, timeout=600)
    return done.returncode, done.stdout, done.stderr


def cli_error(stderr):
    """The message of the program's "icgp: error: ..." line."""
    for line in stderr.splitlines():
        if line.startswith("icgp: error: "):
            return line[len("icgp: error: "):]
    raise AssertionError("no 'icgp: error:' line in:\n" + stderr)
