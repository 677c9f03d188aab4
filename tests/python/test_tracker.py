# SPDX-License-Identifier: GPL-2.0-or-later
"""icgp.Tracker against the C++ program on the same frames, and its errors."""
import csv

import numpy as np
import pytest

import icgp
from conftest import COARSE, SOURCE_DIR, TEABOX, cli_error, run_icgp


def rotation_matrix(theta_u):
    """The rotation of a rotation vector (Rodrigues), as the program's CSV writes rotations."""
    angle = np.linalg.norm(theta_u)
    k = theta_u / angle
    K = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + np.sin(angle) * K + (1 - np.cos(angle)) * K @ K


@pytest.fixture(scope="module")
def teabox():
    return icgp.Sequence(TEABOX)


def track_with_arrays(sequence, tracker):
    tracker.set_pose(sequence[0].truth())
    results = []
    for i in range(len(sequence)):
        frame = sequence[i]
        results.append(tracker.track(frame.color, frame.depth, sequence.K_color, sequence.K_depth, sequence.depth_T_color))
    return results


def test_poses_are_those_of_icgp_track_on_the_same_frames(teabox, icgp_program, tmp_path):
    table = tmp_path / "track.csv"
    code, _, err = run_icgp(icgp_program, "track", "--sequence", TEABOX, "--config", COARSE, "--csv", table, "--quiet")
    assert code == 0, err
    with open(table) as f:
        rows = list(csv.DictReader(f))
    tracker = icgp.Tracker(teabox.objects[0]["model"], COARSE, body=teabox.objects[0]["name"])
    results = track_with_arrays(teabox, tracker)
    assert len(rows) == len(results) == 100
    for row, result in zip(rows, results):
        # The CSV holds 10 significant digits: equal to that precision is equal.
        program_t = np.array([float(row[k]) for k in ("tx", "ty", "tz")])
        np.testing.assert_allclose(result.pose[:3, 3], program_t, rtol=0, atol=1e-9)
        assert result.quality == pytest.approx(float(row["quality"]), abs=1e-9)
        # The CSV's rotation vector is of the nearest rotation: the sequence's poses (and so
        # the tracked ones) are orthonormal to 1e-7 only, as its files write them.
        program_R = rotation_matrix(np.array([float(row[k]) for k in ("rx", "ry", "rz")]))
        assert np.abs(result.pose[:3, :3] - program_R).max() < 3e-7
        assert result.tracked == (row["tracked"] == "1")
    # And the accuracy the program reports on teabox-blender: within a millimetre.
    errors = [np.linalg.norm(r.pose[:3, 3] - teabox[i].truth()[:3, 3]) for i, r in enumerate(results)]
    assert max(errors) < 1e-3


def test_a_frame_object_and_its_arrays_give_the_same_poses(teabox):
    by_arrays = track_with_arrays(teabox, icgp.Tracker(teabox.objects[0]["model"], COARSE))
    tracker = icgp.Tracker(teabox.objects[0]["model"], COARSE)
    tracker.set_pose(teabox[0].truth())
    by_frames = [tracker.track_frame(teabox[i]) for i in range(len(teabox))]
    for a, b in zip(by_arrays, by_frames):
        np.testing.assert_array_equal(a.pose, b.pose)


def test_rgb_and_bgr_arrays_and_uint16_depth_track_alike(teabox):
    frames = [teabox[i] for i in range(10)]
    bgr = icgp.Tracker(teabox.objects[0]["model"], COARSE)
    rgb = icgp.Tracker(teabox.objects[0]["model"], COARSE)
    for t in (bgr, rgb):
        t.set_pose(frames[0].truth())
    for frame in frames:
        a = bgr.track(frame.color, frame.depth, teabox.K_color, teabox.K_depth, teabox.depth_T_color)
        # A non-contiguous RGB view: converted, not read in place.
        b = rgb.track(frame.color[:, :, ::-1], frame.depth.astype(np.float64), teabox.K_color, teabox.K_depth,
                      teabox.depth_T_color, color_order="rgb")
        np.testing.assert_array_equal(a.pose, b.pose)


