// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/detection/usual_scores.h"

#include <algorithm>

namespace icgp {

namespace {

/// The weight of a new frame in the running mean: about the last ten frames count.
constexpr double kLearningRate = 0.1;
/// Cues with evidence required of a pose, at most.
constexpr int kMaxCuesRequired = 2;

}  // namespace

bool has_evidence(const ModalityQuality& q) { return !q.abstained && !q.just_started; }

void UsualScores::learn(const BodyResult& trusted) {
  usual_.resize(trusted.modalities.size(), -1.0);
  for (std::size_t i = 0; i < trusted.modalities.size(); ++i) {
    const ModalityQuality& q = trusted.modalities[i];
    if (!has_evidence(q)) continue;
    usual_[i] = usual_[i] < 0.0 ? q.score : (1.0 - kLearningRate) * usual_[i] + kLearningRate * q.score;
  }
}

bool UsualScores::all_agree(const BodyResult& result, const std::vector<std::string>& cue_names, double bar,
                            std::string& why_not) const {
  int with_evidence = 0;
  for (std::size_t i = 0; i < result.modalities.size(); ++i) {
    const ModalityQuality& q = result.modalities[i];
    if (!has_evidence(q)) continue;
    ++with_evidence;
    const double usual = i < usual_.size() ? usual_[i] : -1.0;
    const double required = usual < 0.0 ? bar : std::min(bar, kShareOfUsual * usual);
    if (q.score < required) {
      why_not = "its " + (i < cue_names.size() ? cue_names[i] : std::string("cue")) + " cue scores " +
                std::to_string(q.score) + ", below " + std::to_string(required);
      return false;
    }
  }
  const int usual_cues = static_cast<int>(std::count_if(usual_.begin(), usual_.end(), [](double u) { return u >= 0.0; }));
  if (with_evidence < std::min(usual_cues, kMaxCuesRequired)) {
    why_not = "only " + std::to_string(with_evidence) + " of its cues can see it";
    return false;
  }
  return true;
}

}  // namespace icgp
