// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/optimizer/tree_optimizer.h"

#include <Eigen/Cholesky>

namespace icgp {

void place_links(const std::vector<TreeLink>& links) {
  for (const TreeLink& link : links) {
    if (link.parent < 0) continue;
    link.body->reference_T_body =
        links[link.parent].body->reference_T_body * link.joint->parent_T_link(*link.joint_values);
  }
}

TreeOptimizer::TreeOptimizer(const OptimizerParams& params)
    : regularisation_((validate(params), params.diagonal())) {}

void TreeOptimizer::step(const std::vector<TreeLink>& links, int corr_iter, int update_iter) {
  // Column offsets of every link's joint values after the root's six.
  offset_.assign(links.size(), 0);
  int n = 6;
  for (std::size_t i = 1; i < links.size(); ++i) {
    offset_[i] = n;
    n += links[i].joint->size();
  }

  const Vec6& lambda = regularisation_;
  A_.setZero(n, n);
  b_.setZero(n);
  A_.diagonal().head<6>() = lambda;
  jacobians_.resize(links.size());
  for (std::size_t i = 0; i < links.size(); ++i) {
    const TreeLink& link = links[i];
    JointJacobian& J = jacobians_[i];
    if (link.parent < 0) {
      J.setZero(6, n);
      J.leftCols<6>().setIdentity();
    } else {
      const std::vector<double>& q = *link.joint_values;
      J.noalias() = adjoint(link.joint->parent_T_link(q).inverse()) * jacobians_[link.parent];
      J.middleCols(offset_[i], link.joint->size()) = link.joint->link_jacobian(q);
      for (int k = 0; k < link.joint->size(); ++k) {
        const JointDirection& d = link.joint->directions[k];
        const int column = offset_[i] + k;
        A_(column, column) += (d.kind == JointDirection::Kind::kRotation ? lambda[0] : lambda[3]) + d.stiffness;
        b_[column] -= d.stiffness * q[k];
      }
    }
    link.terms->collect(*link.cues, corr_iter, update_iter);
    const CueTerms& terms = link.terms->total();
    A_.noalias() -= J.transpose() * terms.hessian * J;
    b_.noalias() += J.transpose() * terms.gradient;
  }

  const Eigen::VectorXd x = A_.ldlt().solve(b_);
  if (!x.allFinite()) return;
  Body& root = *links.front().body;
  root.reference_T_body = root.reference_T_body.updated_in_body_frame(x.head<6>());
  for (std::size_t i = 1; i < links.size(); ++i) {
    std::vector<double>& q = *links[i].joint_values;
    for (int k = 0; k < links[i].joint->size(); ++k) q[k] += x[offset_[i] + k];
    q = links[i].joint->clamped(std::move(q));
  }
  place_links(links);
}

}  // namespace icgp
