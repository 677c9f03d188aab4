// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <vector>

#include "icgp/base/body.h"
#include "icgp/geometry/joint.h"
#include "icgp/modality/modality.h"
#include "icgp/optimizer/optimizer.h"

namespace icgp {

/// A body of a kinematic tree as TreeOptimizer sees it. Links come in tree order: the root
/// first, every link after its parent.
struct TreeLink {
  Body* body = nullptr;
  const std::vector<Modality*>* cues = nullptr;
  /// The link's cue terms, collected each update.
  CueTermSum* terms = nullptr;
  int parent = -1;               ///< index of the parent link; -1 for the root only
  const Joint* joint = nullptr;  ///< to the parent; null for the root
  std::vector<double>* joint_values = nullptr;
};

/// The Newton–Tikhonov step of a kinematic tree (ALGORITHMS.md §2 through the chain rule):
/// the unknowns are the root's body-frame variation θ and every joint value q. Each link's
/// cues give g and H in the link's own θ_L; θ_L = J_L [θ; δq], with J_L the parent's
/// Jacobian carried into the link's frame (adjoint) plus the link's own joint columns, so
///   (Λ − Σ J_Lᵀ H_L J_L + K) [θ; δq] = Σ J_Lᵀ g_L − K q
/// where Λ holds λ_r for the root's rotation and rotational joints, λ_t for translations,
/// and K the joints' stiffnesses (their soft constraints towards 0). Joint values are then
/// clamped into their limits and every link is placed by forward kinematics.
class TreeOptimizer {
 public:
  /// Throws std::invalid_argument for a negative or NaN λ.
  explicit TreeOptimizer(const OptimizerParams& params = {});

  /// One update. A singular system leaves the tree as it is.
  void step(const std::vector<TreeLink>& links, int corr_iter, int update_iter);

 private:
  Vec6 regularisation_;
  // Kept between updates so that a frame's steps reuse their memory.
  std::vector<int> offset_;  ///< column of each link's first joint value
  std::vector<JointJacobian> jacobians_;
  Eigen::MatrixXd A_;
  Eigen::VectorXd b_;
};

/// Places every link after the root at its parent's pose times its joint's motion.
void place_links(const std::vector<TreeLink>& links);

}  // namespace icgp
