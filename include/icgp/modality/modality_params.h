// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "icgp/base/camera_names.h"
#include "icgp/modality/modality.h"
#include "icgp/modality/residual_noise.h"
#include "icgp/model/viewpoint_model.h"

namespace icgp {

/// Noise estimation per cue (ResidualNoise; docs/accuracy.md has the measurements).
/// Region: σ from the schedule. Its residuals share a common contour offset (antialiased or
/// blurred edges dilate the silhouette), so their scatter is small while their error is
/// not; trusting that scatter made the region's bias decide the pose. Robust weights on
/// that scatter, though: a line whose contour lies far beyond the others' (clutter of the
/// object's colour, colour noise) is wrong, not precise. Floor 0.5 px, the pixel grid's.
inline constexpr NoiseParams kRegionNoise{false, true, 0.5};
/// Depth: floor 0.1 mm at 1 m. Exact synthetic depth fits the model to micrometres; the
/// floor keeps the depth Hessian within float range of the others, so directions depth
/// cannot see (sliding along a face) are still decided by the other cues.
inline constexpr NoiseParams kDepthNoise{true, true, 1e-4};
/// Texture: floor 0.5 px, about the keypoint localisation of the 200 px detection crop.
/// Its robust weights are the papers' Tukey norm (TextureParams::tukey_norm_constant).
/// Estimated at the pose the other cues give (TextureModality::weighs_against_others).
inline constexpr NoiseParams kTextureNoise{true, false, 0.5};
/// Flow: floor 0.1 px, about what pyramidal Lucas–Kanade resolves on a corner. Tukey weights
/// on the estimated scale drop points the flow lost (a jump to a look-alike, a highlight
/// sliding over the surface) however few the others are.
inline constexpr NoiseParams kFlowNoise{true, true, 0.1};
/// Edge: floor 0.25 px, about where a smoothed gradient's peak can be told on a clean step.
/// Tukey weights on the estimated scale drop samples that took another edge of the image
/// (texture, background clutter) for the model's.
inline constexpr NoiseParams kEdgeNoise{true, true, 0.25};

/// Measured occlusions (ALGORITHMS.md §7): a point of a cue is hidden when a measurement of
/// the cue's depth camera within `radius` of its projection is closer by more than
/// `threshold`. One set of defaults for every cue; configuration files keep the flat keys
/// measure_occlusions, occlusion_radius and occlusion_threshold of each cue's section.
struct OcclusionParams {
  /// The cue tests its points (texture: its keyframe points) when true and it has depth.
  /// (The texture section of a configuration file has no measure_occlusions key.)
  bool measure = true;
  double radius = 0.01;     ///< metres
  double threshold = 0.03;  ///< metres
  /// Modeled occlusions (ALGORITHMS.md §7): when the tracker has other bodies (tracked,
  /// links or occluders), the cue also rejects points that a focused depth render of all
  /// bodies shows hidden by another body, with its own radius and threshold. (The texture
  /// cue keeps keyframe points only where the render shows its own body.)
  bool model = true;
  double modeled_radius = 0.01;     ///< metres
  double modeled_threshold = 0.03;  ///< metres
  /// Side of the focused render (pixels) of the crop around the body: once per frame, at
  /// the first correspondence iteration, and only with other bodies.
  int render_size = 200;
};

/// Parameters of the region modality (ALGORITHMS.md §4, §7) with the reference defaults.
/// Iteration-indexed lists use entry corr_iter, and their last entry afterwards.
struct RegionParams {
  std::string color_camera = kColorCamera;
  std::string depth_camera = kDepthCamera;  ///< for measured occlusions; empty: none
  int n_lines_max = 200;
  double min_continuous_distance = 3.0;  ///< segments
  int function_length = 8;
  int distribution_length = 12;
  double function_amplitude = 0.43;  ///< α of the smoothed step
  double function_slope = 0.5;       ///< s_h; 0 = hard step
  double learning_rate = 1.3;
  int n_global_iterations = 1;
  /// After the global iterations, follow the contour posterior between its discrete
  /// positions with a smooth (C¹) interpolation of its log, so lines keep the sub-pixel
  /// location of their contour; false: the papers' finite difference of the two
  /// neighbouring positions, which snaps a straight edge to whole pixels.
  bool subpixel_posterior = true;
  std::vector<int> scales = {6, 4, 2, 1};
  std::vector<double> standard_deviations = {15.0, 5.0, 3.5, 1.5};  ///< pixels; the noise estimate's ceiling
  NoiseParams noise = kRegionNoise;
  int n_histogram_bins = 16;
  double learning_rate_f = 0.2;
  double learning_rate_b = 0.2;
  double unconsidered_line_length = 0.5;  ///< pixels
  double max_considered_line_length = 20.0;  ///< pixels
  OcclusionParams occlusion;
  /// Region checking (ALGORITHMS.md §6): with the focused render of modeled occlusions, a
  /// line is kept only when the render shows the cue's body just inside its contour point
  /// and something else just outside, so that contours another body covers, or that are no
  /// longer on the silhouette at the current pose, measure nothing. A cue on one region of
  /// a multi-region object checks only the inside (its outside is often its own object).
  /// Off by default, as in the reference implementation: on the crossing and hinged-box
  /// scenes it cost accuracy (a hinged lid's contour lines along its base were dropped,
  /// one frame's joint error rose from 0.19° to 2.04°; docs/scenes.md).
  bool region_checking = false;
  int n_unoccluded_iterations = 10;  ///< frames after a (re)start without measured occlusion tests
  int min_n_unoccluded_lines = 0;
};

/// Dense depth correspondences (docs/configuration.md): when depth is a body's only cue, a
/// model's ~200 sparse points pin its pose less well than its visible surface can. The
/// cue then renders the body's depth and normals at the current pose whenever it has moved
/// enough since the last render (DenseDepthSampling) and pairs each sampled measured pixel
/// inside the rendered
/// silhouette with the rendered surface at that pixel, point-to-plane, as ViSP's dense
/// depth features do.
struct DenseDepthParams {
  /// Dense correspondences replace the sparse model points when depth is the body's only
  /// cue; false keeps the model points.
  bool when_only_cue = true;
  /// Image pixels between samples along columns (x) and rows (y), ViSP's
  /// setDepthDenseSamplingStep; 0: the smallest step that puts at most n_points_max
  /// samples on the image of the body's bounding sphere, so that a near body costs no more
  /// than a far one and a far one still gets every pixel.
  int step_x = 0;
  int step_y = 0;
  int n_points_max = 5000;
};

/// Image pixels between the samples of dense depth along columns (x) and rows (y).
struct SamplingStep {
  int x = 1;
  int y = 1;
};

/// Parameters of the depth modality (ALGORITHMS.md §5, §7) with the reference defaults.
struct DepthParams {
  std::string depth_camera = kDepthCamera;
  int n_points_max = 200;
  double stride_length = 0.005;  ///< metres between window samples
  std::vector<double> considered_distances = {0.05, 0.02, 0.01};  ///< metres
  std::vector<double> standard_deviations = {0.05, 0.03, 0.02};   ///< metres at 1 m; the noise estimate's ceiling
  NoiseParams noise = kDepthNoise;
  OcclusionParams occlusion;
  int n_unoccluded_iterations = 10;
  int min_n_unoccluded_points = 0;
  DenseDepthParams dense;
};

/// The keypoint descriptors of the texture cue (make_descriptor; docs/configuration.md).
enum class Descriptor {
  kOrb,           ///< OpenCV's ORB
  kBrisk,         ///< OpenCV's BRISK
  kSift,          ///< OpenCV's SIFT
  kAkaze,         ///< OpenCV's AKAZE
  kFreak,         ///< icgp::Freak on ORB keypoints
  kDaisy,         ///< icgp::Daisy on ORB keypoints
  kOrientedBrief  ///< icgp::OrientedBrief, icgp's own ORB-style extractor
};

inline constexpr std::array<Descriptor, 7> kDescriptors = {Descriptor::kOrb,   Descriptor::kBrisk, Descriptor::kSift,
                                                           Descriptor::kAkaze, Descriptor::kFreak, Descriptor::kDaisy,
                                                           Descriptor::kOrientedBrief};

/// The name configuration files use: "orb", "brisk", "sift", "akaze", "freak", "daisy",
/// "oriented_brief".
inline const std::string& to_string(Descriptor descriptor) {
  static const std::array<std::string, 7> names = {"orb", "brisk", "sift", "akaze", "freak", "daisy", "oriented_brief"};
  return names[static_cast<std::size_t>(descriptor)];
}

/// The descriptor called `name`; nullopt for any other name.
inline std::optional<Descriptor> parse_descriptor(const std::string& name) {
  for (const Descriptor descriptor : kDescriptors)
    if (to_string(descriptor) == name) return descriptor;
  return std::nullopt;
}

/// Parameters of the texture modality (paper §III-C, §IV; ALGORITHMS.md §8) with the
/// reference defaults. Pixel values refer to the full colour image.
struct TextureParams {
  std::string color_camera = kColorCamera;
  std::string depth_camera = kDepthCamera;  ///< measured occlusions at keyframes; empty: none
  /// oriented_brief: icgp's own ORB-style extractor, a third of cv::ORB's time.
  Descriptor descriptor = Descriptor::kOrientedBrief;
  int focused_image_size = 200;          ///< side of the rescaled detection crop, pixels
  int orb_n_features = 300;              ///< also oriented_brief's, and the detector of freak and daisy
  int orb_n_levels = 3;
  double orb_scale_factor = 1.2;
  int sift_n_octave_layers = 3;
  double sift_contrast_threshold = 0.04;
  double sift_edge_threshold = 10.0;
  double sift_sigma = 0.7;
  double ratio_test = 0.7;  ///< best / second-best descriptor distance must be below this
  double keyframe_orientation_threshold_deg = 10.0;
  /// Frames after which a keyframe is renewed even without rotation (refreshes appearance
  /// after lighting or scale changes); 0: only the orientation criterion of the paper.
  int keyframe_max_age = 100;
  /// A keyframe with fewer points than this shows corners of the silhouette, not texture:
  /// the cue then abstains from the body's quality (ModalityQuality::abstained).
  int min_keyframe_points = 20;
  double tukey_norm_constant = 20.0;                 ///< c, pixels
  std::vector<double> standard_deviations = {15.0, 5.0};  ///< σ_t, pixels; the noise estimate's ceiling
  NoiseParams noise = kTextureNoise;
  OcclusionParams occlusion;
};

/// Parameters of the flow cue (ViSP's KLT tracker): Shi–Tomasi corners on the body, tracked
/// from frame to frame with pyramidal Lucas–Kanade and lifted onto the model where they were
/// found. The corner and flow settings are vpKltOpencv's, with vpMbKltTracker's defaults;
/// the cameras are the texture cue's. Pixel values refer to the full colour image.
struct FlowParams {
  int max_features = 10000;    ///< cv::goodFeaturesToTrack's maxCorners; 0: no limit, as there
  double quality = 0.01;       ///< its qualityLevel: of the best corner's response
  double min_distance = 5.0;   ///< pixels between corners
  int block_size = 3;          ///< pixels of the corner response's window
  /// Harris' response instead of the smaller eigenvalue. Off: at the same quality the
  /// smaller eigenvalue keeps about 4x the corners on a real textured cube (105 vs 27 per
  /// frame on tests/data/realsense-cube), where Harris' few strongest set a high bar.
  bool use_harris = false;
  double harris_k = 0.01;      ///< Harris' free parameter
  int window_size = 5;         ///< pixels, side of Lucas–Kanade's window
  int pyramid_levels = 3;      ///< coarser levels above the image
  /// Pixels of the body's silhouette that give no corner (vpMbKltTracker's mask border):
  /// corners on the outline belong to the background as much as to the body.
  int mask_border = 5;
  /// A point tracked forward and back must come back within this many pixels, or it is
  /// dropped: the flow then lost it (a look-alike, an occluder, a highlight).
  double forward_backward_threshold = 1.0;
  /// Corners are found anew when fewer than this share of the last renewal's survive, or
  /// when the body turned by renew_rotation_deg since: new faces then carry none.
  double renew_fraction = 0.6;
  double renew_rotation_deg = 10.0;
  /// With fewer corners lifted than this, the cue abstains from the body's quality.
  int min_points = 20;
  std::vector<double> standard_deviations = {15.0, 5.0};  ///< pixels; the noise estimate's ceiling
  NoiseParams noise = kFlowNoise;
  OcclusionParams occlusion;  ///< measured occlusions of corners when they are lifted
};

/// Parameters of the edge cue (ViSP's moving edges, in ICG+'s Newton step): the model's
/// creases, sampled along their projection and matched along their normal to the strongest
/// step of brightness near them. The cameras are the region cue's. Pixel values refer to the
/// full colour image.
struct EdgeParams {
  /// Faces that meet at more than this angle make a crease the cue follows (a border or an
  /// edge of more than two faces always does).
  double crease_angle_deg = 30.0;
  /// A crease is followed when one of its faces is seen at most this far from its normal
  /// (ViSP's angle_disappear of its examples' files). A face seen more obliquely is a
  /// sliver whose two creases project a few pixels apart, and each would take the other's
  /// step.
  double max_view_angle_deg = 75.0;
  /// Pixels between samples along a projected crease (vpMe's sample step)...
  double sample_step = 5.0;
  /// ...widened so that the visible creases get at most this many samples.
  int n_points_max = 300;
  /// Pixels searched either side of a sample along its normal (vpMe's range), per
  /// correspondence iteration.
  std::vector<int> search_ranges = {12, 8, 4, 3, 2};
  /// The smallest brightness step a match must show: grey levels per pixel of the smoothed
  /// gradient along the normal.
  double min_contrast = 4.0;
  /// With fewer visible samples than this, the cue abstains from the body's quality.
  int min_points = 20;
  /// Pixels: the noise estimate's ceiling, and the spread of the search's prior on a step's
  /// distance from the prediction.
  std::vector<double> standard_deviations = {10.0, 5.0, 3.0, 2.0, 1.5};
  NoiseParams noise = kEdgeNoise;
  /// The visible samples are chosen anew when the camera has moved around the body by this
  /// angle since they were chosen (or came 10 % nearer or farther): about the spacing of the
  /// region and depth models' views (4.1° at 2562 views), which decide their visible points by
  /// the nearest view. Samples a turn hides or shows meanwhile are few, and the robust
  /// weights drop the hidden ones. On ViSP's castle (not convex: a render per choice), 2°
  /// rendered nearly every frame (1.04 ms median for the edge cue alone), 5° 0.67 ms, with
  /// the same errors.
  double resample_angle_deg = 5.0;
  /// Side of the focused render that decides which samples are hidden, when the body may
  /// hide parts of itself (not convex) or another body may cover it.
  int render_size = 200;
};

}  // namespace icgp
