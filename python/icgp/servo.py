# SPDX-License-Identifier: GPL-2.0-or-later
"""The servo simulator: scenarios, closed-loop runs and batch trials (docs/servo.md).

    import icgp.servo
    scenario = icgp.servo.load_scenario("scenarios/default.yaml")
    result = icgp.servo.run(scenario, "oracle")          # as `icgp servo --tracker oracle`
    print(result["succeeded"], result["final_t_mm"], result["final_r_deg"])

load_scenario  reads a scenario file (errors: icgp.Error naming the file and key), with
               numeric fields set over the file's: load_scenario(path, {"camera.latency_ms": 50})
Scenario       what it holds: robot, law, poses (4x4), stop thresholds, trial spread, seed
run            one closed-loop run; trial=i is `icgp servo --trials`' trial i; on_step(step)
               sees every step, control(state) replaces the scenario's control law
trials         batch trials, here or on a Dask cluster (icgp.batch): trials(scenario, n,
               seed, trackers=[...], client=None) -> the runs, summaries and table
sweep          the trials at each value of a scenario field, as `icgp servo --sweep`
local_cluster  a Dask LocalCluster of one-thread worker processes for trials
"""
from ._icgp.servo import Scenario, load_scenario, run  # noqa: F401
from .batch import local_cluster, sweep, trials  # noqa: F401
