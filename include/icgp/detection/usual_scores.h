// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <string>
#include <vector>

#include "icgp/tracker/tracker.h"

namespace icgp {

/// Whether a cue's score on a frame says anything about the pose: it neither abstained nor
/// just started.
bool has_evidence(const ModalityQuality& q);

/// Each cue's usual score while its body is tracked and trusted. A cue that matches little
/// by nature scores little on a right pose too (texture on ViSP's weakly textured castle:
/// 0.2-0.5 beside region and depth at 0.6-0.9), so "every cue agrees with a pose" asks of
/// each cue what it gives on this body, not one bar for all.
class UsualScores {
 public:
  /// Learns from the cue scores of a frame whose pose is trusted (a running mean over about
  /// the last ten frames; cues that abstained or just started are left out).
  void learn(const BodyResult& trusted);
  /// Forgets every score (a body started again at a pose given by the caller).
  void clear() { usual_.clear(); }

  /// Whether every cue with evidence in `result` agrees with its pose: scores at least
  /// min(`bar`, kShareOfUsual of its usual score), and at least as many cues have evidence
  /// as there are cues with a usual score, up to two (a pose that only one cue can see is
  /// one that the others' data contradict by silence). `why_not` names the cue that did not.
  bool all_agree(const BodyResult& result, const std::vector<std::string>& cue_names, double bar,
                 std::string& why_not) const;

  /// A cue agrees at this share of its usual score.
  static constexpr double kShareOfUsual = 0.8;

 private:
  std::vector<double> usual_;  ///< per cue, in the tracker's order; negative: none yet
};

}  // namespace icgp
