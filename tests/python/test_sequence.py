# SPDX-License-Identifier: GPL-2.0-or-later
"""icgp.Sequence and icgp.make_sequence against the files they read and write."""
import xml.etree.ElementTree as ElementTree

import numpy as np
import pytest

import icgp
from conftest import SOURCE_DIR, TEABOX, cli_error, run_icgp


def camera_matrix_of(xml_file):
    camera = ElementTree.parse(xml_file).getroot().find(".//camera")
    value = {key: float(camera.find(key).text) for key in ("px", "py", "u0", "v0")}
    return np.array([[value["px"], 0, value["u0"]], [0, value["py"], value["v0"]], [0, 0, 1]])


def test_teabox_reads_as_its_files_write_it():
    sequence = icgp.Sequence(TEABOX)
    assert (sequence.layout, len(sequence)) == ("visp-blender", 100)
    np.testing.assert_array_equal(sequence.K_color, camera_matrix_of(TEABOX / "teabox.xml"))
    np.testing.assert_array_equal(sequence.K_depth, camera_matrix_of(TEABOX / "teabox_depth.xml"))
    np.testing.assert_array_equal(sequence.depth_T_color, np.loadtxt(TEABOX / "depth_M_color.txt"))
    frame = sequence[4]
    assert frame.index == 4
    np.testing.assert_array_equal(frame.truth(), np.loadtxt(TEABOX / "camera_poses" / "Camera_005.txt"))
    assert frame.color.shape == (480, 640, 3) and frame.color.dtype == np.uint8
    assert frame.depth.shape == (480, 640) and frame.depth.dtype == np.float32
    # The teabox is about 0.5-0.9 m away; the background is no measurement.
    measured = frame.depth[frame.depth > 0]
    assert 0.3 < measured.min() < measured.max() < 1.5 and (frame.depth == 0).any()
    assert [c["camera"] for c in frame.colors] == ["Camera1"] and [d["camera"] for d in frame.depths] == ["Camera2"]
    assert sequence[-1].index == 99
    with pytest.raises(IndexError):
        sequence[100]


def test_grey_without_depth_gives_grey_frames_only():
    frame = icgp.Sequence(TEABOX, grey_without_depth=True)[0]
    assert frame.color.shape == (480, 640) and frame.depth is None


def test_make_sequence_writes_what_sequence_reads_back(tmp_path):
    sequence = icgp.make_sequence(tmp_path / "box", frames=4, width=160, height=120, focal=150, baseline=0.05,
                                  seed=3, progress=False)
    assert (sequence.layout, len(sequence)) == ("icgp", 4)
    np.testing.assert_array_equal(sequence.K_color, [[150, 0, 79.5], [0, 150, 59.5], [0, 0, 1]])
    np.testing.assert_array_equal(sequence.depth_T_color[:3, 3], [-0.05, 0, 0])
    frame = sequence[0]
    cMo = frame.truth("textured_box")
    # The box's origin projects into the image, and depth there is about its distance.
    u, v, _ = sequence.K_color @ (cMo[:3, 3] / cMo[2, 3])
    assert 0 <= u < 160 and 0 <= v < 120
    depth_at_centre = frame.depth[int(v) - 3:int(v) + 4, int(u) - 3:int(u) + 4]
    assert abs(np.median(depth_at_centre[depth_at_centre > 0]) - cMo[2, 3]) < 0.1
    # The same options and seed write the same frames.
    again = icgp.make_sequence(tmp_path / "again", frames=4, width=160, height=120, focal=150, baseline=0.05,
                               seed=3, progress=False)
    np.testing.assert_array_equal(again[3].color, sequence[3].color)
    np.testing.assert_array_equal(again[3].truth(), sequence[3].truth())


def test_make_sequence_refuses_what_the_program_refuses(tmp_path):
    with pytest.raises(ValueError, match=r"frames: expected an integer in \[1, 100000\], got 0"):
        icgp.make_sequence(tmp_path / "s", frames=0)
    with pytest.raises(ValueError, match=r"depth_dropout: expected a number in \[0, 1\], got 1.5"):
        icgp.make_sequence(tmp_path / "s", depth_dropout=1.5)
    with pytest.raises(ValueError, match="give a model or a scene, not both"):
        icgp.make_sequence(tmp_path / "s", SOURCE_DIR / "models" / "textured_box" / "textured_box.obj",
                           scene=SOURCE_DIR / "scenes" / "crossing.yaml")
    with pytest.raises(TypeError, match="unexpected keyword argument 'frame'"):
        icgp.make_sequence(tmp_path / "s", frame=3)


def test_a_folder_that_is_no_sequence_gets_the_program_s_message(icgp_program, tmp_path):
    (tmp_path / "empty").mkdir()
    code, _, err = run_icgp(icgp_program, "track", "--sequence", tmp_path / "empty")
    assert code != 0
    with pytest.raises(icgp.Error) as raised:
        icgp.Sequence(tmp_path / "empty")
    assert str(raised.value) == cli_error(err)
    with pytest.raises(icgp.Error, match="does not exist"):
        icgp.Sequence(tmp_path / "missing")
