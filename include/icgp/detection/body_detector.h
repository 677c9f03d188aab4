// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "icgp/base/frame.h"
#include "icgp/detection/keypoint_model.h"
#include "icgp/detection/mesh_symmetries.h"
#include "icgp/detection/shape_templates.h"
#include "icgp/detection/template_matcher.h"
#include "icgp/detection/texture_alignment.h"
#include "icgp/tracker/tracker.h"
#include "icgp/tracker/tracker_builder.h"
#include "icgp/tracker/tracker_config.h"

namespace icgp {

/// What a detection found in one frame.
struct Detection {
  bool found = false;
  Pose reference_T_body;  ///< the verified pose, in the frame's reference camera
  double quality = 0.0;   ///< the refining cues' quality at that pose
  /// Further poses as good as the found one and clearly different from it: the found pose
  /// turned by each symmetry of the mesh (mesh_symmetries), and other verified poses of
  /// the same quality and appearance. The equivalent views of a symmetric object, not a failure.
  std::vector<Pose> equivalents;
  /// Axes of the body frame about which the found pose may turn freely: a shape round about
  /// them (round_axes) with no texture or colours to fix the turn. No image tells those
  /// turns apart either; whoever has a reason to prefer one turns it (turned_towards).
  std::vector<BodyAxis> free_turn_axes;
  int candidates = 0;  ///< keypoint poses, and template matches above the score threshold after suppression
  int refined = 0;     ///< of those, hypotheses refined by the tracker's cues
  std::string why_not;  ///< when not found: why, in a sentence
};

/// Finds one body in a frame without a given pose (docs/detection.md): gradient templates
/// from its viewpoint models give scored pose candidates, depth (when measured) places and
/// checks them, and the best few are refined by the body's own region and depth cues,
/// coarse to fine, on the same frame. A pose is reported only when that refinement's
/// quality reaches DetectionParams::accept_quality and a strict majority of its cues score
/// it at the tracker's loss bar: "not found" rather than a confident wrong pose.
class BodyDetector {
 public:
  /// The body `body_name` of `mesh` as `config` tracks it with `cameras` (the first camera
  /// with the region cue is searched; a depth camera, when a camera has the depth cue,
  /// places and checks). Its viewpoint models come from the same cache as the tracker's.
  /// `others`: the bodies that may stand in front of it (the tracker's other bodies and
  /// occluders), whose poses each search is given. Throws std::invalid_argument naming the
  /// body when no camera has a colour image.
  BodyDetector(const TrackerConfig& config, const Mesh& mesh, const std::string& body_name,
               const std::vector<CameraCues>& cameras, std::shared_ptr<SceneRenderer> renderer = nullptr,
               std::vector<Body> others = {});
  ~BodyDetector();

  /// Where the `others` are in the frame (reference_T_body by name; those not named stay
  /// where they were last put), so that refinement and appearance leave out what they hide.
  using OtherPoses = std::map<std::string, Pose>;

  /// Searches the whole image over the configured distances.
  Detection detect(const Frame& frame, const OtherPoses& others = {});
  /// Searches near `reference_T_body` (the last trusted pose of a body just lost): a
  /// bounded window in the image, distance and rotation, and fewer hypotheses.
  Detection search_near(const Frame& frame, const Pose& reference_T_body, const OtherPoses& others = {});

  /// Whether the tracker's pose `reference_T_body` of a body found by a search shows what a
  /// wrong pose cannot: its whole silhouette in view (nearly all its contour inside the
  /// image and its mask), the measured depth stepping back beyond that contour (with depth),
  /// and for a body with appearance its render agreeing with the image. `why_not` says
  /// what failed.
  bool confirms(const Frame& frame, const Pose& reference_T_body, const OtherPoses& others, std::string& why_not);

  /// How far apart two poses of the body are in local search windows (search_near's image
  /// radius in sphere radii, and its rotation): at most 1 within one window.
  double windows_apart(const Pose& a, const Pose& b) const;

  const ShapeTemplates& templates() const { return *templates_; }

