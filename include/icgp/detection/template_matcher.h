// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <array>
#include <functional>
#include <optional>
#include <optional>
#include <string>
#include <vector>

#include "icgp/base/frame.h"
#include "icgp/detection/orientation_responses.h"
#include "icgp/detection/ray_depth.h"
#include "icgp/detection/shape_templates.h"

namespace icgp {

/// A pose the templates suggest, before any refinement.
struct PoseCandidate {
  Pose camera_T_body;  ///< in the colour camera the templates were matched in
  double score = 0.0;  ///< share of the template's contour points the image answers, [0, 1]
  int template_index = 0;
  double distance = 0.0;  ///< metres to the sphere centre
  /// What a CandidateCheck found for it (the detector: depth agreement), for ranking.
  double support = 0.0;
};

/// Checks a candidate before suppression, and may move it (the detector places it in the
/// measured depth): false drops it.
using CandidateCheck = std::function<bool(PoseCandidate&)>;

/// Where to look: the whole image over a range of distances, or near a pose (a body just
/// lost), within a radius in the image, a distance ratio and a rotation.
struct SearchWindow {
  double min_distance = 0.25, max_distance = 1.5;
  /// Near a pose: the pose, and how far from it to look.
  std::optional<Pose> near;
  double radius_px = 0.0;
  double max_rotation = 0.0;  ///< radians
  /// The measured depth along the camera's rays, when there is one: a template is not
  /// scored where the surface is not at its distance (the body's front lies between its
  /// centre's distance and one radius nearer, within a distance step).
  const RayDepth* depth = nullptr;
};

/// One image's orientation responses at pyramid levels 0..kLevels-1 (2^L times smaller),
/// each computed the first time a search asks for it, so that several searches of one
/// frame (coarse views, then fine ones near their matches) share them. Pixels the image's
/// mask excludes answer nothing.
class OrientationPyramid {
 public:
  static constexpr int kLevels = 4;
  struct Level {
    Intrinsics intrinsics;
    OrientationResponses responses;
  };

  explicit OrientationPyramid(const ColorImage& color) : color_(color) {}
  const ColorImage& color() const { return color_; }
  const Level& level(int L);

 private:
  const cv::Mat& image(int L);

  const ColorImage& color_;
  std::array<std::optional<Level>, kLevels> levels_;
  std::array<cv::Mat, kLevels> images_;
};

/// Gradient template matching (docs/detection.md): every template at every distance step
/// over every grid position of the image level where its contour spans a few dozen pixels,
/// scored by the share of its contour points whose orientation the image answers. Costs
/// grow with the image area the smallest templates need and the number of templates.
class TemplateMatcher {
 public:
  /// The step between searched distances: a template a step off in scale still matches
  /// within the spread radius at the level it is matched on.
  static constexpr double kDistanceStep = 1.15;
  /// Template matches kept from one search, best first, before they are checked and
  /// suppressed: enough that a cluttered background's many good matches (a painted
  /// rectangle answers a box's template fully) leave room for the object's.
  static constexpr int kMaxMatches = 3000;

  explicit TemplateMatcher(const ShapeTemplates& templates) : templates_(templates) {}

  /// At most `limit` candidates of the pyramid's image scoring at least `min_score` that
  /// pass `check` (when given), best first, distinct (no two at the same place, distance
  /// and rotation). `why_none` receives the reason when no distance of the window could be
  /// searched (the object would be too small or larger than the image).
  std::vector<PoseCandidate> match(OrientationPyramid& pyramid, const SearchWindow& window, double min_score, int limit,
                                   const CandidateCheck& check = nullptr, std::string* why_none = nullptr);


 private:
  const ShapeTemplates& templates_;
  std::vector<std::uint16_t> scores_;
};

}  // namespace icgp
