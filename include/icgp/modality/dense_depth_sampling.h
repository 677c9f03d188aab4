// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "icgp/base/body.h"
#include "icgp/base/frame.h"
#include "icgp/base/mesh.h"
#include "icgp/modality/depth_correspondence.h"
#include "icgp/modality/modality.h"
#include "icgp/modality/modality_params.h"

namespace icgp {

/// Dense depth correspondences of one body in one depth camera (docs/configuration.md): a
/// render of every body at its current pose, on the lattice of sampled pixels, pairs each
/// sampled measured pixel where the render shows this body with the surface seen there.
/// Another body in front of it hides its pixels in the render, so modeled occlusions need
/// no test of their own.
class DenseDepthSampling {
 public:
  /// Throws std::invalid_argument for a negative step or a point budget below 1.
  DenseDepthSampling(const Body& body, std::string camera, const DenseDepthParams& params);

  /// The render a correspondence iteration reads: depth, normals and ids on the sampling
  /// lattice over the image of the body's bounding sphere (the whole image when the sphere
  /// reaches the camera's plane). None in other stages, when the sphere's image misses the
  /// image, and in a later iteration of a frame when the body has moved by less than a
  /// quarter of a sampling step since the last pairs were made: re-pairing would find the
  /// same pixels on the same surfaces.
  std::optional<RenderRequest> request(const Stage& stage, const DepthImage& depth) const;

  /// What one pass over the samples found.
  struct Counts {
    int n_on_body = 0;       ///< sampled pixels where the render shows the body
    bool saw_depth = false;  ///< any of them held a measurement
  };
  /// Replaces `out` with the pairs of the render that request() asked for in `renders`, the
  /// body's pose unchanged since. A pair whose measured point lies farther than
  /// `considered_distance` (metres) from the rendered surface point is left out: an
  /// occluder, or the background behind an edge of the silhouette.
  Counts collect(const Renders& renders, const DepthImage& depth, float considered_distance,
                 std::vector<DepthCorrespondence>& out);
  /// Whether `renders` holds the render request() asked for (else the last pairs stand).
  bool rendered(const Renders& renders, const DepthImage& depth) const;

 private:
  /// The sampled pixels (columns col0 + k·step_x, rows row0 + k·step_y, inside the image)
  /// and the render that shows them: one render pixel per render_step image pixels (the
  /// steps' greatest common divisor), its centres on image pixel centres, size × size.
  struct Lattice {
    int step_x = 1, step_y = 1, render_step = 1;
    int col0 = 0, row0 = 0;
    int size = 0;  ///< render pixels per side; 0: nothing to sample
  };
  Lattice lattice(const DepthImage& depth) const;
  RenderRequest request_of(const Lattice& lattice, const DepthImage& depth) const;

  /// How far (metres) the body's sphere has moved in the depth camera since the last pairs,
  /// its turn counted at its radius.
  double moved_since_paired(const DepthImage& depth) const;

  const Body* body_;
  std::string camera_;
  DenseDepthParams params_;
  Sphere sphere_;
  Pose paired_depth_T_body_;  ///< the pose the last pairs were made at
};

}  // namespace icgp