 private:
  /// A refined hypothesis: its pose, the refining cues' quality there and, for a mesh with
  /// a texture or colours, how well its render agrees with the image.
  struct Hypothesis {
    Pose reference_T_body;
    double quality = 0.0;
    double appearance = 0.0;
    /// A strict majority of the refining cues with evidence score it at the loss bar or
    /// above (most_cues_agree): required of the answer, not of the poses searched from.
    bool cues_agree = false;
  };
  Detection search(const Frame& frame, const SearchWindow& window, int hypotheses, const OtherPoses& others);
  /// The template matches in `window`, best first, at most `hypotheses`: with depth placed
  /// on and checked against the measured surface; whole-image searches coarse to fine.
  std::vector<PoseCandidate> template_candidates(const Frame& frame, const ColorImage& color,
                                                 const SearchWindow& window, int hypotheses, Detection& detection);
  /// Tracker frames on `frame` from `reference_T_body`, coarse to fine, in `stages` starts
  /// (each learning the colour statistics again where the one before ended).
  Hypothesis refine(const Frame& frame, const Pose& reference_T_body, int stages);
  /// Whether a strict majority of the cues with evidence score `result` at the tracker's
  /// loss bar or above.
  bool most_cues_agree(const BodyResult& result) const;
  /// `start` refined; when its quality verifies it, with its appearance, aligned with the
  /// texture of a textured body (docs/detection.md, step 7); nothing otherwise.
  /// `from_texture`: the start is a keypoint pose, which may itself be the better one.
  std::optional<Hypothesis> refine_and_verify(const Frame& frame, const ColorImage& color, const cv::Mat& grey,
                                              const Pose& start, bool from_texture, int stages,
                                              Detection& detection);
  /// What refine_and_verify does after refining: `refined` is the refinement of `start`.
  std::optional<Hypothesis> verify(const Frame& frame, const ColorImage& color, const cv::Mat& grey,
                                   Hypothesis refined, const Pose& start, bool from_texture, int stages,
                                   Detection& detection);
  /// The candidates' refinements whose turns are worth refining when none is confident: the
  /// best that are not alike, best first, kTurnedRefinements of them counting the pose whose
  /// turns search() refines anyway (for flat colours, the best verified one), which is left out.
  std::vector<Pose> poses_to_turn(std::vector<Hypothesis> refined, const std::vector<Hypothesis>& verified) const;
  /// Zero-mean normalised cross-correlation in [-1, 1] of the body's render (its texture
  /// and colours) with the image over the body's pixels; -1 when it is not in view. For a
  /// body of flat colours, 0 when the image's colours do not differ where the render's do.
  double appearance_agreement(const ColorImage& color, const Pose& reference_T_body);
  /// Moves a candidate along its ray so its surface points meet the measured depth; the
  /// share of them that then agree, or a negative value without enough measurements.
  double place_in_depth(const Frame& frame, PoseCandidate& candidate) const;
  /// Whether `turn` (body <- turned body) is one of the body's symmetries, or no turn.
  bool is_symmetry(const Pose& turn) const;
  /// Whether two poses put the body's centre half its bounding radius or more apart.
  bool apart(const Pose& a, const Pose& b) const;
  /// Why the best of `verified` (its front) is not the image's only answer: a rival that
  /// fits alike elsewhere, or for flat colours at a turn that is no symmetry (kRivalQuality);
  /// empty when there is none.
  std::string rival_answer(const std::vector<Hypothesis>& verified) const;
  /// The share of the body's contour points at `reference_T_body` beyond which the
  /// measured depth steps back or vanishes; -1 without depth there.
  double silhouette_support(const Frame& frame, const Pose& reference_T_body) const;
  /// The share of the body's contour points at `reference_T_body` that `color` sees
  /// (inside its image and its mask).
  double share_in_view(const ColorImage& color, const Pose& reference_T_body) const;
  /// The pixels of `color` templates are matched in (CV_8UC1, 0: not; empty: all): those
  /// of its mask that the other bodies do not cover, at their current poses.
  cv::Mat usable_for_templates(const ColorImage& color);
  /// Puts the refiner's occluders where `others` says they are.
  void place_others(const OtherPoses& others);

  DetectionParams params_;
  std::string body_name_;
  std::string color_camera_, depth_camera_;
  std::unique_ptr<Tracker> refiner_;
  std::unique_ptr<ShapeTemplates> templates_;  ///< the configured views and rolls
  std::unique_ptr<TemplateMatcher> matcher_;
  /// Coarser views and rolls for the first pass over the whole image.
  std::unique_ptr<ShapeTemplates> coarse_templates_;
  std::unique_ptr<TemplateMatcher> coarse_matcher_;
  bool appearance_ = false;  ///< the mesh has a texture or colours to compare
  std::vector<Pose> symmetries_;  ///< mesh_symmetries of the body: S with T·S equivalent to T
  /// The half and quarter turns about the body axes (symmetric_turns).
  std::vector<Pose> axis_turns_;
  /// Turns S of a verified pose T whose T·S the shape may fit as well (docs/detection.md,
  /// step 6): the axis turns and, with appearance, a round shape's turns about its axis.
  std::vector<Pose> turns_;
  /// With appearance: the shape is round about an axis (round_axes), so only its texture
  /// or colours fix the turn about it.
  bool round_ = false;
  /// Without appearance: the axes the shape is round about, which nothing fixes the turn about.
  std::vector<BodyAxis> free_turn_axes_;
  /// A textured mesh's keypoints and texture alignment, null for a mesh without texture.
  std::unique_ptr<KeypointModel> keypoints_;
  std::unique_ptr<TextureAlignment> alignment_;
};

}  // namespace icgp
