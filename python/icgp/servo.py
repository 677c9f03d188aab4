# SPDX-License-Identifier: GPL-2.0-or-later
"""The servo simulator: scenarios, closed-loop runs and batch trials (docs/servo.md).

    import icgp.servo
    scenario = icgp.servo.load_scenario("scenarios/default.yaml")
    result = icgp.servo.run(scenario, "oracle")          # as `icgp servo --tracker oracle`
    print(result["succeeded"], result["final_t_mm"], result["final_r_deg"])

load_scenario  reads a scenario file (errors: icgp.Error naming the file and key)
Scenario       what it holds: robot, law, poses (4x4), stop thresholds, trial spread, seed
run            one closed-loop run; trial=i is `icgp servo --trials`' trial i; on_step(step)
               sees every step, control(state) replaces the scenario's control law
trials         batch trials, here or on a Dask cluster (icgp.batch): trials(scenario, n,
               seed, trackers=[...], client=None) -> the runs, summaries and table
local_cluster  a Dask LocalCluster of one-thread worker processes for trials
"""
from ._icgp.servo import Scenario, load_scenario, run  # noqa: F401
from .batch import local_cluster, trials  # noqa: F401
