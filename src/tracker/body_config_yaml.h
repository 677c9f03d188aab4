// SPDX-License-Identifier: GPL-2.0-or-later
// A configuration's `bodies:` list in YAML (BodyConfig), for the configuration's reader and
// writer: private to the tracker module, so that no public header brings in yaml-cpp.
#pragma once

#include <vector>

#include "icgp/io/yaml_reader.h"
#include "icgp/tracker/body_config.h"

namespace icgp {

/// Reads a `bodies:` list. Errors name the file, the body and the field: a name given
/// twice, a joint whose values are out of order (limits with min > max), an occluder with a
/// joint, a cycle of parents.
std::vector<BodyConfig> read_body_configs(const yaml::Value& list);
/// Checks bodies set in code as read_body_configs checks a file's, failing at `list`: the
/// error names the body and the field.
void check_body_configs(const std::vector<BodyConfig>& bodies, const yaml::Location& list);
/// Writes `bodies` as read_body_configs reads them.
void write_body_configs(YAML::Emitter& out, const std::vector<BodyConfig>& bodies);

}  // namespace icgp
