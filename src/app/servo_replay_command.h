// SPDX-License-Identifier: GPL-2.0-or-later
// `icgp servo SCENARIO --replay LOG`: a recorded run's camera path rendered again and tracked
// open-loop (icgp::servo::replay_camera_path), with progress, a table and its files.
#pragma once

#include <optional>
#include <string>

#include "icgp/servo/scenario.h"

namespace icgp::app {

/// Replays the run whose log is `log` with `scenario` (its renderer and tracker as the
/// command line set them), seeded as replay_seed says with `seed` (--seed, when given);
/// prints the table and writes `out`/replay.csv and `out`/replay.json. Progress lines on
/// stderr unless `quiet`. Ctrl-C stops it after the current frame, writing the frames
/// done (CommandOutcome, exit status 130).
void run_servo_replay(const servo::Scenario& scenario, const std::string& log, std::optional<unsigned> seed,
                      const std::string& out, bool quiet);

}  // namespace icgp::app
