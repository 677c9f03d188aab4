// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/detection/body_detector.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <stdexcept>
#include <tuple>

#include <Eigen/Geometry>
#include <opencv2/imgproc.hpp>

#include "icgp/detection/mesh_symmetries.h"
#include "icgp/detection/usual_scores.h"
#include "icgp/detection/verified_ranking.h"
#include "icgp/modality/depth_modality.h"
#include "icgp/modality/region_modality.h"

namespace icgp {
namespace {

/// Template matches below this share of answered contour points are not candidates.
constexpr double kMinTemplateScore = 0.55;
/// The whole image is searched with views and rolls this many times coarser, then the
/// fine templates near each coarse match: within this image radius (sphere radii, at
/// least kFineMinRadiusPx), a distance step and this rotation (the coarse views' spacing).
constexpr int kCoarseViewDivides = 1;
constexpr double kCoarseRollFactor = 1.5;
constexpr double kFineRadiusSpheres = 0.3;
constexpr double kFineMinRadiusPx = 8.0;
constexpr double kFineRotation = 30.0 * kPi / 180.0;
/// Distinct candidates ranked (template score and depth support) per hypothesis refined.
constexpr int kCandidatesRanked = 4;
/// A candidate whose surface points mostly disagree with the measured depth is dropped
/// before refinement (with enough measurements to say so).
constexpr double kMinDepthAgreement = 0.3;
/// Tracker frames run on the detection's frame to refine a hypothesis: the first starts at
/// the region cue's coarsest scale, so three pull a candidate in from tens of pixels.
constexpr int kRefinementRounds = 3;
constexpr int kRefinementStages = 2;
/// Near a lost pose: the image radius (in sphere radii, at least kNearMinRadiusPx), the
/// distance ratio and rotation searched, and the hypotheses refined: a small part of a
/// whole-image search, which is left to every few frames (DetectionParams).
constexpr double kNearRadiusSpheres = 1.5;
constexpr double kNearMinRadiusPx = 40.0;
constexpr double kNearDistanceRatio = 1.3;
constexpr double kNearRotation = 35.0 * kPi / 180.0;
constexpr int kNearHypotheses = 2;
/// With depth, the share of contour points beyond which the measured surface must step
/// back (or vanish): a body stands out of its surroundings, a picture of it does not.
constexpr double kMinSilhouetteSupport = 0.4;
/// Pixels outside the projected contour where that step is looked for.
constexpr double kSilhouetteOffsetPx = 5.0;
/// A pose found far from where the body was trusted is confirmed only with nearly all of its
/// contour in view: a part of a silhouette matches far more wrong poses than the whole.
constexpr double kMinShareInView = 0.9;
/// For a body with appearance, a refined hypothesis of this quality ends the refinement of
/// further candidates (the turns compared by appearance find its symmetric twin); a plain
/// shape refines them all, since a small part (a mug's handle) tells them apart.
constexpr double kConfidentQuality = 0.85;
/// Without depth the fit of the contour does not tell the body from clutter shaped like it:
/// on the sweep's grey labelled can, patches of clutter taken for the can 0.5 m further
/// away fitted at quality 0.82-0.87 and the can itself at 0.61, while their renders
/// correlated with the image at 0.66-0.82 against the can's 0.985-0.988. There a pose is
/// verified only when it looks this much like the image (the first such ends the search),
/// and the verified poses are ranked by their look alone.
constexpr double kMinAppearanceWithoutDepth = 0.9;
/// Verified poses within this quality of the best and this rotation apart are equivalent.
constexpr double kEquivalentQuality = 0.05;
constexpr double kEquivalentRotation = 10.0 * kPi / 180.0;
/// A verified pose within this quality (and, with appearance, this agreement) of the best
/// is a rival answer: elsewhere, a look-alike of the body is in view; at the same place, a
/// turn that is no symmetry (flat colours) leaves the orientation to chance. A mug among
/// cans of its colour fitted its own place and a can's 0.00-0.05 apart (`icgp bench
/// --detect`: 20 far-off poses); refinements of one pose from different starts spread by
/// up to 0.03.
constexpr double kRivalQuality = 0.1;

/// The other bodies are rendered this many times smaller than the image to leave their
/// silhouettes out of template matching.
constexpr int kOthersRenderScale = 4;

/// Side of the focused render the appearance of a hypothesis is compared in.
constexpr int kAppearanceRenderSize = 128;
/// Verified poses this far below the best quality still compete on appearance: a pose of
/// the right shape turned wrong fits the contour and the depth as well as the right one.
constexpr double kAppearanceQualityMargin = 0.25;
/// Renders that correlate with the image within this of each other look alike: the fit
/// ranks them. On the two-colour box in the realistic servo cell a pose 14 mm and a quarter
/// turn off fitted at 0.63 and looked 0.944, the right pose fitted at 0.84 and looked 0.928.
constexpr double kAlikeAppearance = 0.05;

/// Whether the mesh tells its views apart beyond its shape: a texture, or parts of
/// different colours.
bool has_appearance(const Mesh& mesh) {
  for (const MeshPart& part : mesh.parts)
    if (!part.material.texture_bgr.empty() ||
        !part.material.diffuse_rgb.isApprox(mesh.parts.front().material.diffuse_rgb, 1e-3f))
      return true;
  return false;
}

/// A body with appearance is verified only when its render correlates at least this much
/// with the image (NCC). In `icgp bench --detect` the right poses of the textured box, the
/// labelled can and the two-colour box scored 0.69-0.99 (0.79 with a bar across a third of
/// the box); what the detectors of those three found in frames without their object (other
/// objects, clutter) scored 0.05-0.61, and the can turned 11-27 degrees 0.33-0.67. Without
/// this check, with depth, such poses passed on their shape alone.
constexpr double kMinAppearance = 0.65;
/// The appearance check climbs to the best correlation over image shifts of up to this many
/// pixels each way: a calibrated RGB-D sensor registers its colour to its depth within a few
/// pixels (each camera's principal point within 1-2 px, the extrinsics within a millimetre
/// and a few tenths of a degree), and a pose fitted to depth and contour leaves the texture
/// that far off. Without it, a right pose of the textured box scored 0.55 (0.93 four pixels
/// down) in 1 of 10 servo trials with such errors (the realistic profile, docs/servo.md).
constexpr int kAppearanceShiftPx = 6;
/// A turned pose is refined only when it looks this much more like the image (NCC).
constexpr double kAppearanceGain = 0.1;

/// The turns that map a box, a cylinder or a cube onto itself: 180 degrees about each
/// axis of the body frame and 90 degrees either way about each, about the sphere centre
/// `c`. From a verified pose T they give the poses T·S an object of such a shape could
/// equally have.
std::vector<Pose> symmetric_turns(const Eigen::Vector3d& c) {
  std::vector<Pose> turns;
  for (int axis = 0; axis < 3; ++axis)
    for (const double angle : {kPi, kPi / 2.0, -kPi / 2.0}) {
      const Eigen::Matrix3d turn = Eigen::AngleAxisd(angle, Eigen::Vector3d::Unit(axis)).toRotationMatrix();
      turns.emplace_back(turn, c - turn * c);
    }
  return turns;
}

/// Turns about a round shape's axis compared by appearance: a 15-degree step leaves the
/// best of them within 7.5 degrees, which the texture alignment pulls in.
constexpr double kRoundTurnStep = 15.0 * kPi / 180.0;

/// How many of the best refinements are turned when no candidate was confident.
constexpr std::size_t kTurnedRefinements = 2;

/// The hypothesis of `hypotheses` (not empty) that fits best.
template <typename Hypothesis>
const Hypothesis& best_fitting(const std::vector<Hypothesis>& hypotheses) {
  return *std::max_element(hypotheses.begin(), hypotheses.end(),
                           [](const Hypothesis& a, const Hypothesis& b) { return a.quality < b.quality; });
}

/// The refining tracker: the body alone, with its region cue and, where the rig has one,
/// its depth cue; texture is left out, since its keyframe would be taken at the unrefined pose.
TrackerConfig refinement_config(const TrackerConfig& config) {
  TrackerConfig refine = config;
  refine.modalities = {cue::kRegion};
  if (has_cue(config.modalities, cue::kDepth)) refine.modalities.push_back(cue::kDepth);
  refine.bodies.clear();
  return refine;
}

/// Image pixels around a near search's templates that their probes and a level's grid reach.
constexpr double kWindowMarginPx = 32.0;

/// The part of `color` a search near a pose reads: the window's centre, its radius, the
/// largest template's radius at the window's nearest distance, and a margin for the
/// template's probes and the gradients' spread; the intrinsics moved to the part. None when
/// that part lies wholly outside the image (a body last trusted out of view).
std::optional<ColorImage> window_crop(const ColorImage& color, const SearchWindow& window, const Sphere& sphere) {
  const Intrinsics& K = color.intrinsics;
  const Eigen::Vector3d centre = *window.near * sphere.centre;
  if (centre.z() <= 0.0) return color;
  const Eigen::Vector2d px = K.project(centre);
  const double half = window.radius_px + K.fu * sphere.radius / window.min_distance + kWindowMarginPx;
  if (px.x() + half <= 0.0 || px.y() + half <= 0.0 || px.x() - half >= K.width || px.y() - half >= K.height)
    return std::nullopt;
  const int x0 = std::clamp(static_cast<int>(std::floor(px.x() - half)), 0, K.width - 1);
  const int y0 = std::clamp(static_cast<int>(std::floor(px.y() - half)), 0, K.height - 1);
  const int x1 = std::clamp(static_cast<int>(std::ceil(px.x() + half)), x0 + 1, K.width);
  const int y1 = std::clamp(static_cast<int>(std::ceil(px.y() + half)), y0 + 1, K.height);
  ColorImage crop = color;
  crop.image = color.image(cv::Rect(x0, y0, x1 - x0, y1 - y0));
  crop.intrinsics.pu -= x0;
  crop.intrinsics.pv -= y0;
  crop.intrinsics.width = x1 - x0;
  crop.intrinsics.height = y1 - y0;
  if (!color.mask.all_pixels()) crop.mask.mask = color.mask.mask(cv::Rect(x0, y0, x1 - x0, y1 - y0));
  return crop;
}

/// `value` as printf's %g writes it: 0.65, not 0.650000.
std::string shortest(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

/// A region of flat colour counts in the colour check when it covers this share of the
/// body's rendered pixels.
constexpr double kMinColourRegionShare = 0.1;
/// Where a body's flat colours differ, the image's must too: the squared distance of the
/// image's mean chromaticities on either side must exceed this many times the sum of
/// their variances. The two-colour box at its true poses: 5.8-370 (`icgp bench --detect`,
/// 31 frames of plain, occluded and distractor scenes); on the red mug and on look-alikes
/// painted its mean colour, where its detector had found it: 0.00-1.5. Chromaticity is
/// blind to the camera's gain and to shading.
constexpr double kMinColourSeparation = 2.0;

/// The image's chromaticity under each flat colour of a render: which colour a pixel has in
/// the render is told by its chromaticity, which Lambertian shading leaves unchanged.
class ChromaByRenderedColour {
 public:
  void add(const cv::Vec3b& rendered, const cv::Vec3b& image) {
    const double rendered_sum = rendered[0] + rendered[1] + rendered[2];
    if (rendered_sum < kMinRenderedSum) return;  // too dark for a chromaticity
    const Eigen::Vector3d key_chroma = Eigen::Vector3d(rendered[0], rendered[1], rendered[2]) / rendered_sum;
    const int bin = static_cast<int>(key_chroma.x() * kBins) * (kBins + 1) + static_cast<int>(key_chroma.y() * kBins);
    const double image_sum = image[0] + image[1] + image[2] + 1.0;
    const Eigen::Vector3d chroma = Eigen::Vector3d(image[0], image[1], image[2]) / image_sum;
    Group& g = groups_[bin];
    ++g.count;
    g.rendered_sum += key_chroma;
    g.sum += chroma;
    g.sum_squares += chroma.squaredNorm();
    ++pixels_;
  }

  /// Whether the image's colours differ, by kMinColourSeparation, under the largest
  /// rendered colour and the largest that differs from it; true when the render shows no
  /// two colours large enough. One colour split between two bins is not two colours.
  bool differ_as_rendered() const {
    std::vector<const Group*> large;
    for (const Group& g : groups_)
      if (g.count > 0 && g.count >= kMinColourRegionShare * pixels_) large.push_back(&g);
    std::sort(large.begin(), large.end(), [](const Group* a, const Group* b) { return a->count > b->count; });
    const auto other = std::find_if(large.begin(), large.end(), [&](const Group* g) {
      return (g->rendered_mean() - large.front()->rendered_mean()).norm() >= kMinRenderedDifference;
    });
    if (other == large.end()) return true;
    const Group& a = *large.front();
    const Group& b = **other;
    return (a.mean() - b.mean()).squaredNorm() > kMinColourSeparation * (a.variance() + b.variance());
  }

 private:
  static constexpr double kMinRenderedSum = 30.0;
  static constexpr int kBins = 10;
  /// Rendered chromaticities this far apart are two colours (a bin is 0.1 wide).
  static constexpr double kMinRenderedDifference = 0.1;
  struct Group {
    int count = 0;
    Eigen::Vector3d rendered_sum = Eigen::Vector3d::Zero();
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    double sum_squares = 0.0;
    Eigen::Vector3d rendered_mean() const { return rendered_sum / count; }
    Eigen::Vector3d mean() const { return sum / count; }
    double variance() const { return std::max(0.0, sum_squares / count - mean().squaredNorm()); }
  };
  /// By the rendered chromaticity's blue and green components, kBins + 1 bins each (a
  /// component of 1 is a bin of its own): fixed, so a check allocates nothing per pixel.
  std::array<Group, (kBins + 1) * (kBins + 1)> groups_{};
  int pixels_ = 0;
};

}  // namespace

BodyDetector::BodyDetector(const TrackerConfig& config, const Mesh& mesh, const std::string& body_name,
                           const std::vector<CameraCues>& cameras, std::shared_ptr<SceneRenderer> renderer,
                           std::vector<Body> others)
    : params_(config.detection), body_name_(body_name) {
  for (const CameraCues& c : cameras) {
    if ((c.types & visp_type::kEdge) && color_camera_.empty()) color_camera_ = c.camera;
    if ((c.types & visp_type::kDepth) && depth_camera_.empty() && has_cue(config.modalities, cue::kDepth))
      depth_camera_ = c.camera;
  }
  if (color_camera_.empty())
    throw std::invalid_argument("detection of body '" + body_name +
                                "': no camera has a colour or grey image (the region cue's camera), and the templates "
                                "are matched in one");
  if (!(params_.min_distance < params_.max_distance))
    throw std::invalid_argument("detection of body '" + body_name + "': detection.min_distance (" +
                                std::to_string(params_.min_distance) + " m) must be below detection.max_distance (" +
                                std::to_string(params_.max_distance) + " m)");
  refiner_ = build_tracker(refinement_config(config), mesh, body_name, cameras, std::move(renderer));
  for (Body& other : others) refiner_->add_occluder(std::move(other));
  std::vector<const ViewpointModel*> region_models;
  const ViewpointModel* depth_model = nullptr;
  for (const Modality* m : refiner_->modalities(body_name)) {
    if (const auto* region = dynamic_cast<const RegionModality*>(m)) region_models.push_back(&region->model());
    if (const auto* depth = dynamic_cast<const DepthModality*>(m)) depth_model = &depth->model();
  }
  // The fine templates are searched near the coarse ones' matches and near a lost pose
  // only: their views are made as those searches reach them.
  templates_ = std::make_unique<ShapeTemplates>(mesh, region_models, depth_model, params_.view_divides,
                                                params_.roll_step_deg, params_.template_points,
                                                ShapeTemplates::Filling::kOnDemand);
  matcher_ = std::make_unique<TemplateMatcher>(*templates_);
  coarse_templates_ = std::make_unique<ShapeTemplates>(
      mesh, region_models, depth_model, std::min(params_.view_divides, kCoarseViewDivides),
      params_.roll_step_deg * kCoarseRollFactor, params_.template_points);
  coarse_matcher_ = std::make_unique<TemplateMatcher>(*coarse_templates_);
  appearance_ = has_appearance(mesh);
  symmetries_ = mesh_symmetries(mesh);
  axis_turns_ = symmetric_turns(templates_->sphere().centre);
  turns_ = axis_turns_;
  // A round shape (a labelled can) fits its contour and depth at any turn about its axis;
  // with appearance, those turns are compared too (without, they are its symmetries).
  const std::vector<BodyAxis> round_axes_of_shape = round_axes(mesh);
  if (appearance_) {
    const std::vector<Pose> round_turns = turns_about(round_axes_of_shape, kRoundTurnStep);
    round_ = !round_turns.empty();
    turns_.insert(turns_.end(), round_turns.begin(), round_turns.end());
  } else {
    free_turn_axes_ = round_axes_of_shape;
  }
  if (has_texture(mesh)) {
    auto keypoints =
        std::make_unique<KeypointModel>(render_training_views(refiner_->renderer(), refiner_->body(body_name)));
    if (!keypoints->empty()) keypoints_ = std::move(keypoints);
    alignment_ = std::make_unique<TextureAlignment>(refiner_->renderer(), refiner_->body(body_name));
  }
}

BodyDetector::~BodyDetector() = default;

Detection BodyDetector::detect(const Frame& frame, const OtherPoses& others) {
  SearchWindow window;
  window.min_distance = params_.min_distance;
  window.max_distance = params_.max_distance;
  return search(frame, window, params_.hypotheses, others);
}

Detection BodyDetector::search_near(const Frame& frame, const Pose& reference_T_body, const OtherPoses& others) {
  const ColorImage* color = frame.find_color(color_camera_);
  SearchWindow window;
  if (color) {
    const Pose camera_T_body = color->camera_T_reference * reference_T_body;
    const double distance = (camera_T_body * templates_->sphere().centre).norm();
    window.near = camera_T_body;
    window.min_distance = distance / kNearDistanceRatio;
    window.max_distance = distance * kNearDistanceRatio;
    window.radius_px = std::max(kNearMinRadiusPx, kNearRadiusSpheres * color->intrinsics.fu *
                                                      templates_->sphere().radius / distance);
    window.max_rotation = kNearRotation;
  }
  return search(frame, window, kNearHypotheses, others);
}

double BodyDetector::silhouette_support(const Frame& frame, const Pose& reference_T_body) const {
  const DepthImage* depth = depth_camera_.empty() ? nullptr : frame.find_depth(depth_camera_);
  if (!depth || !depth->delivered()) return -1.0;
  const Pose depth_T_body = depth->camera_T_reference * reference_T_body;
  const ShapeTemplates::View& view = templates_->closest_view(depth_T_body);
  const double margin = std::max(0.02, 0.2 * templates_->sphere().radius);
  int stepping = 0, seen = 0;
  for (const ShapeTemplates::ViewContourPoint& p : view.contour) {
    const Eigen::Vector3d X = depth_T_body * p.position.cast<double>();
    const Eigen::Vector3d N = depth_T_body.rotation() * p.normal.cast<double>();
    if (X.z() <= 0.0) continue;
    const Eigen::Vector2d uv = depth->intrinsics.project(X);
    const Eigen::Vector2d beside = depth->intrinsics.project(Eigen::Vector3d(X + 1e-3 * N));
    const Eigen::Vector2d outwards = (beside - uv).normalized();
    if (!outwards.allFinite()) continue;
    const Eigen::Vector2d out = uv + kSilhouetteOffsetPx * outwards;
    const int col = static_cast<int>(std::lround(out.x())), row = static_cast<int>(std::lround(out.y()));
    if (col < 0 || row < 0 || col >= depth->depth.cols || row >= depth->depth.rows) continue;
    ++seen;
    const float z = depth->at(row, col);
    stepping += !(z > 0.f) || z > X.z() + margin;
  }
  return seen >= 4 ? static_cast<double>(stepping) / seen : -1.0;
}

double BodyDetector::place_in_depth(const Frame& frame, PoseCandidate& candidate) const {
  const DepthImage* depth = depth_camera_.empty() ? nullptr : frame.find_depth(depth_camera_);
  const ColorImage* color = frame.find_color(color_camera_);
  if (!depth || !depth->delivered() || !color) return -1.0;
  const ShapeTemplates::View& view = templates_->closest_view(candidate.camera_T_body);
  if (view.surface.empty()) return -1.0;
  // Depth camera <- colour camera.
  const Pose depth_T_color = depth->camera_T_reference * color->camera_T_reference.inverse();
  const Eigen::Vector3d ray = (candidate.camera_T_body * templates_->sphere().centre).normalized();
  auto differences = [&](const Pose& camera_T_body) {
    std::vector<double> d;
    const Pose depth_T_body = depth_T_color * camera_T_body;
    for (const Eigen::Vector3f& p : view.surface) {
      const Eigen::Vector3d X = depth_T_body * p.cast<double>();
      if (X.z() <= 0.0) continue;
      const Eigen::Vector2d uv = depth->intrinsics.project(X);
      const int col = static_cast<int>(std::lround(uv.x())), row = static_cast<int>(std::lround(uv.y()));
      if (col < 0 || row < 0 || col >= depth->depth.cols || row >= depth->depth.rows) continue;
      const float z = depth->at(row, col);
      if (z > 0.f) d.push_back(z - X.z());
    }
    return d;
  };
  std::vector<double> d = differences(candidate.camera_T_body);
  if (d.size() < view.surface.size() / 4 || d.size() < 4) return -1.0;
  std::nth_element(d.begin(), d.begin() + d.size() / 2, d.end());
  const double shift = d[d.size() / 2];
  // Along the ray, the centre's depth changes by ray.z per metre.
  const Pose moved(candidate.camera_T_body.rotation(), candidate.camera_T_body.translation() + shift / ray.z() * ray);
  d = differences(moved);
  const double tolerance = std::max(0.01, 0.1 * templates_->sphere().radius);
  const double agreeing =
      static_cast<double>(std::count_if(d.begin(), d.end(), [&](double x) { return std::abs(x) < tolerance; }));
  candidate.camera_T_body = moved;
  candidate.distance = (moved * templates_->sphere().centre).norm();
  return agreeing / static_cast<double>(view.surface.size());
}

bool BodyDetector::most_cues_agree(const BodyResult& result) const {
  // The body's quality is the median of its cues' scores; of an even count, the mean of the
  // middle two, so with two cues one that fits a wrong pose carries one that refutes it. A
  // two-colour box turned a quarter about its long axis lies on the real box's faces: depth
  // fitted it at 0.92 and the region cue refuted it at 0.44 (0.56-0.69 at the right pose),
  // and it was verified at 0.68. The pose a detection answers has a strict majority of the
  // cues with evidence at the tracker's own loss bar or above: both of two, two of three.
  // One cue that scores little by nature (a thin colour region of the labelled can, 0.3 at
  // its right pose) is still outvoted.
  const double bar = refiner_->params().quality_threshold;
  int with_evidence = 0, agreeing = 0;
  for (const ModalityQuality& q : result.modalities) {
    if (!has_evidence(q)) continue;
    ++with_evidence;
    agreeing += q.score >= bar;
  }
  return 2 * agreeing > with_evidence;
}

BodyDetector::Hypothesis BodyDetector::refine(const Frame& frame, const Pose& reference_T_body, int stages) {
  refiner_->body(body_name_).reference_T_body = reference_T_body;
  BodyResult result;
  // The colour statistics are learnt where the cues start: a second start at the refined
  // pose learns them again from the body's own pixels.
  try {
    for (int stage = 0; stage < stages; ++stage) {
      refiner_->start(frame);
      for (int round = 0; round < kRefinementRounds; ++round) result = refiner_->track(frame).front();
    }
  } catch (const std::runtime_error&) {
    // A cue that cannot start at this pose (the body out of view): not verified.
    return {reference_T_body, 0.0, 0.0};
  }
  // Where depth is measured, a verified body also stands out of its surroundings there.
  const double silhouette = silhouette_support(frame, result.reference_T_body);
  const bool stands_out = silhouette < 0.0 || silhouette >= kMinSilhouetteSupport;
  return {result.reference_T_body, stands_out ? result.quality : 0.0, 0.0, most_cues_agree(result)};
}

double BodyDetector::appearance_agreement(const ColorImage& color, const Pose& reference_T_body) {
  std::optional<RenderRequest> request =
      focused_render_request(color.camera, color.intrinsics, color.camera_T_reference, reference_T_body,
                             templates_->sphere(), kAppearanceRenderSize);
  if (!request) return -1.0;
  request->targets = kRenderDepth | kRenderColor | kRenderIds;
  Body& body = refiner_->body(body_name_);
  body.reference_T_body = reference_T_body;
  std::vector<const Body*> shown{&body};
  for (const Body* other : refiner_->occluders()) shown.push_back(other);
  Renders renders;
  refiner_->renderer().render(shown, {*request}, renders);
  const FocusedRender& render = renders.at(*request);
  const std::uint8_t id = renders.id(body_name_);
  cv::Mat rendered_grey, image_grey;
  cv::cvtColor(render.color, rendered_grey, cv::COLOR_BGR2GRAY);
  if (color.image.channels() == 3)
    cv::cvtColor(color.image, image_grey, cv::COLOR_BGR2GRAY);
  else
    image_grey = color.image;
  // Zero-mean normalised cross-correlation over the body's pixels (blind to the gain and
  // offset between the renderer's shading and the camera), the best within
  // kAppearanceShiftPx of where the pose puts them.
  const Intrinsics& crop = render.intrinsics;
  const Intrinsics& K = color.intrinsics;
  // The body's pixels of the render and where they fall in the image.
  struct Sample {
    int x, y, u, v;
  };
  std::vector<Sample> samples;
  for (int y = 0; y < render.depth.rows; ++y)
    for (int x = 0; x < render.depth.cols; ++x) {
      if (render.ids.at<std::uint8_t>(y, x) != id) continue;  // background, or another body in front
      samples.push_back({x, y, static_cast<int>(std::lround((x - crop.pu) / crop.fu * K.fu + K.pu)),
                         static_cast<int>(std::lround((y - crop.pv) / crop.fv * K.fv + K.pv))});
    }
  // Zero-mean normalised cross-correlation of the samples with the image moved by (du, dv);
  // -1 with too few samples in the image.
  const auto correlation = [&](int du, int dv) {
    double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
    int n = 0;
    for (const Sample& s : samples) {
      const int u = s.u + du, v = s.v + dv;
      if (u < 0 || v < 0 || u >= image_grey.cols || v >= image_grey.rows) continue;
      const double a = rendered_grey.at<std::uint8_t>(s.y, s.x), b = image_grey.at<std::uint8_t>(v, u);
      sa += a;
      sb += b;
      saa += a * a;
      sbb += b * b;
      sab += a * b;
      ++n;
    }
    if (n < 16) return -1.0;
    const double cov = sab - sa * sb / n, va = saa - sa * sa / n, vb = sbb - sb * sb / n;
    return va > 0 && vb > 0 ? cov / std::sqrt(va * vb) : 0.0;
  };
  // Uphill from no shift, a pixel at a time: the correlation of a texture peaks where it
  // is registered.
  double best = correlation(0, 0);
  if (best <= -1.0) return -1.0;
  int best_du = 0, best_dv = 0;
  for (bool climbed = true; climbed;) {
    climbed = false;
    const int from_du = best_du, from_dv = best_dv;
    for (int dv = from_dv - 1; dv <= from_dv + 1; ++dv)
      for (int du = from_du - 1; du <= from_du + 1; ++du) {
        if (std::max(std::abs(du), std::abs(dv)) > kAppearanceShiftPx || (du == from_du && dv == from_dv)) continue;
        const double c = correlation(du, dv);
        if (c <= best) continue;
        std::tie(best, best_du, best_dv) = std::tie(c, du, dv);
        climbed = true;
      }
  }
  // A body of flat colours: its colours must differ in the image where they differ in the
  // render (the grey correlation alone follows the faces' shading: a red mug passed for
  // the two-colour box).
  if (appearance_ && !alignment_ && color.image.channels() == 3) {
    ChromaByRenderedColour chroma;
    for (const Sample& s : samples) {
      const int u = s.u + best_du, v = s.v + best_dv;
      if (u < 0 || v < 0 || u >= image_grey.cols || v >= image_grey.rows) continue;
      chroma.add(render.color.at<cv::Vec3b>(s.y, s.x), color.image.at<cv::Vec3b>(v, u));
    }
    if (!chroma.differ_as_rendered()) return 0.0;
  }
  return best;
}

std::optional<BodyDetector::Hypothesis> BodyDetector::refine_and_verify(const Frame& frame, const ColorImage& color,
                                                                      const cv::Mat& grey, const Pose& start,
                                                                      bool from_texture, int stages,
                                                                      Detection& detection) {
  const Hypothesis refined = refine(frame, start, stages);
  ++detection.refined;
  return verify(frame, color, grey, refined, start, from_texture, stages, detection);
}

std::optional<BodyDetector::Hypothesis> BodyDetector::verify(const Frame& frame, const ColorImage& color,
                                                           const cv::Mat& grey, Hypothesis h, const Pose& start,
                                                           bool from_texture, int stages, Detection& detection) {
  if (h.quality < params_.accept_quality) return std::nullopt;
  const auto aligned = [&](const Pose& pose) {
    return alignment_->align(grey, color.intrinsics, color.camera_T_reference, pose, refiner_->occluders());
  };
  const DepthImage* depth = depth_camera_.empty() ? nullptr : frame.find_depth(depth_camera_);
  if (alignment_ && !(depth && depth->delivered())) {
    // Without depth the contour of a body in clutter pulls less surely than its texture
    // does, and leaves a monocular pose millimetres off along the line of sight: the
    // texture aligns the refined pose (and a keypoint start), and of those poses the one
    // that looks most like the image is kept.
    std::vector<Pose> poses{h.reference_T_body};
    if (from_texture) poses.push_back(start);
    for (std::size_t k = 0, n = poses.size(); k < n; ++k)
      if (const std::optional<Pose> pose = aligned(poses[k])) poses.push_back(*pose);
    h.appearance = -2.0;
    for (const Pose& pose : poses) {
      const double agreement = appearance_agreement(color, pose);
      if (agreement > h.appearance) h.appearance = agreement, h.reference_T_body = pose;
    }
  } else if (appearance_) {
    h.appearance = appearance_agreement(color, h.reference_T_body);
    // With depth the shape fits a body turned about an axis it is round about (a can's
    // label) as well as the right pose, and its colour regions may not tell either: only
    // the texture turns it back (5-15 degrees off on the can, looking alike at NCC
    // 0.65-0.81), and the cues refine it again. Any other shape is aligned only when it
    // does not look like the image.
    if (alignment_ && (round_ || h.appearance < kMinAppearance))
      if (const std::optional<Pose> pose = aligned(h.reference_T_body)) {
        Hypothesis again = refine(frame, *pose, stages);
        ++detection.refined;
        again.appearance = appearance_agreement(color, again.reference_T_body);
        if (again.quality >= params_.accept_quality && again.appearance > h.appearance) h = again;
      }
  }
  return h;
}

std::vector<PoseCandidate> BodyDetector::template_candidates(const Frame& frame, const ColorImage& color,
                                                             const SearchWindow& window, int hypotheses,
                                                             Detection& detection) {
  // With depth: each match placed on the measured surface and checked against it before
  // suppression, so that matches of the background do not crowd out the body's.
  const Pose reference_T_camera = color.camera_T_reference.inverse();
  const DepthImage* depth = depth_camera_.empty() ? nullptr : frame.find_depth(depth_camera_);
  const bool has_depth = depth && depth->delivered();
  const CandidateCheck in_depth = [&](PoseCandidate& c) {
    if (!has_depth) return true;
    const double agreement = place_in_depth(frame, c);
    if (agreement >= 0.0 && agreement < kMinDepthAgreement) return false;
    const double silhouette = silhouette_support(frame, reference_T_camera * c.camera_T_body);
    if (silhouette >= 0.0 && silhouette < kMinSilhouetteSupport) return false;
    c.support = std::max(agreement, 0.0) + std::max(silhouette, 0.0);
    return true;
  };
  // Near a pose, only the part of the image its window's templates can reach is searched:
  // the same camera with its principal point moved, so the poses found are unchanged.
  const std::optional<ColorImage> cropped = window.near ? window_crop(color, window, templates_->sphere()) : color;
  if (!cropped) {
    detection.why_not = "the search window around its last trusted pose is out of view";
    return {};
  }
  const ColorImage& searched = *cropped;
  std::optional<RayDepth> ray_depth;
  SearchWindow gated = window;
  if (has_depth)
    // A crop keeps the whole image's cell size.
    gated.depth = &ray_depth.emplace(
        *depth, searched, std::max(1, RayDepth::kWidth * searched.intrinsics.width / color.intrinsics.width));
  OrientationPyramid pyramid(searched);
  const auto best_ranked = [&](std::vector<PoseCandidate> found) {
    std::stable_sort(found.begin(), found.end(), [](const PoseCandidate& a, const PoseCandidate& b) {
      return a.score + a.support > b.score + b.support;
    });
    if (static_cast<int>(found.size()) > hypotheses) found.resize(hypotheses);
    return found;
  };
  const bool whole_image = !window.near;
  TemplateMatcher& first = whole_image ? *coarse_matcher_ : *matcher_;
  std::vector<PoseCandidate> candidates = best_ranked(
      first.match(pyramid, gated, kMinTemplateScore, kCandidatesRanked * hypotheses, in_depth, &detection.why_not));
  detection.candidates += static_cast<int>(candidates.size());
  if (whole_image) {
    // Coarse views first, then the fine templates near each of their best matches.
    for (PoseCandidate& c : candidates) {
      SearchWindow near = gated;
      near.near = c.camera_T_body;
      near.min_distance = c.distance / TemplateMatcher::kDistanceStep;
      near.max_distance = c.distance * TemplateMatcher::kDistanceStep;
      near.radius_px = std::max(kFineMinRadiusPx, kFineRadiusSpheres * color.intrinsics.fu *
                                                      templates_->sphere().radius / c.distance);
      near.max_rotation = kFineRotation;
      const std::vector<PoseCandidate> fine = matcher_->match(pyramid, near, kMinTemplateScore, 1, in_depth);
      if (!fine.empty() && fine.front().score >= c.score) c = fine.front();
    }
    candidates = best_ranked(std::move(candidates));
  }

  return candidates;
}

cv::Mat BodyDetector::usable_for_templates(const ColorImage& color) {
  const std::vector<Body*> others = refiner_->occluders();
  if (others.empty()) return color.mask.mask;
  // The other bodies rendered over the whole image at a quarter of its resolution, their
  // silhouettes grown by what a quarter pixel spans and by the orientations' spread.
  const Intrinsics& K = color.intrinsics;
  RenderRequest request;
  request.camera = color.camera;
  request.intrinsics = K;
  request.camera_T_reference = color.camera_T_reference;
  request.square = {-0.5, -0.5, static_cast<double>(std::max(K.width, K.height))};
  request.size = (std::max(K.width, K.height) + kOthersRenderScale - 1) / kOthersRenderScale;
  request.targets = kRenderIds;
  std::vector<const Body*> shown(others.begin(), others.end());
  Renders renders;
  refiner_->renderer().render(shown, {request}, renders);
  const cv::Mat& ids = renders.at(request).ids;
  cv::Mat covered;
  cv::resize(ids != 0, covered, cv::Size(request.size * kOthersRenderScale, request.size * kOthersRenderScale), 0, 0,
             cv::INTER_NEAREST);
  covered = covered(cv::Rect(0, 0, K.width, K.height));
  const int grow = kOthersRenderScale + OrientationResponses::kSpreadRadius + 1;
  cv::dilate(covered, covered, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(2 * grow + 1, 2 * grow + 1)));
  cv::Mat usable = covered == 0;
  if (!color.mask.all_pixels()) usable &= color.mask.mask != 0;
  return usable;
}

void BodyDetector::place_others(const OtherPoses& others) {
  for (Body* occluder : refiner_->occluders()) {
    const auto it = others.find(occluder->name);
    if (it != others.end()) occluder->reference_T_body = it->second;
  }
}

double BodyDetector::share_in_view(const ColorImage& color, const Pose& reference_T_body) const {
  const Pose camera_T_body = color.camera_T_reference * reference_T_body;
  const ShapeTemplates::View& view = templates_->closest_view(camera_T_body);
  int seen = 0, all = 0;
  for (const ShapeTemplates::ViewContourPoint& p : view.contour) {
    const Eigen::Vector3d X = camera_T_body * p.position.cast<double>();
    ++all;
    if (X.z() <= 0.0) continue;
    const Eigen::Vector2d uv = color.intrinsics.project(X);
    seen += color.intrinsics.contains(uv.x(), uv.y()) && color.mask.usable(uv.cast<float>());
  }
  return all > 0 ? static_cast<double>(seen) / all : 0.0;
}

bool BodyDetector::is_symmetry(const Pose& turn) const {
  return std::any_of(symmetries_.begin(), symmetries_.end(), [&](const Pose& symmetry) {
    return rotation_angle_between(symmetry.rotation(), turn.rotation()) <= kEquivalentRotation;
  }) || Eigen::AngleAxisd(turn.rotation()).angle() <= kEquivalentRotation;
}

bool BodyDetector::apart(const Pose& a, const Pose& b) const {
  const Sphere& sphere = templates_->sphere();
  return (a * sphere.centre - b * sphere.centre).norm() >= 0.5 * sphere.radius;
}

std::string BodyDetector::rival_answer(const std::vector<Hypothesis>& verified) const {
  const Hypothesis& best = verified.front();
  const auto alike = [&](const Hypothesis& h) {
    return h.quality >= best.quality - kRivalQuality && (!appearance_ || h.appearance >= best.appearance - kRivalQuality);
  };
  char why[200];
  for (auto h = verified.begin() + 1; h != verified.end(); ++h)
    if (alike(*h) && apart(h->reference_T_body, best.reference_T_body)) {
      const Sphere& sphere = templates_->sphere();
      std::snprintf(why, sizeof why,
                    "it fits two places alike (quality %.2f, and %.2f %.0f mm away): a look-alike is in view, and "
                    "either would be a guess",
                    best.quality, h->quality,
                    1e3 * (h->reference_T_body * sphere.centre - best.reference_T_body * sphere.centre).norm());
      return why;
    }
  // A textured body's turns are told apart by its texture; a plain shape's turns that fit
  // alike are its equivalents (a mug's handle out of sight).
  if (!appearance_ || alignment_) return {};
  for (auto h = verified.begin() + 1; h != verified.end(); ++h)
    if (alike(*h) && !is_symmetry(best.reference_T_body.inverse() * h->reference_T_body)) {
      std::snprintf(why, sizeof why,
                    "it fits two orientations alike (quality %.2f, and %.2f turned %.0f deg): its shape and colours "
                    "do not tell which",
                    best.quality, h->quality,
                    rotation_angle_between(h->reference_T_body.rotation(), best.reference_T_body.rotation()) * 180.0 /
                        kPi);
      return why;
    }
  return {};
}

double BodyDetector::windows_apart(const Pose& a, const Pose& b) const {
  const Sphere& sphere = templates_->sphere();
  const double moved = (a * sphere.centre - b * sphere.centre).norm() / (kNearRadiusSpheres * sphere.radius);
  const double turned = rotation_angle_between(a.rotation(), b.rotation()) / kNearRotation;
  return std::max(moved, turned);
}

bool BodyDetector::confirms(const Frame& frame, const Pose& reference_T_body, const OtherPoses& others,
                            std::string& why_not) {
  const ColorImage* color = frame.find_color(color_camera_);
  if (!color) {
    why_not = "the frame has no image from camera '" + color_camera_ + "'";
    return false;
  }
  if (share_in_view(*color, reference_T_body) < kMinShareInView) {
    why_not = "part of its silhouette is out of view";
    return false;
  }
  const double silhouette = silhouette_support(frame, reference_T_body);
  if (silhouette >= 0.0 && silhouette < kMinSilhouetteSupport) {
    why_not = "the measured depth does not step back beyond its contour";
    return false;
  }
  if (appearance_) {
    place_others(others);
    const DepthImage* depth = depth_camera_.empty() ? nullptr : frame.find_depth(depth_camera_);
    const double min_appearance = depth && depth->delivered() ? kMinAppearance : kMinAppearanceWithoutDepth;
    if (appearance_agreement(*color, reference_T_body) < min_appearance) {
      why_not = "its render does not look like the image";
      return false;
    }
  }
  return true;
}

std::vector<Pose> BodyDetector::poses_to_turn(std::vector<Hypothesis> refined,
                                             const std::vector<Hypothesis>& verified) const {
  std::stable_sort(refined.begin(), refined.end(),
                   [](const Hypothesis& a, const Hypothesis& b) { return a.quality > b.quality; });
  // Flat colours have every turn of their best verified pose refined after this pass: it
  // counts as turned already.
  std::vector<Pose> turned;
  if (!alignment_ && !verified.empty())
    turned.push_back(best_fitting(verified).reference_T_body);
  std::vector<Pose> sources;
  for (const Hypothesis& h : refined) {
    if (turned.size() >= kTurnedRefinements) break;
    const bool alike = std::any_of(turned.begin(), turned.end(), [&](const Pose& pose) {
      return !apart(pose, h.reference_T_body) &&
             rotation_angle_between(pose.rotation(), h.reference_T_body.rotation()) <= kEquivalentRotation;
    });
    if (alike) continue;
    sources.push_back(h.reference_T_body);
    turned.push_back(h.reference_T_body);
  }
  return sources;
}

Detection BodyDetector::search(const Frame& frame, const SearchWindow& window, int hypotheses,
                               const OtherPoses& others) {
  place_others(others);
  Detection detection;
  // Near a pose the body was just trusted at, its colours are learnt where they are: one
  // stage is enough for a shape, and the cost per frame stays bounded. A body with
  // appearance keeps both: its verdict rests on how its render agrees with the image,
  // which one stage left short of the check on the textured box (11 of 12 local searches
  // found, 12 with two) and on the labelled can turned 15 degrees.
  const int stages = window.near && !appearance_ ? 1 : kRefinementStages;
  const ColorImage* found_color = frame.find_color(color_camera_);
  if (!found_color) {
    detection.why_not = "the frame has no image from camera '" + color_camera_ + "' to search";
    return detection;
  }
  // The image as the templates see it: what the tracker's other bodies cover (a gripper
  // over the object) shows their edges, not this body's.
  ColorImage masked = *found_color;
  masked.mask.mask = usable_for_templates(masked);
  const ColorImage* color = &masked;
  const Pose reference_T_camera = color->camera_T_reference.inverse();
  const DepthImage* depth = depth_camera_.empty() ? nullptr : frame.find_depth(depth_camera_);
  const bool has_depth = depth && depth->delivered();
  if (!has_depth && !alignment_) {
    // Measured without depth, a plain shape fits too many outlines of a cluttered image
    // (86 % wrong poses for a mug in `icgp bench --detect`), and a shape of flat colours
    // fits as many two-tone patches (the two-colour box: 13 poses far off in its grey rows
    // against 21 right or equivalent): only a texture verifies it there. Better not found
    // than wrong.
    detection.why_not = "without depth, a body without texture cannot be verified (give depth, or a model with its "
                        "texture)";
    return detection;
  }
  cv::Mat grey = color->image;
  if (grey.channels() == 3 && (keypoints_ || alignment_)) cv::cvtColor(color->image, grey, cv::COLOR_BGR2GRAY);
  std::vector<Hypothesis> verified;
  std::vector<Hypothesis> refined;  // every candidate's refinement, verified or not
  // Keeps a start's verified refinement, and says whether it fits so well that the other
  // candidates have nothing to win but a symmetric twin (which the turns below find).
  const auto refined_confidently = [&](const Pose& start, bool from_texture = false) {
    refined.push_back(refine(frame, start, stages));
    ++detection.refined;
    const std::optional<Hypothesis> h = verify(frame, *color, grey, refined.back(), start, from_texture, stages, detection);
    if (!h) return false;
    verified.push_back(*h);
    // Only a pose that also looks like the body: another object of its shape may fit as well.
    if (!has_depth) return appearance_ && h->appearance >= kMinAppearanceWithoutDepth;
    return appearance_ && h->quality >= kConfidentQuality && h->appearance >= kMinAppearance;
  };
  // A textured body's keypoints place it wherever its texture shows, whatever its shape's
  // symmetry: tried first over the whole image, and the templates only when they fail.
  bool confident = false;
  if (!window.near && keypoints_) {
    for (const KeypointModel::Located& located : keypoints_->locate(grey, color->intrinsics)) {
      ++detection.candidates;
      if ((confident = refined_confidently(reference_T_camera * located.camera_T_body, true))) break;
    }
  }
  if (!confident)
    for (const PoseCandidate& candidate : template_candidates(frame, *color, window, hypotheses, detection))
      if ((confident = refined_confidently(reference_T_camera * candidate.camera_T_body))) break;
  if (appearance_ && !confident && !window.near) {
    // No candidate both fits and looks like the body. A refinement started a quarter turn
    // off stays there, fitting part of the outline: a box seen nearly edge-on fitted 0.55-0.67
    // at turns of the right pose, which fits 0.96. So the best two refinements, verified or
    // not, are turned about the body's axes and refined again; a turn that then fits
    // confidently is verified as any candidate is.
    const std::vector<Pose> sources = poses_to_turn(std::move(refined), verified);
    for (const Pose& source : sources)
      for (const Pose& turn : axis_turns_) {
        if (is_symmetry(turn)) continue;
        const Pose start = source * turn;
        const Hypothesis turned = refine(frame, start, stages);
        ++detection.refined;
        if (turned.quality < kConfidentQuality) continue;
        if (const std::optional<Hypothesis> h = verify(frame, *color, grey, turned, start, false, stages, detection))
          verified.push_back(*h);
      }
  }
  // A local search's window is near a pose the tracker trusted: of the turns, only those
  // it spans (a round shape's small turns about its axis) are tried there.
  std::vector<Pose> turns;
  for (const Pose& turn : turns_)
    if (!window.near || Eigen::AngleAxisd(turn.rotation()).angle() <= window.max_rotation)
      turns.push_back(turn);
  if (appearance_ && !verified.empty()) {
    // The shape may not tell a box from the box turned about an axis: the appearance does.
    const Hypothesis best = best_fitting(verified);
    if (alignment_) {
      // A textured body: a turn that maps the shape onto itself needs no refinement to be
      // compared, so only the turn that looks most like the image is refined. A best pose
      // that does not look like the image leaves any better-looking turn worth it.
      std::optional<Pose> look_alike;
      double look_alike_appearance = best.appearance + (best.appearance >= kMinAppearance ? kAppearanceGain : 0.0);
      for (const Pose& turn : turns) {
        const Pose turned = best.reference_T_body * turn;
        const double appearance = appearance_agreement(*color, turned);
        if (appearance <= look_alike_appearance) continue;
        look_alike = turned;
        look_alike_appearance = appearance;
      }
      if (look_alike)
        if (const std::optional<Hypothesis> h =
                refine_and_verify(frame, *color, grey, *look_alike, false, stages, detection))
          verified.push_back(*h);
    } else {
      // Flat colours may not tell a turn that is no symmetry either (a box of two colours
      // partly hidden fits a quarter turn): each is refined, to be compared by
      // rival_answer; a symmetric turn fits and looks as the best does.
      for (const Pose& turn : turns) {
        if (is_symmetry(turn)) continue;
        if (const std::optional<Hypothesis> h =
                refine_and_verify(frame, *color, grey, best.reference_T_body * turn, false, stages, detection))
          verified.push_back(*h);
      }
    }
    // Without depth only the appearance tells a textured body from a picture of its shape
    // (a painted rectangle for a box), and with depth only the appearance tells it from
    // another object of its size.
    const double min_appearance = has_depth ? kMinAppearance : kMinAppearanceWithoutDepth;
    const std::size_t fitting = verified.size();
    verified.erase(std::remove_if(verified.begin(), verified.end(),
                                  [&](const Hypothesis& h) { return h.appearance < min_appearance; }),
                   verified.end());
    if (verified.empty() && fitting > 0)
      detection.why_not = "no pose that fits the image looks like the body there (its render correlates below " +
                          shortest(min_appearance) + (has_depth ? "" : " without depth") +
                          (alignment_ ? "" : ", or its colours do not differ where the model's do") + ")";
  } else if (!verified.empty()) {
    // Without appearance, a turn that is no symmetry of the shape shows in the fit of its
    // contour and depth (a mug's handle): every turn is refined and the best fit wins; the
    // turns that fit as well are the equivalent poses of a symmetric shape.
    const Hypothesis best = best_fitting(verified);
    for (const Pose& turn : turns) {
      const Hypothesis h = refine(frame, best.reference_T_body * turn, stages);
      ++detection.refined;
      if (h.quality >= params_.accept_quality) verified.push_back(h);
    }
  }
  // Only now, so that a refinement the cues disagree on still seeds the turns above (the
  // two-colour box's right pose was found by turning one whose region scored 0.48).
  const std::size_t searched = verified.size();
  verified.erase(std::remove_if(verified.begin(), verified.end(), [](const Hypothesis& h) { return !h.cues_agree; }),
                 verified.end());
  if (verified.empty() && searched > 0)
    detection.why_not = "its cues disagree on every pose that fits (one of two, or two of three, score it below " +
                        shortest(refiner_->params().quality_threshold) + ")";
  if (verified.empty()) {
    if (detection.why_not.empty())
      detection.why_not = detection.candidates == 0 ? "no template matched the image"
                                                    : "no hypothesis reached quality " +
                                                          shortest(params_.accept_quality) + " after refinement";
    return detection;
  }
  // Among the poses that fit nearly as well as the best, the one that looks like the image,
  // and of those that look alike the best fitting; without depth, the look alone ranks all.
  std::vector<VerifiedScores> scores;
  for (const Hypothesis& h : verified) scores.push_back({h.quality, h.appearance});
  const VerifiedRanking ranking = has_depth ? VerifiedRanking{kAppearanceQualityMargin, kAlikeAppearance}
                                            : VerifiedRanking{std::numeric_limits<double>::infinity(), 0.0};
  std::vector<Hypothesis> ranked;
  for (const std::size_t i : rank_verified(scores, ranking)) ranked.push_back(verified[i]);
  verified = std::move(ranked);
  detection.why_not = rival_answer(verified);
  if (!detection.why_not.empty()) return detection;
  detection.found = true;
  detection.quality = verified.front().quality;
  detection.reference_T_body = verified.front().reference_T_body;
  detection.free_turn_axes = free_turn_axes_;
  const auto add_equivalent = [&](const Pose& pose) {
    const bool new_one = std::none_of(detection.equivalents.begin(), detection.equivalents.end(), [&](const Pose& e) {
      return rotation_angle_between(pose.rotation(), e.rotation()) <= kEquivalentRotation;
    });
    if (new_one) detection.equivalents.push_back(pose);
  };
  // The body's symmetries give poses no image can tell from the found one.
  for (const Pose& symmetry : symmetries_) add_equivalent(detection.reference_T_body * symmetry);
  for (std::size_t k = 1; k < verified.size(); ++k) {
    const Hypothesis& h = verified[k];
    if (h.quality < detection.quality - kEquivalentQuality) continue;
    // With appearance, only a pose that looks as alike is equivalent.
    if (appearance_ && h.appearance < verified.front().appearance - kEquivalentQuality) continue;
    const Pose& pose = h.reference_T_body;
    const bool turned = rotation_angle_between(pose.rotation(), detection.reference_T_body.rotation()) > kEquivalentRotation;
    if (!apart(pose, detection.reference_T_body) && turned) add_equivalent(pose);
  }
  return detection;
}

}  // namespace icgp
