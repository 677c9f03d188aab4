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

void TreeOptimizer::step(const std::vector<TreeLink>& links, int corr_iter, int update_iter) {
  // Column offsets of every link's joint values after the root's six.
  std::vector<int> offset(links.size(), 0);
  int n = 6;
  for (std::size_t i = 1; i < links.size(); ++i) {
    offset[i] = n;
    n += links[i].joint->size();
  }

  const Vec6& lambda = links.front().terms->regularisation();
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n);
  Eigen::VectorXd b = Eigen::VectorXd::Zero(n);
  A.diagonal().head<6>() = lambda;
  std::vector<JointJacobian> jacobians(links.size(), JointJacobian::Zero(6, n));
  jacobians.front().leftCols<6>().setIdentity();
  for (std::size_t i = 0; i < links.size(); ++i) {
    const TreeLink& link = links[i];
    JointJacobian& J = jacobians[i];
    if (link.parent >= 0) {
      const std::vector<double>& q = *link.joint_values;
      J = adjoint(link.joint->parent_T_link(q).inverse()) * jacobians[link.parent];
      J.middleCols(offset[i], link.joint->size()) = link.joint->link_jacobian(q);
      for (int k = 0; k < link.joint->size(); ++k) {
        const JointDirection& d = link.joint->directions[k];
        const int column = offset[i] + k;
        A(column, column) += (d.kind == JointDirection::Kind::kRotation ? lambda[0] : lambda[3]) + d.stiffness;
        b[column] -= d.stiffness * q[k];
      }
    }
    link.terms->collect(*link.cues, corr_iter, update_iter);
    const CueTerms& terms = link.terms->total();
    A.noalias() -= J.transpose() * terms.hessian * J;
    b.noalias() += J.transpose() * terms.gradient;
  }

  const Eigen::VectorXd x = A.ldlt().solve(b);
  if (!x.allFinite()) return;
  Body& root = *links.front().body;
  root.reference_T_body = root.reference_T_body.updated_in_body_frame(x.head<6>());
  for (std::size_t i = 1; i < links.size(); ++i) {
    std::vector<double>& q = *links[i].joint_values;
    for (int k = 0; k < links[i].joint->size(); ++k) q[k] += x[offset[i] + k];
    q = links[i].joint->clamped(std::move(q));
  }
  place_links(links);
}

}  // namespace icgp