def test_result_reports_every_cue(teabox):
    tracker = icgp.Tracker(teabox.objects[0]["model"], COARSE)
    result = track_with_arrays(teabox, tracker)[-1]
    assert [c["cue"] for c in result.cues] == ["region", "depth", "texture"]
    for cue in result.cues:
        assert 0.0 <= cue["score"] <= 1.0 and cue["sigma"] > 0.0 and cue["n_valid"] > 0
    assert result.tracked and 0.5 < result.quality <= 1.0
    assert result.quality == pytest.approx(np.median([c["score"] for c in result.cues if not c["abstained"]]))
    assert list(result.bodies) == ["object"]


def test_keyword_settings_are_read_as_a_file_s_keys(tmp_path):
    model = TEABOX / "teabox.cao"
    by_keywords = icgp.Tracker(model, COARSE, modalities=["region", "depth"], depth={"noise": {"estimate": False}})
    config = tmp_path / "config.yaml"
    config.write_text(open(COARSE).read() + "modalities: [region, depth]\ndepth: {noise: {estimate: false}}\n")
    assert by_keywords.config == icgp.Tracker(model, config).config
    assert by_keywords.config != icgp.Tracker(model, COARSE).config


def test_covariance_is_symmetric_positive_and_shrinks_with_depth(teabox):
    tracker = icgp.Tracker(teabox.objects[0]["model"], COARSE)
    with pytest.raises(icgp.Error, match="no frame has been tracked yet"):
        tracker.covariance()
    track_with_arrays(teabox, tracker)
    with_depth = tracker.covariance()
    assert with_depth.shape == (6, 6)
    np.testing.assert_array_equal(with_depth, with_depth.T)
    assert np.linalg.eigvalsh(with_depth).min() > -1e-15
    colour_only = icgp.Tracker(teabox.objects[0]["model"], COARSE, modalities=["region"])
    colour_only.set_pose(teabox[0].truth())
    for i in range(10):
        colour_only.track(teabox[i].color, None, teabox.K_color)
    # Depth pins the distance along the optical axis far better than a contour does.
    assert colour_only.covariance()[2, 2] > 10 * with_depth[2, 2]


def test_an_articulated_object_is_tracked_with_its_joint(tmp_path):
    sequence = icgp.make_sequence(tmp_path / "hinged", scene=SOURCE_DIR / "scenes" / "hinged_box.yaml", frames=30,
                                  width=320, height=240, focal=300, progress=False)
    models = SOURCE_DIR / "models" / "hinged_box"
    tracker = icgp.Tracker(models / "base.obj", COARSE, body="base")
    tracker.add_body("lid", models / "lid.obj", joint={
        "parent": "base", "joint": "revolute", "axis": [-1, 0, 0],
        "origin": {"t": [0, 0.03, -0.04], "r_deg": [0, 0, 0]}, "limits_deg": [0, 110]})
    assert tracker.body_names == ["base", "lid"]
    first = sequence[0]
    tracker.set_pose(first.truth("base"))
    tracker.set_joint_values("lid", first.joint_truth["lid"])
    for i in range(len(sequence)):
        frame = sequence[i]
        result = tracker.track_frame(frame)
        lid = result.bodies["lid"]
        assert abs(lid.joint_values[0] - frame.joint_truth["lid"][0]) < np.radians(1.0)
        assert np.linalg.norm(result.pose[:3, 3] - frame.truth("base")[:3, 3]) < 2e-3
    assert sequence[29].joint_truth["lid"][0] > np.radians(10.0)  # the lid did open


