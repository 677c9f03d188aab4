// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/eval/joint_evaluation.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <stdexcept>

namespace icgp {

JointEvaluation::JointEvaluation(const Joint& joint) {
  for (const JointDirection& d : joint.directions)
    units_.push_back(d.kind == JointDirection::Kind::kRotation ? 180.0 / kPi : 1000.0);
}

void JointEvaluation::add(int frame, const std::vector<double>& estimate, const std::vector<double>* truth) {
  const std::size_t n = units_.size();
  if (estimate.size() != n || (truth && truth->size() != n))
    throw std::invalid_argument("JointEvaluation: frame " + std::to_string(frame) + ": expected " + std::to_string(n) +
                                " joint values");
  Frame f;
  f.index = frame;
  for (std::size_t k = 0; k < n; ++k) {
    f.estimate.push_back(estimate[k] * units_[k]);
    if (!truth) continue;
    f.truth.push_back((*truth)[k] * units_[k]);
    f.error.push_back(std::abs(f.estimate[k] - f.truth[k]));
  }
  frames_.push_back(std::move(f));
}

std::vector<JointEvaluation::DirectionSummary> JointEvaluation::summary() const {
  std::vector<DirectionSummary> directions;
  for (std::size_t k = 0; k < units_.size(); ++k) {
    DirectionSummary d;
    d.unit = units_[k] == 1000.0 ? "mm" : "deg";
    double sum = 0.0;
    for (const Frame& f : frames_) {
      if (f.error.empty()) continue;
      ++d.frames_with_truth;
      sum += f.error[k];
      d.max_error = std::max(d.max_error, f.error[k]);
    }
    if (d.frames_with_truth == 0) d.mean_error = d.max_error = std::numeric_limits<double>::quiet_NaN();
    else d.mean_error = sum / d.frames_with_truth;
    directions.push_back(d);
  }
  return directions;
}

JsonObject JointEvaluation::to_json() const {
  std::vector<JsonObject> directions;
  for (const DirectionSummary& d : summary())
    directions.push_back(JsonObject()
                             .add("unit", d.unit)
                             .add("frames_with_truth", d.frames_with_truth)
                             .add("mean_error", d.mean_error)
                             .add("max_error", d.max_error));
  return JsonObject().add("directions", std::move(directions));
}

void JointEvaluation::write_csv(const std::string& path) const {
  const std::filesystem::path file(path);
  if (file.has_parent_path()) std::filesystem::create_directories(file.parent_path());
  std::ofstream out(file);
  out.precision(10);
  out << "frame";
  for (std::size_t k = 0; k < units_.size(); ++k) {
    const std::string q = "q" + std::to_string(k);
    out << ',' << q << ',' << q << "_truth," << q << "_error";
  }
  out << '\n';
  for (const Frame& f : frames_) {
    out << f.index;
    for (std::size_t k = 0; k < units_.size(); ++k) {
      out << ',' << f.estimate[k] << ',';
      if (!f.truth.empty()) out << f.truth[k] << ',' << f.error[k];
      else out << ',';
    }
    out << '\n';
  }
  if (!out) throw std::runtime_error("cannot write CSV file '" + path + "'");
}

}  // namespace icgp
