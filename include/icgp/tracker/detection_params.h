// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

namespace icgp {

/// How a body is found without a given pose, and found again after a loss
/// (docs/detection.md). Templates come from the body's region viewpoint models; every
/// hypothesis is refined by the tracker's own region (and depth) cues and accepted only
/// when their quality verifies it.
struct DetectionParams {
  /// Search again when a body is reported lost: near the last trusted pose every frame,
  /// over the whole image every `global_search_interval` frames.
  bool recovery = true;
  int global_search_interval = 5;
  /// Template views: the directions of an icosphere of this many subdivisions
  /// (2: 162 views, about 15 degrees apart), each at in-plane rotations `roll_step_deg` apart.
  int view_divides = 2;
  double roll_step_deg = 20.0;
  /// The distances searched when no depth gives them (metres, camera to the body's centre).
  double min_distance = 0.25;
  double max_distance = 1.5;
  /// Template points per view (contour points of the region models).
  int template_points = 40;
  /// Best template matches refined by the tracker's cues, in rank order until one fits
  /// confidently; the best is accepted when its quality reaches `accept_quality`.
  int hypotheses = 20;
  double accept_quality = 0.6;
};

}  // namespace icgp
