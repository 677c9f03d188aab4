// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <string>

namespace icgp {

/// A path's extension in lower case, with its dot (".cao" for "Box.CAO"); empty when none.
/// Readers pick the format by it, whatever case the file was saved with.
std::string lower_extension(const std::string& path);

}  // namespace icgp
