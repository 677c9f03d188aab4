// SPDX-License-Identifier: GPL-2.0-or-later
#include "servo_replay_command.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>

#include "commands.h"
#include "eta_progress.h"
#include "icgp/servo/recorded_run.h"
#include "icgp/servo/servo_replay.h"

namespace icgp::app {
namespace {

/// A progress line at most this often (seconds of wall time), and after the last frame: an
/// OpenGL replay makes tens of frames a second, a Cycles one a frame in seconds.
constexpr double kProgressInterval = 2.0;

/// "replay t 0.37 s: tracker 0.842 mm 0.120 deg [12/240, elapsed 30 s, ETA 570 s]" on stderr.
class ReplayProgress {
 public:
  ReplayProgress(std::size_t total, bool quiet) : eta_(static_cast<long long>(total)), quiet_(quiet) {}

  void frame_done(const servo::ReplayFrame& frame, std::size_t done, std::size_t total) {
    const std::string bracket = eta_.done();
    const auto now = std::chrono::steady_clock::now();
    if (quiet_ || (done < total && std::chrono::duration<double>(now - last_).count() < kProgressInterval)) return;
    last_ = now;
    char error[64] = "no estimate yet";
    if (!std::isnan(frame.track_t))
      std::snprintf(error, sizeof error, "%.3f mm %.3f deg", 1e3 * frame.track_t, frame.track_r / servo::kDegree);
    std::fprintf(stderr, "replay t %.2f s: tracker %s%s %s\n", frame.time, error, frame.lost ? ", LOST" : "",
                 bracket.c_str());
  }

 private:
  EtaProgress eta_;
  bool quiet_;
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

}  // namespace

void run_servo_replay(const servo::Scenario& scenario, const std::string& log, std::optional<unsigned> seed,
                      const std::string& out, bool quiet) {
  const servo::RecordedRun run = servo::read_recorded_run(log);
  const unsigned replay_seed = servo::replay_seed(run, scenario, seed);
  ReplayProgress progress(run.steps.size(), quiet);
  servo::ReplayOptions options;
  options.on_frame = [&progress](const servo::ReplayFrame& frame, std::size_t done, std::size_t total) {
    progress.frame_done(frame, done, total);
  };
  const servo::ReplayResult replay = servo::replay_camera_path(scenario, run, replay_seed, options);
  servo::print_replay(std::cout, replay);
  const std::filesystem::path folder(out);
  const std::string csv = (folder / "replay.csv").string(), json = (folder / "replay.json").string();
  servo::write_replay_csv(replay, csv);
  servo::write_replay_json(replay, json);
  std::cout << "wrote " << csv << ", " << json << "\n";
  if (replay.interrupted)
    throw CommandOutcome(kExitInterrupted, "interrupted: " + std::to_string(replay.frames.size()) + " of " +
                                               std::to_string(replay.recorded_steps) + " steps replayed, in " + csv +
                                               " and " + json);
}

}  // namespace icgp::app
