// SPDX-License-Identifier: GPL-2.0-or-later
// Numeric derivatives of a modality's log-likelihood, to check its analytic gradient.
#pragma once

#include "icgp/modality/modality.h"

namespace icgp::test {

/// Central differences of the modality's log-likelihood over body-frame variations θ (the
/// body's pose is restored afterwards).
inline Vec6 numeric_gradient(Modality& modality, int corr_iter) {
  Body& body = modality.body();
  const Pose start = body.reference_T_body;
  Vec6 gradient;
  for (int i = 0; i < 6; ++i) {
    const double h = i < 3 ? 1e-5 : 1e-6;
    Vec6 theta = Vec6::Zero();
    theta[i] = h;
    body.reference_T_body = start.updated_in_body_frame(theta);
    const double plus = modality.log_likelihood(corr_iter);
    body.reference_T_body = start.updated_in_body_frame(-theta);
    const double minus = modality.log_likelihood(corr_iter);
    gradient[i] = (plus - minus) / (2 * h);
  }
  body.reference_T_body = start;
  return gradient;
}

}  // namespace icgp::test
