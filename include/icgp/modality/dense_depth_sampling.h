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
/// render of every body, on the lattice of sampled pixels, gives the body's surface seen at
/// each sampled pixel; each sampled measured pixel where the render shows this body is
/// paired with that surface. Another body in front of it hides its pixels in the render, so
/// modeled occlusions need no test of their own.
///
/// The surface is kept (in the body frame) from render to render: the body is rendered again
/// only when it has moved by a quarter of a sampling step since (within a frame or from one
/// frame to the next, as the motion goes), or when another body may have moved over it.
class DenseDepthSampling {
 public:
  /// Throws std::invalid_argument for a negative step or a point budget below 1.
  DenseDepthSampling(const Body& body, std::string camera, const DenseDepthParams& params);

  /// The render a correspondence iteration needs: depth, normals and ids on the sampling
  /// lattice over the image of the body's bounding sphere (the whole image when the sphere
  /// reaches the camera's plane). None in other stages, when the sphere's image misses the
  /// image, and while the kept surface still stands (see above).
  std::optional<RenderRequest> request(const Stage& stage, const DepthImage& depth) const;
  /// Forgets the kept surface (a restart).
  void forget() { surface_.clear(); }

  /// What one pass over the samples found.
  struct Counts {
    int n_on_body = 0;       ///< sampled pixels where the body's surface is seen
    bool saw_depth = false;  ///< any of them held a measurement
  };
  /// Replaces `out` with the pairs of the sampled pixels of the body's surface: from the
  /// render that request() asked for in `renders`, or the kept one. A pair whose measured
  /// point lies farther than `considered_distance` (metres) from its surface point at the
  /// current pose is left out: an occluder, or the background behind an edge of the
  /// silhouette.
  Counts collect(const Renders& renders, const DepthImage& depth, float considered_distance,
                 std::vector<DepthCorrespondence>& out);

 private:
  /// The sampled pixels (columns col0 + k·step_x, rows row0 + k·step_y, inside the image)
  /// and the render that shows them: one render pixel per render_step image pixels (the
  /// steps' greatest common divisor), its centres on image pixel centres, size × size.
  struct Lattice {
    int step_x = 1, step_y = 1, render_step = 1;
    int col0 = 0, row0 = 0;
    int size = 0;  ///< render pixels per side; 0: nothing to sample
  };
  /// A sampled pixel where the last render showed the body, and the surface it showed there.
  struct SurfaceSample {
    int row, col;
    Eigen::Vector3f body_point, body_normal;
  };
  Lattice lattice(const DepthImage& depth) const;
  RenderRequest request_of(const Lattice& lattice, const DepthImage& depth) const;
  /// Whether the kept surface stands for `depth` at the body's current pose.
  bool surface_stands(const Stage& stage, const Lattice& lattice, const DepthImage& depth) const;
  void keep_surface(const FocusedRender& render, std::uint8_t id, const Lattice& lattice, const DepthImage& depth);

  const Body* body_;
  std::string camera_;
  DenseDepthParams params_;
  Sphere sphere_;
  std::vector<SurfaceSample> surface_;
  Pose rendered_depth_T_body_;  ///< the pose surface_ was rendered at
  int rendered_width_ = 0, rendered_height_ = 0;  ///< of the depth image it was rendered for
};

}  // namespace icgp
