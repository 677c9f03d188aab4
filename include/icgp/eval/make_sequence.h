// SPDX-License-Identifier: GPL-2.0-or-later
// Rendering a sequence of a model or of a scene file with exact ground truth: what `icgp
// make-sequence` and icgp.make_sequence (Python) do, with the ranges both check.
#pragma once

#include <functional>
#include <string>

#include "icgp/base/mesh.h"
#include "icgp/eval/sequence_writer.h"
#include "icgp/io/yaml_reader.h"

namespace icgp {

/// What to render: one model (a spinning mesh or .cao) or the bodies of a scene file, seen
/// by a colour camera and a depth camera `baseline` metres to its side (and a second colour
/// camera `stereo_baseline` metres along its x axis when non-zero), both `width` x `height`
/// with focal length `focal` pixels and the principal point at the image centre.
struct MakeSequenceRequest {
  std::string model;  ///< used when `scene` is empty
  std::string scene;  ///< a scene file (eval/sequence_scene.h)
  std::string out;    ///< the folder written (SequenceWriter::write)
  double scale = 1.0;  ///< metres per unit of `model`
  int width = 640, height = 480;
  double focal = 600.0;
  double baseline = 0.0;
  double stereo_baseline = 0.0;
  double spin = 0.0;  ///< the model's rotation about its y axis, rad/s
  SequenceWriterOptions writer;
};

/// The ranges of the request's numbers: the program's options and the Python keywords are
/// checked against these (and the image size against base/resource_limits.h).
namespace make_sequence_range {
inline constexpr yaml::Interval kFocal{0.0, 100000.0, true};
inline constexpr yaml::Interval kScale{0.0, 1000.0, true};
inline constexpr yaml::Interval kRate{0.0, 1000.0, true};
inline constexpr yaml::Interval kSpeed{0.0, 100.0, true};
inline constexpr yaml::Interval kDistance{0.0, 1000.0, true};
inline constexpr yaml::Interval kBaseline{-10.0, 10.0};
inline constexpr yaml::Interval kSpin{-100.0, 100.0};
inline constexpr yaml::Interval kColorNoise{0.0, 255.0};
inline constexpr yaml::Interval kDepthNoise{0.0, 1.0};
inline constexpr yaml::Interval kDepthDropout{0.0, 1.0};
inline constexpr yaml::Interval kGrazingAngle{0.0, 90.0, true};
inline constexpr yaml::Interval kExposure{0.0, 1.0};
inline constexpr yaml::Interval kGainVariation{0.0, 1.0, false, true};
/// Each frame is colour and depth images, about 0.6 MB at 640x480: 100 000 frames ~60 GB.
inline constexpr long long kMaxFrames = 100000;
inline constexpr long long kMaxDepthEdgeHoles = 100;
inline constexpr long long kMaxAntialiasSamples = 64;
inline constexpr long long kMaxMotionBlurSamples = 256;
}  // namespace make_sequence_range

/// Reads a model file into metres (a mesh, or a .cao through ViSP in icgp::visp).
using ModelReader = std::function<Mesh(const std::string& path, double scale)>;

/// Renders the request into request.out and returns what was written, e.g. "100 frames of
/// 'textured_box' (stereo)". Scene model names are resolved against `models_dir`. The
/// ranges above are the caller's to check (each caller names its options its own way);
/// throws what SequenceWriter, the scene reader and `read_model` throw.
std::string make_sequence(MakeSequenceRequest request, const std::string& models_dir, const ModelReader& read_model);

}  // namespace icgp
