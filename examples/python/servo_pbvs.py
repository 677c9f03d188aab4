#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-2.0-or-later
"""A position-based visual servoing (PBVS) law written in Python, in the loop of icgp's servo
simulator, and the scenario's own vpServo law on the same seed for comparison.

    PYTHONPATH=build/python python3 examples/python/servo_pbvs.py [SCENARIO.yaml]

Without a scenario it runs scenarios/default.yaml (a free-flying camera, icgp tracking).
The law drives s = (t, θu) of cdMc, the current camera in the desired camera's frame, to
zero: with R and t the rotation and translation of cdMc, the camera twist v = -λ Rᵀ t,
ω = -λ θu makes ds/dt = -λ s, so the camera moves along a straight line. On a Viper 850
carrying the camera (arm_eye_in_hand.yaml) or a gripper (grasp_approach.yaml, where the
law drives the gripper's pose to the object), the joints get pinv(J) times that twist.
"""
import sys
from pathlib import Path

import numpy as np

import icgp
import icgp.servo

GAIN = 1.0  # λ, 1/s


def theta_u(R):
    """The rotation R (of less than 180°) as θu: its axis times its angle, radians."""
    angle = np.arccos(np.clip((np.trace(R) - 1.0) / 2.0, -1.0, 1.0))
    if angle < 1e-12:
        return np.zeros(3)
    return angle / (2.0 * np.sin(angle)) * np.array([R[2, 1] - R[1, 2], R[0, 2] - R[2, 0], R[1, 0] - R[0, 1]])


def pbvs(state):
    """The velocity the robot takes: the camera's twist (vx, vy, vz, wx, wy, wz) in its own
    frame, m/s and rad/s, through the robot's Jacobian (the identity for a free-flying camera;
    an arm's joint velocities otherwise)."""
    cdMc = state["desired"] @ np.linalg.inv(state["pose"])  # pose: the estimated cMo (gMo)
    R, t = cdMc[:3, :3], cdMc[:3, 3]
    twist = np.concatenate([-GAIN * R.T @ t, -GAIN * theta_u(R)])
    return np.linalg.pinv(state["jacobian"]) @ twist


def report(label, run):
    converged = f"at {run['converged_time']:.2f} s" if run["converged"] else "never"
    print(f"{label:<16} {'success' if run['succeeded'] else 'FAILED':<7}  converged {converged:<9}  "
          f"final {run['final_t_mm']:.3f} mm {run['final_r_deg']:.3f} deg  "
          f"tracker mean {run['mean_track_t_mm']:.3f} mm  {run['steps_per_s']:.0f} steps/s")


def main():
    default = Path(icgp.models_dir()).parent / "scenarios" / "default.yaml"
    scenario = icgp.servo.load_scenario(sys.argv[1] if len(sys.argv) > 1 else default)
    if scenario.robot == "viper850_eye_to_hand":
        sys.exit(f"{scenario.file}: this law moves the camera or the gripper; eye-to-hand, the arm moves the object")
    print(scenario)
    python = icgp.servo.run(scenario, control=pbvs)
    visp = icgp.servo.run(scenario)  # the scenario's law, same seed: same noise
    report("PBVS in Python", python)
    report(f"vpServo {scenario.law}", visp)
    return 0 if python["succeeded"] and visp["succeeded"] else 1


if __name__ == "__main__":
    sys.exit(main())
