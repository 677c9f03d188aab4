// SPDX-License-Identifier: GPL-2.0-or-later
// The pose covariance a Newton step's data Hessian implies, in ViSP's convention.
#pragma once

#include "icgp/base/pose.h"
#include "icgp/modality/modality.h"

namespace icgp {

/// The covariance of `reference_T_body` over the reference-frame (camera) twist ordered as
/// ViSP orders it, (v, ω): Ad(reference_T_body) P (−H)⁺ Pᵀ Ad(…)ᵀ, where (−H)⁺ (the
/// pseudo-inverse, so a cue-less direction gives 0 rather than inf) is the covariance over
/// the body-frame variation θ = [θ_r; θ_t] and P reorders θ to (v, ω). Exactly symmetric.
Mat66 camera_twist_covariance(const Mat66& hessian, const Pose& reference_T_body);

}  // namespace icgp
