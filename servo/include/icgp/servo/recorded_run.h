// SPDX-License-Identifier: GPL-2.0-or-later
// A servo run read back from what it left behind: the camera path of its log.csv
// (write_step_csv) and the seed of the summary.json beside it, for replay_camera_path.
#pragma once

#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>
#include <visp3/core/vpHomogeneousMatrix.h>

namespace icgp::servo {

/// A log or summary that cannot be read back. The message names the file, the line and the
/// column ("out/log.csv:7: column 'camera_ty': expected a number, got 'abc'").
class LogError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// One step of a recorded run.
struct RecordedStep {
  int line = 0;        ///< where the log gives it (the header is line 1), for messages
  double time = 0.0;   ///< seconds of simulated time at the capture
  vpHomogeneousMatrix wMc;  ///< where the camera truly was (ServoStep::wMc_true)
  bool skipped = false;     ///< the run's tracker was busy and skipped the frame (false when the log does not say)
  /// The run's own tracker error (metres, radians); NaN where the run had none or the log
  /// does not say.
  double track_t = std::numeric_limits<double>::quiet_NaN();
  double track_r = std::numeric_limits<double>::quiet_NaN();
};

/// What a run's log.csv and the summary.json beside it (when there is one) say.
struct RecordedRun {
  std::string log;  ///< the log.csv it was read from
  std::vector<RecordedStep> steps;  ///< at least one
  std::string summary;              ///< the summary.json read beside the log; empty when none
  std::optional<unsigned> seed;     ///< the summary's noise seed, when it gives one
  std::optional<std::string> scenario;  ///< the summary's scenario name, when it gives one
};

/// Reads the camera path of a log.csv: the columns time and kCameraPoseColumns (required),
/// skipped, track_t_mm and track_r_deg (when there). Reads summary.json beside it when it
/// is there. Throws LogError naming the file, the line and the column for a missing column,
/// a line of another number of values than the header, a value that is not a number (or
/// not finite where it must be), a flag other than 0 or 1, a θu vector that is not a
/// rotation's (an angle above π), a log without steps, and a summary.json that is not JSON
/// or whose seed is not a non-negative integer.
RecordedRun read_recorded_run(const std::string& log_csv);

}  // namespace icgp::servo
