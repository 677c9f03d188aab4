// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <string>
#include <vector>

#include "icgp/eval/json_object.h"
#include "icgp/geometry/joint.h"

namespace icgp {

/// The errors of a link's joint values over a tracking run, per free direction of its
/// joint: |estimate − truth| in degrees for a rotation, millimetres for a translation.
class JointEvaluation {
 public:
  explicit JointEvaluation(const Joint& joint);

  /// Records one frame: the tracker's joint values (one per direction) and the ground truth,
  /// nullptr when the frame has none. Throws std::invalid_argument for a wrong count.
  void add(int frame, const std::vector<double>& estimate, const std::vector<double>* truth);

  /// What one direction's errors amount to over the frames with ground truth (NaN: none).
  struct DirectionSummary {
    std::string unit;  ///< "deg" or "mm"
    int frames_with_truth = 0;
    double mean_error = 0.0, max_error = 0.0;
  };
  std::vector<DirectionSummary> summary() const;
  /// {"directions": [{"unit", "frames_with_truth", "mean_error", "max_error"}, ...]}.
  JsonObject to_json() const;
  /// One line per frame: frame, then per direction k its estimate, truth and error
  /// (q<k>, q<k>_truth, q<k>_error, in the direction's unit); empty fields where undefined.
  /// Throws std::runtime_error naming the file when it cannot be written.
  void write_csv(const std::string& path) const;

 private:
  struct Frame {
    int index = 0;
    std::vector<double> estimate, truth, error;  ///< in display units; truth and error empty without truth
  };
  std::vector<double> units_;  ///< display unit per radian or metre, per direction
  std::vector<Frame> frames_;
};

}  // namespace icgp
