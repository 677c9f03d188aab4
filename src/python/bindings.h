// SPDX-License-Identifier: GPL-2.0-or-later
// The parts of the extension module icgp._icgp, each registered by its own file.
#pragma once

#include <pybind11/pybind11.h>

#include <string>

#include "icgp/tracker/tracker_config.h"

namespace icgp::python {

/// The tracker: icgp.Tracker, icgp.TrackResult.
void register_tracker(pybind11::module_& m);
/// Sequences: icgp.Sequence, icgp.Frame, icgp.make_sequence.
void register_sequence(pybind11::module_& m);
/// Tracking errors as `icgp track` reports them: icgp.Evaluation, icgp.evaluate_tracker.
void register_evaluation(pybind11::module_& m);
/// The servo simulator: scenarios, runs and trials (icgp._icgp.servo, wrapped by icgp.servo).
void register_servo(pybind11::module_& m);
/// Batch trials of the servo simulator: one trial's result as a picklable value, and the
/// summaries of many (icgp._icgp.servo, used by icgp.batch).
void register_trials(pybind11::module_& m);

/// A tracker configuration as the bindings take it: `config` (None, a YAML file or a dict of
/// its keys), then the keyword `settings` read over it, each checked by the file's rules.
TrackerConfig tracker_config(const pybind11::object& config, const pybind11::dict& settings);

/// The models folder: $ICGP_MODELS_DIR, else the installed share/icgp/models beside the
/// package, else the source tree's.
std::string models_dir();

}  // namespace icgp::python