def test_errors_name_the_argument():
    tracker = icgp.Tracker(TEABOX / "teabox.cao", COARSE)
    color = np.zeros((48, 64, 3), np.uint8)
    K = np.array([[50.0, 0, 32], [0, 50, 24], [0, 0, 1]])
    with pytest.raises(icgp.Error, match=r"no initial pose: call set_pose\(pose\) first"):
        tracker.track(color, None, K)
    tracker.set_pose(np.eye(4) + np.diag([0, 0, 0, 0]))
    with pytest.raises(ValueError, match=r"color: expected shape \(H, W, 3\) or \(H, W\), got \(48, 64, 4\)"):
        tracker.track(np.zeros((48, 64, 4), np.uint8), None, K)
    with pytest.raises(ValueError, match="color: expected dtype uint8, got float32"):
        tracker.track(color.astype(np.float32), None, K)
    with pytest.raises(ValueError, match=r"K_color: expected shape \(3, 3\), got \(4, 4\)"):
        tracker.track(color, None, np.eye(4))
    with pytest.raises(ValueError, match=r"depth: expected dtype float32 or float64 \(metres\) or uint16"):
        tracker.track(color, np.zeros((48, 64), np.int8), K)
    with pytest.raises(ValueError, match="pose: expected a homogeneous transform"):
        tracker.set_pose(np.ones((4, 4)))
    with pytest.raises(icgp.Error, match="no body named 'lid' \\(the bodies are object\\)"):
        tracker.pose("lid")


def test_a_bad_configuration_gets_the_program_s_message(icgp_program, tmp_path):
    config = tmp_path / "bad.yaml"
    config.write_text("depth:\n  noise: {estimate: maybe}\n")
    code, _, err = run_icgp(icgp_program, "track", "--sequence", TEABOX, "--config", config)
    assert code != 0
    with pytest.raises(icgp.Error) as raised:
        icgp.Tracker(TEABOX / "teabox.cao", config)
    assert str(raised.value) == cli_error(err)
    with pytest.raises(icgp.Error, match=r"keyword arguments: depth.noise.estimate: expected true or false"):
        icgp.Tracker(TEABOX / "teabox.cao", depth={"noise": {"estimate": "maybe"}})
    with pytest.raises(icgp.Error, match=r"keyword arguments: colour: unknown key \(valid keys: preset, "):
        icgp.Tracker(TEABOX / "teabox.cao", colour=1)


def test_a_missing_model_names_the_file():
    with pytest.raises(icgp.Error, match="/no/such/model.obj"):
        icgp.Tracker("/no/such/model.obj")


def test_an_occluder_hides_what_its_pose_puts_in_front(tmp_path):
    # The mug crosses in front of the box. Tracked with the mug as an occluder at its true
    # pose every frame, the box's cues leave out what the mug hides: the run differs from one
    # without it, and is the one a configuration's occluder gives. Far away, it hides nothing.
    sequence = icgp.make_sequence(tmp_path / "crossing", scene=SOURCE_DIR / "scenes" / "crossing.yaml", frames=50,
                                  width=320, height=240, focal=300, progress=False)
    box = SOURCE_DIR / "models" / "textured_box" / "textured_box.obj"
    mug = SOURCE_DIR / "models" / "textureless_mug" / "textureless_mug.obj"
    far = np.eye(4)
    far[:3, 3] = [5.0, 5.0, 5.0]

    def run(tracker, mug_pose):
        tracker.set_pose(sequence[0].truth("box"))
        poses = []
        for i in range(len(sequence)):
            frame = sequence[i]
            if mug_pose:
                tracker.set_pose(mug_pose(frame), body="mug")
                np.testing.assert_array_equal(tracker.pose("mug"), mug_pose(frame))
            result = tracker.track_frame(frame)
            assert list(result.bodies) == ["box"]  # an occluder is not tracked
            poses.append(result.pose)
        return np.array(poses)

    def with_occluder():
        tracker = icgp.Tracker(box, COARSE, body="box")
        tracker.add_occluder("mug", mug)
        return tracker

    alone = run(icgp.Tracker(box, COARSE, body="box"), None)
    np.testing.assert_array_equal(run(with_occluder(), lambda frame: far), alone)
    in_front = run(with_occluder(), lambda frame: frame.truth("mug"))
    assert np.abs(in_front - alone).max() > 1e-6
    configured = icgp.Tracker(box, COARSE, body="box", bodies=[{"name": "mug", "mesh": str(mug), "role": "occluder"}])
    np.testing.assert_array_equal(run(configured, lambda frame: frame.truth("mug")), in_front)


