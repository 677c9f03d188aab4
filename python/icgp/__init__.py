# SPDX-License-Identifier: GPL-2.0-or-later
"""icgp: the ICG+ multi-modality 6-DoF object tracker, and a closed-loop servo simulator.

    import icgp
    seq = icgp.Sequence("tests/data/teabox-blender")
    tracker = icgp.Tracker(seq.objects[0]["model"])
    tracker.set_pose(seq[0].truth())
    for i in range(len(seq)):
        frame = seq[i]
        result = tracker.track(frame.color, frame.depth, seq.K_color, seq.K_depth, seq.depth_T_color)

Tracker      the tracker on NumPy images (help(icgp.Tracker))
Sequence     RGB-D sequences as `icgp track` reads them; make_sequence renders one
Evaluation   the errors and AUCs `icgp track` reports, for poses tracked here
evaluate_tracker  a sequence tracked and evaluated as `icgp bench` does, in one call
servo        scenarios, closed-loop runs and batch trials (local or on a Dask cluster)
Error        every error of icgp's C++ core, with the message the icgp program prints
"""
import sys

try:
    import numpy  # noqa: F401  (every image and pose is a NumPy array)
except ImportError as error:
    raise ImportError(f"icgp needs NumPy, which {sys.executable} does not have: run icgp with the Python it "
                      "was built for (by default Debian's /usr/bin/python3, with python3-numpy)") from error

try:
    from . import _icgp
except ImportError as error:
    raise ImportError(f"icgp's extension module cannot be loaded by {sys.executable} (Python "
                      f"{sys.version.split()[0]}): {error}. It is built for one interpreter (CMake's "
                      "Python3_EXECUTABLE, by default Debian's /usr/bin/python3)") from error

from ._icgp import (  # noqa: E402,F401  (the package's public names)
    BodyResult,
    Error,
    Evaluation,
    Frame,
    Sequence,
    Tracker,
    TrackResult,
    __version__,
    evaluate_tracker,
    make_sequence,
    models_dir,
    set_num_threads,
)
