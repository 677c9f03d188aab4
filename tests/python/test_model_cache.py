# SPDX-License-Identifier: GPL-2.0-or-later
"""The model cache shared by processes: two that need the same models at once on an empty
cache generate each model once (one waits for the other's file), and the file is the one a
process alone writes. Batch trials on several workers start exactly like this."""
import os
import subprocess
from pathlib import Path

ICGP = os.environ["ICGP"]
SOURCE = Path(os.environ["ICGP_SOURCE_DIR"])
MESH = SOURCE / "models" / "textured_box" / "textured_box.obj"
# Coarse (about a second each on llvmpipe, as tests/configs/coarse_models.yaml), yet long
# enough that two processes started together overlap.
COARSE = ["--views-divides", "3", "--image-size", "800"]


def start_model(cache_dir):
    return subprocess.Popen([ICGP, "model", str(MESH), *COARSE, "--cache-dir", str(cache_dir)],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)


def finish(process):
    out, err = process.communicate(timeout=300)
    assert process.returncode == 0, err
    return err


def model_files(cache_dir):
    return sorted(p.name for p in Path(cache_dir).glob("*.icgpmodel"))


def test_processes_started_together_generate_each_model_once(tmp_path):
    shared = tmp_path / "shared"
    first, second = start_model(shared), start_model(shared)
    errors = [finish(first), finish(second)]
    files = model_files(shared)
    assert len(files) == 2  # region and depth, no temporary or lock file left over
    assert not list(shared.glob("*.tmp.*")) and not list(shared.glob("*.lock"))
    for name in files:
        assert sum(f"{name}: not found; generating" in e for e in errors) == 1, errors
    # One process generated both (they are made together); the other waited for its files, or
    # found them written when it looked.
    waiter = [e for e in errors if "not found; generating" not in e]
    assert len(waiter) == 1, errors
    assert "another process is generating it; waiting for it" in waiter[0] or waiter[0] == "", errors

    alone = tmp_path / "alone"
    finish(start_model(alone))
    assert model_files(alone) == files
    for name in files:
        assert (shared / name).read_bytes() == (alone / name).read_bytes()

    # The shared files load: nothing is generated again.
    assert "generating" not in finish(start_model(shared))


def test_a_cache_that_cannot_be_locked_or_written_still_gives_the_models(tmp_path):
    not_a_folder = tmp_path / "file"
    not_a_folder.write_text("")
    process = subprocess.run([ICGP, "model", str(MESH), *COARSE, "--cache-dir", str(not_a_folder / "cache")],
                             capture_output=True, text=True, timeout=300)
    assert process.returncode == 0, process.stderr
    assert "not found; generating" in process.stderr
    assert "continuing without the cache" in process.stderr