def test_detect_starts_without_a_pose_at_the_truth_up_to_the_model_symmetry(teabox):
    """The teabox .cao has no appearance: a box turned 180 degrees about an axis through its
    centre is the same model, so the detection is checked by ADD-S, and then tracked on."""
    tracker = icgp.Tracker(teabox.objects[0]["model"], COARSE, body=teabox.objects[0]["name"])
    evaluation = icgp.Evaluation(teabox.objects[0]["model"])
    frame = teabox[0]
    found = tracker.detect(frame.color, frame.depth, teabox.K_color, teabox.K_depth, teabox.depth_T_color)
    assert found["found"], found["why_not"]
    assert found["pose"].shape == (4, 4)
    assert found["quality"] >= 0.6
    for i in range(1, 6):
        frame = teabox[i]
        r = tracker.track(frame.color, frame.depth, teabox.K_color, teabox.K_depth, teabox.depth_T_color)
        evaluation.add(i, r.pose, frame.truth(), r.tracked, r.ms, r.quality)
    summary = evaluation.summary()
    assert summary["tracked"] == 5
    # The model's surface where the truth's is (a frozen or wrong pose is centimetres off).
    assert summary["mean_adds_mm"] < 5.0, summary


def test_detect_reports_why_nothing_is_found_in_a_blank_frame(teabox):
    tracker = icgp.Tracker(teabox.objects[0]["model"], COARSE, body=teabox.objects[0]["name"])
    frame = teabox[0]
    found = tracker.detect(np.zeros_like(frame.color), np.zeros_like(frame.depth), teabox.K_color, teabox.K_depth,
                           teabox.depth_T_color)
    assert not found["found"]
    assert found["pose"] is None
    assert found["why_not"]


def test_the_edge_cue_alone_follows_the_grey_teabox(teabox):
    """The creases alone, from Python, on grey images without depth: ViSP's moving edges."""
    tracker = icgp.Tracker(teabox.objects[0]["model"], COARSE, modalities=["edge"], edge={"n_points_max": 200})
    assert "edge:" in tracker.config and "n_points_max: 200" in tracker.config
    tracker.set_pose(teabox[0].truth())
    errors = []
    for i in range(30):
        grey = teabox[i].color.mean(axis=2).astype(np.uint8)
        result = tracker.track(grey, None, teabox.K_color)
        assert result.cues[0]["cue"] == "edge" and result.cues[0]["n_valid"] >= 50
        errors.append(np.linalg.norm(result.pose[:3, 3] - teabox[i].truth()[:3, 3]))
    # A frozen pose would be this far off by the last frame.
    frozen = np.linalg.norm(teabox[0].truth()[:3, 3] - teabox[29].truth()[:3, 3])
    assert max(errors) < 5e-3 < frozen


def test_evaluate_tracker_runs_the_benchmarks_loop_and_beats_a_frozen_pose(teabox):
    """icgp.evaluate_tracker is the loop of `icgp bench`: started at the first truth, every frame
    tracked and evaluated. A pose frozen at the start scores far worse on the same frames."""
    evaluation = icgp.evaluate_tracker(teabox, config=COARSE, frames=30)
    summary = evaluation.summary()
    assert summary["frames"] == 30 and summary["frames_with_truth"] == 30
    assert summary["tracked"] == 30
    assert summary["median_ms"] > 0.0

    frozen = icgp.Evaluation(teabox.objects[0]["model"])
    start = teabox[0].truth()
    for i in range(30):
        frozen.add(i, start, teabox[i].truth())
    assert summary["mean_t_mm"] < 0.5 * frozen.summary()["mean_t_mm"], (summary, frozen.summary())

    with pytest.raises(icgp.Error, match="no frames to track"):
        icgp.evaluate_tracker(teabox, config=COARSE, frames=0)
