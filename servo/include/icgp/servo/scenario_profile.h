// SPDX-License-Identifier: GPL-2.0-or-later
// Scenario profiles: the cell a scenario runs in unless its file says otherwise. "realistic"
// (the default) is a real cell's latency, robot response, calibration and object errors;
// "ideal" the exact world (docs/servo.md, "Profiles").
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "icgp/servo/scenario.h"

namespace icgp::servo {

/// The names scenario files give them (the top-level key `profile`), the default first.
const std::vector<std::pair<std::string, Profile>>& profile_names();

/// One field a profile gives: its dotted key path in a scenario file and its value as YAML
/// text. The file's own value wins; and the field is left out when the file sets
/// `unless_set` (a field whose meaning it depends on: a compute time only counts with the
/// timing the profile gives).
struct ProfileField {
  std::string field;
  std::string value;
  std::string unless_set;
};

/// The fields `profile` gives a scenario whose robot is `robot` (a free-flying camera has
/// no joints or hand-eye calibration, an arm no Cartesian acceleration limits).
std::vector<ProfileField> profile_fields(Profile profile, RobotKind robot);

}  // namespace icgp::servo
