// SPDX-License-Identifier: GPL-2.0-or-later
// The names of an RGB-D sensor's cameras, shared by frames, sequences, the modalities'
// parameters and the ViSP layer. They are ViSP's names for the cameras of a
// vpMbGenericTracker built with more than one camera, so a colour + depth pair in icgp is
// the same pair in ViSP; the stereo camera continues the numbering.
#pragma once

namespace icgp {

/// The colour camera: the reference of a frame and of a sequence (identity pose).
inline constexpr char kColorCamera[] = "Camera1";
/// The depth camera.
inline constexpr char kDepthCamera[] = "Camera2";
/// A sequence's second colour camera, beside kColorCamera for stereo.
inline constexpr char kStereoCamera[] = "Camera3";

}  // namespace icgp
