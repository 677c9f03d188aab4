# SPDX-License-Identifier: GPL-2.0-or-later
"""icgp.servo: runs from Python match `icgp servo`'s, callbacks see every step, a control
law written in Python drives the robot, and errors arrive as they were raised."""
import csv
import json
import math
import os
import re
import select
import signal
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import icgp
import icgp.servo

SOURCE = Path(os.environ["ICGP_SOURCE_DIR"])
SMALL = SOURCE / "tests" / "servo" / "data" / "small_pbvs.yaml"
MALFORMED = SOURCE / "tests" / "servo" / "data" / "malformed.yaml"
GAIN = 1.5  # 1/s, the hand-written law's


def icgp_servo(*args):
    """Runs `icgp servo ARGS --tracker oracle --quiet`; returns its stderr."""
    done = subprocess.run([os.environ["ICGP"], "servo", *map(str, args), "--tracker", "oracle", "--quiet"],
                          capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr
    return done.stderr


def theta_u(R):
    angle = math.acos(max(-1.0, min(1.0, (np.trace(R) - 1.0) / 2.0)))
    if angle < 1e-12:
        return np.zeros(3)
    return angle / (2.0 * math.sin(angle)) * np.array([R[2, 1] - R[1, 2], R[0, 2] - R[2, 0], R[1, 0] - R[0, 1]])


def pbvs(state):
    """PBVS on s = (t, θu) of cdMc: v = -λ Rᵀ t, ω = -λ θu makes ds/dt = -λ s."""
    cdMc = state["desired"] @ np.linalg.inv(state["pose"])
    R, t = cdMc[:3, :3], cdMc[:3, 3]
    return np.concatenate([-GAIN * R.T @ t, -GAIN * theta_u(R)])


@pytest.fixture(scope="module")
def scenario():
    return icgp.servo.load_scenario(SMALL)


def test_scenario_properties_and_pickle(scenario):
    import pickle
    assert scenario.name == "small_pbvs"
    assert (scenario.robot, scenario.law, scenario.tracker) == ("free_flying", "pbvs", "icgp")
    assert scenario.profile == "ideal"
    assert icgp.servo.load_scenario(SOURCE / "scenarios" / "default.yaml").profile == "realistic"
    assert scenario.image_size == (320, 240) and scenario.rate_hz == 30
    assert scenario.stop == pytest.approx({"translation_mm": 1, "rotation_deg": 0.1, "settle_time": 0.2, "max_time": 8})
    assert scenario.trials == pytest.approx({"translation_mm": 10, "rotation_deg": 5})
    np.testing.assert_allclose(scenario.desired_cMo[:3, 3], [0, 0, 0.35], atol=1e-12)
    np.testing.assert_allclose(scenario.initial_cMo[:3, 3], [0.03, -0.02, 0.45], atol=1e-12)
    assert scenario.start_gMo is None and scenario.desired_gMo is None
    assert "small_pbvs" in repr(scenario)
    copy = pickle.loads(pickle.dumps(scenario))
    assert os.path.isabs(copy.file) and Path(copy.file).samefile(SMALL)
    assert copy.seed == scenario.seed


def test_run_converges_as_the_command_line_run(scenario, tmp_path):
    result = icgp.servo.run(scenario, "oracle")
    assert result["succeeded"] and result["converged"]
    assert result["tracker"].startswith("oracle") and result["trial"] is None
    assert result["final_t_mm"] < 1.0 and result["final_r_deg"] < 0.1
    assert result["steps"][0]["servo_t_mm"] > 100.0  # it started far from the goal
    summary = tmp_path / "summary.json"
    icgp_servo(SMALL, "--summary", summary, "--out", tmp_path)
    cli = json.loads(summary.read_text())
    assert cli["trials"] == 1
    assert result["final_t_mm"] == pytest.approx(cli["final_t_mm"]["median"], rel=1e-8)
    assert result["final_r_deg"] == pytest.approx(cli["final_r_deg"]["median"], rel=1e-8)
    assert result["converged_time"] == pytest.approx(cli["converged_time_s_median"], rel=1e-8)
    assert cli["seed"] == scenario.seed
    # Each step's true camera pose, as the command's log.csv gives it (a replay reads it).
    with open(tmp_path / "log.csv", newline="") as log:
        rows = list(csv.DictReader(log))
    assert len(rows) == len(result["steps"])
    last = result["steps"][-1]["wMc_true"]
    assert np.linalg.norm(last[:3, 3]) > 0.05  # the camera moved from the world's origin
    np.testing.assert_allclose([float(rows[-1][c]) for c in ("camera_tx", "camera_ty", "camera_tz")], last[:3, 3],
                               atol=1e-12)


def test_trial_i_is_the_command_line_trial_i(scenario, tmp_path):
    trials = [icgp.servo.run(scenario, "oracle", seed=5, trial=i) for i in range(2)]
    summary = tmp_path / "summary.json"
    stderr = icgp_servo(SMALL, "--trials", 2, "--seed", 5, "--summary", summary, "--out", tmp_path)
    cli = json.loads(summary.read_text())
    final_t = sorted(r["final_t_mm"] for r in trials)
    assert cli["final_t_mm"]["max"] == pytest.approx(final_t[1], rel=1e-8)
    assert cli["final_t_mm"]["median"] == pytest.approx(sum(final_t) / 2, rel=1e-8)
    # Each trial's line: "trial 1/2 oracle ...: success, final 0.123 mm 0.012 deg, ..."
    lines = re.findall(r"^trial (\d)/2 .*final ([\d.]+) mm ([\d.]+) deg", stderr, re.MULTILINE)
    assert [int(i) for i, _, _ in lines] == [1, 2]
    for r, (_, mm, deg) in zip(trials, lines):
        assert (f"{r['final_t_mm']:.3f}", f"{r['final_r_deg']:.3f}") == (mm, deg)
        assert r["seed"] == 5 + r["trial"]
    # Each trial starts at a random offset of the scenario's start, within its spread.
    starts = [r["steps"][0]["cMo_true"] for r in trials]
    for start in starts:
        offset = start @ np.linalg.inv(scenario.initial_cMo)
        assert 0.0 < np.linalg.norm(offset[:3, 3]) <= 0.010 + 1e-9
        assert 0.0 < np.linalg.norm(theta_u(offset[:3, :3])) <= math.radians(5) + 1e-9
    assert not np.array_equal(starts[0], starts[1])


def test_on_step_sees_every_step_in_order(scenario):
    seen = []
    result = icgp.servo.run(scenario, "oracle", on_step=seen.append)
    assert len(seen) == len(result["steps"]) > 10
    assert all(a is b for a, b in zip(seen, result["steps"]))  # the dicts the summary lists
    times = [step["time"] for step in seen]
    np.testing.assert_allclose(np.diff(times), 1.0 / scenario.rate_hz, rtol=1e-9)
    assert times[0] == 0.0
    step = seen[0]
    assert step["cMo_true"].shape == (4, 4) and step["velocity"].shape == (6,)
    assert not step["lost"] and not step["safety_stop"]
    np.testing.assert_allclose(step["cMo_true"], scenario.initial_cMo, atol=1e-9)
    # The ideal loop: every frame taken, every command at once.
    assert not any(s["skipped"] for s in seen)
    assert all(s["command_delay_ms"] == 0.0 for s in seen)


def test_a_scenario_with_latency_logs_each_commands_delay(scenario):
    delayed = icgp.servo.load_scenario(scenario.file, {"camera.latency_ms": 100})
    result = icgp.servo.run(delayed, "oracle")
    assert [s["command_delay_ms"] for s in result["steps"]] == pytest.approx([100.0] * len(result["steps"]))


def test_a_control_law_in_python_converges(scenario):
    states = []

    def law(state):
        states.append(state)
        return pbvs(state)

    result = icgp.servo.run(scenario, "oracle", control=law)
    assert result["succeeded"], (result["final_t_mm"], result["final_r_deg"])
    assert len(states) == len(result["steps"])
    for state, step in zip(states, result["steps"]):
        assert state["time"] == step["time"]
        assert (state["robot"], state["velocity_size"]) == ("free_flying", 6)
        np.testing.assert_array_equal(state["jacobian"], np.eye(6))  # the camera's own twist
        np.testing.assert_array_equal(state["desired"], scenario.desired_cMo)
        np.testing.assert_allclose(state["pose"], step["cMo_true"], atol=1e-12)  # the oracle's
        assert math.isnan(step["servo_error_norm"])  # no vpServo features
    # Applied as commanded once within the robot's limits (0.1 m/s, 0.5 rad/s by default).
    last = result["steps"][-1]
    np.testing.assert_allclose(last["velocity"], pbvs(states[-1]), atol=1e-12)


def test_a_law_in_python_drives_an_arm_through_its_jacobian(tmp_path):
    # The eye-in-hand Viper 850 at the small scenario's size and start, with the oracle.
    arm = tmp_path / "arm.yaml"
    arm.write_text(SMALL.read_text().replace("object: {model: textured_box}",
                                             "object: {model: textured_box}\nrobot: viper850_eye_in_hand")
                   .replace("../../configs/coarse_models.yaml", str(SOURCE / "tests" / "configs" / "coarse_models.yaml")))
    jacobians = []

    def law(state):
        jacobians.append(state["jacobian"])
        return np.linalg.pinv(state["jacobian"]) @ pbvs(state)

    result = icgp.servo.run(icgp.servo.load_scenario(arm), "oracle", control=law)
    assert result["succeeded"], (result["final_t_mm"], result["final_r_deg"])
    # cVe eJe: full rank away from singularities, and changing as the joints move.
    assert jacobians[0].shape == (6, 6) and np.linalg.matrix_rank(jacobians[0]) == 6
    assert np.abs(jacobians[-1] - jacobians[0]).max() > 1e-3


def test_a_law_of_the_wrong_size_is_an_error_naming_6(scenario):
    with pytest.raises(icgp.Error, match=r"control law: expected 6 values \(the camera twist"):
        icgp.servo.run(scenario, "oracle", control=lambda state: [0.0] * 5)
    with pytest.raises(TypeError, match="control: expected a sequence of numbers"):
        icgp.servo.run(scenario, "oracle", control=lambda state: "fast")


def test_exceptions_in_callbacks_propagate_unchanged(scenario):
    class Enough(Exception):
        pass

    steps = []

    def on_step(step):
        steps.append(step)
        if len(steps) == 3:
            raise Enough("three steps")

    with pytest.raises(Enough, match="three steps"):
        icgp.servo.run(scenario, "oracle", on_step=on_step)
    assert len(steps) == 3  # the run ended there

    def interrupted(state):
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        icgp.servo.run(scenario, "oracle", control=interrupted)


def test_ctrl_c_stops_a_run_without_callbacks(tmp_path):
    # A run of 18 000 steps (settle_time: it cannot end before 600 s), so that it is still
    # running when the signal comes; the progress line says it has started.
    long_run = tmp_path / "long_run.yaml"
    long_run.write_text(SMALL.read_text().replace("settle_time: 0.2, max_time: 8", "settle_time: 600, max_time: 600")
                        .replace("../../configs/coarse_models.yaml", str(SOURCE / "tests/configs/coarse_models.yaml")))
    child = subprocess.Popen(
        [sys.executable, "-c", "import sys, icgp.servo\n"
         "try:\n"
         "    icgp.servo.run(icgp.servo.load_scenario(sys.argv[1]), 'oracle', progress=True)\n"
         "except KeyboardInterrupt:\n"
         "    sys.exit(42)\n", str(long_run)],
        stderr=subprocess.PIPE)
    try:
        seen = b""
        while b"[servo]" not in seen:
            ready, _, _ = select.select([child.stderr], [], [], 120)
            assert ready, "no progress line within 120 s"
            chunk = os.read(child.stderr.fileno(), 4096)
            assert chunk, seen.decode()
            seen += chunk
        child.send_signal(signal.SIGINT)
        assert child.wait(timeout=120) == 42, seen.decode()
    finally:
        child.kill()
        child.wait()


def test_bad_arguments_name_themselves(scenario):
    with pytest.raises(ValueError, match="tracker: expected 'icgp', 'visp', 'oracle', 'image_oracle' or None"):
        icgp.servo.run(scenario, "orcale")
    with pytest.raises(ValueError, match=r"seed: expected an integer in \[0, 4294967295\]"):
        icgp.servo.run(scenario, "oracle", seed=-1)
    with pytest.raises(ValueError, match="trial: expected an integer"):
        icgp.servo.run(scenario, "oracle", trial=True)
    with pytest.raises(TypeError, match="on_step: expected a callable"):
        icgp.servo.run(scenario, "oracle", on_step=3)


def test_a_malformed_scenario_is_the_command_line_error():
    with pytest.raises(icgp.Error) as error:
        icgp.servo.load_scenario(MALFORMED)
    assert str(error.value) == f"{MALFORMED}: control.gain: expected a number in (0, 1000], got 'fast'"
    done = subprocess.run([os.environ["ICGP"], "servo", str(MALFORMED)], capture_output=True, text=True, timeout=60)
    assert done.returncode == 1
    assert done.stderr.strip().endswith(f"icgp: error: {error.value}")
