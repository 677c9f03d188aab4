// SPDX-License-Identifier: GPL-2.0-or-later
// `icgp bench --sweep`: icgp's defaults, the paper's reference parameters and ViSP's
// vpMbGenericTracker over many rendered conditions with exact ground truth.
#pragma once

#include <string>
#include <vector>

namespace icgp::app {

/// One of the sweep's objects: its mesh and, for multi-region tracking, its colour regions.
struct SweepModel {
  std::string name;
  std::string mesh_path;
  std::vector<std::string> regions;  ///< colour-region meshes (multi-region tracking); empty: one region
};

/// The sweep's four objects (textured box, two-colour box, labelled can, textureless mug),
/// which `bench --detect` uses too.
std::vector<SweepModel> sweep_models();

struct SweepOptions {
  std::string out = "out/sweep";              ///< rendered sequences (cached), ViSP models, plot script
  std::string summary;                        ///< JSON rows; empty: none
  std::string plot = "docs/images/sweep.png";  ///< PNG of mean error against depth noise
  int frames = 60;
  bool quick = false;  ///< one model, two conditions and its grey cell, 320x240, few frames: a test
  /// A YAML file whose viewpoint-model keys (region_model, depth_model) replace those of both
  /// presets, e.g. coarse models for a test; tracking parameters stay the presets'.
  std::string viewpoint_models;
};

/// Renders (or reuses) every cell's sequence, tracks it with each tracker from the first
/// ground-truth pose, prints the table to stdout and writes the summary and the plot.
void run_sweep(const SweepOptions& options);

}  // namespace icgp::app
