// SPDX-License-Identifier: GPL-2.0-or-later
// Replay: the camera path of a recorded servo run rendered again (with its renderer or
// another) and tracked open-loop by the scenario's tracker, to see how the tracker fares on
// the same path in other images, cue by cue.
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "icgp/servo/pose_estimator.h"
#include "icgp/servo/recorded_run.h"
#include "icgp/servo/scenario.h"

namespace icgp::servo {

/// One frame of a replay.
struct ReplayFrame {
  double time = 0.0;     ///< seconds of simulated time, the recorded step's
  bool dropped = false;  ///< the sensor lost the frame (the scenario's frame_drop, drawn again)
  bool skipped = false;  ///< the run's tracker skipped it (busy, TrackerSpec::real_timing), so the replay's does
  bool lost = false;     ///< the tracker's verdict: on a frame it did not take, the last one's
  /// The tracker's estimate to the true cMo, metres and radians; NaN while the object is out
  /// of the scene or not yet found, as in the run.
  double track_t = 0.0, track_r = 0.0;
  double recorded_track_t = 0.0, recorded_track_r = 0.0;  ///< the run's own (RecordedStep)
  double render_ms = 0.0, track_ms = 0.0;  ///< wall time; track_ms 0 on a frame not taken
  std::vector<CueFit> cues;  ///< each cue's fit on the frame; empty when the tracker did not track it
};

/// A replay of a recorded run.
struct ReplayResult {
  std::string log;       ///< the log.csv replayed
  std::string scenario;  ///< its name
  std::string tracker;   ///< PoseEstimator::name
  std::string renderer;  ///< the name of the renderer (renderer_names)
  unsigned seed = 0;     ///< the noise seed the scene was built with
  std::size_t recorded_steps = 0;  ///< the log's; more than frames.size() when interrupted
  std::vector<ReplayFrame> frames;
  bool interrupted = false;  ///< a stop request ended the replay before the log's last step
};

struct ReplayOptions {
  /// Called after every frame with it and how many are done of how many.
  std::function<void(const ReplayFrame&, std::size_t done, std::size_t total)> on_frame;
};

/// The seed the replay of `run` builds its scene with: the one its summary.json gives, else
/// `requested` (icgp servo --seed), else the scenario's. Throws std::invalid_argument when
/// `requested` is not the summary's: another seed draws another cell (calibration, object,
/// background, noise), not the run's.
unsigned replay_seed(const RecordedRun& run, const Scenario& scenario, std::optional<unsigned> requested);

/// Renders `scenario`'s scene (with its camera.renderer) at each recorded step's camera pose
/// and time and gives the frames to the scenario's tracker, as the run gave them: started
/// as the scenario says (detection, or the truth), taught the goal by showing when the
/// scenario teaches it so, restarted after a loss at the last pose it did not report lost,
/// the frames the run's tracker skipped skipped. No control law runs and no robot moves: the
/// path is the run's. With the run's seed and renderer the frames are the run's own, so
/// are the tracker's errors. A stop request (icgp::stop_requested()) ends the replay after
/// the current frame, marked interrupted.
/// Throws std::invalid_argument naming the scenario's robot for a robot that moves what the
/// log does not record (eye-to-hand: the object; grasp: the gripper), and LogError naming the
/// log's line and column for a log that is not a run of this scenario with this seed: a
/// summary of another scenario, a step at another time than the scenario's camera rate
/// gives it, more steps than its stop.max_time, a camera that starts elsewhere.
ReplayResult replay_camera_path(const Scenario& scenario, const RecordedRun& run, unsigned seed,
                                const ReplayOptions& options = {});

/// One cue's fit over a replay.
struct CueSummary {
  std::string cue, camera;
  int frames = 0;     ///< frames the tracker tracked
  int abstained = 0;  ///< of those, frames where the cue had nothing to measure
  /// Over the frames where it measured: its score (mean, least) and noise sigma (mean,
  /// largest; pixels, depth: metres at 1 m). NaN when it never measured.
  double mean_score = 0.0, min_score = 0.0;
  double mean_sigma = 0.0, max_sigma = 0.0;
  double mean_valid_fraction = 0.0;
};

/// A replay in numbers: the tracker's error (mean over the frames with one, as a run's),
/// the run's own on the same steps, and each cue's fit.
struct ReplaySummary {
  int frames = 0, lost = 0, dropped = 0, skipped = 0;
  double mean_track_t = 0.0, max_track_t = 0.0;  ///< metres
  double mean_track_r = 0.0, max_track_r = 0.0;  ///< radians
  double recorded_mean_track_t = 0.0, recorded_mean_track_r = 0.0;  ///< NaN when the log has none
  double median_render_ms = 0.0;
  std::vector<CueSummary> cues;  ///< in the tracker's order
};
ReplaySummary summarise_replay(const ReplayResult& replay);

/// The table: frames, renderer, tracker error (the replay's and the run's), lost frames,
/// then a line per cue.
void print_replay(std::ostream& out, const ReplayResult& replay);
/// replay.csv: one line per frame: time, renderer, tracker error (mm, deg), lost, dropped,
/// skipped, timings, the run's own error, then per cue <cue>_score, <cue>_sigma,
/// <cue>_valid_fraction, <cue>_abstained (NaN on frames the tracker did not track; a cue
/// read on several cameras is <cue>_<camera>_...).
void write_replay_csv(const ReplayResult& replay, const std::string& path);
/// replay.json: {"log", "scenario", "tracker", "renderer", "seed", "frames",
/// "recorded_steps", "lost_frames", "dropped_frames", "skipped_frames", "track_t_mm": {"mean",
/// "max"}, "track_r_deg": {"mean", "max"}, "recorded_track_t_mm": {"mean"},
/// "recorded_track_r_deg": {"mean"}, "median_render_ms", "cues": [{"cue", "camera", "frames",
/// "abstained_frames", "score": {"mean", "min"}, "sigma": {"mean", "max"},
/// "valid_fraction_mean"}], "interrupted"}.
void write_replay_json(const ReplayResult& replay, const std::string& path);

}  // namespace icgp::servo
