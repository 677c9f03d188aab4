// SPDX-License-Identifier: GPL-2.0-or-later
// What both ViSP layouts ("visp-blender", "visp-realsense") share: their calibration files
// and image sizes taken from the first frame.
#pragma once

#include <filesystem>
#include <string>

#include "icgp/eval/sequence.h"

namespace icgp {

class VispLayout : public SequenceLayout {
 public:
  explicit VispLayout(std::filesystem::path dir) : dir_(std::move(dir)) {}
  std::string size_origin() const override { return "size of the first frame"; }

 protected:
  /// Fills `d` with the calibration: the intrinsics of the <camera> blocks of the XML files
  /// (SequenceOptions, else detected as Sequence::open describes), sized like the first
  /// colour and depth images; depth_M_color.txt; the objects (the top-level .cao files,
  /// else the .cao beside the colour XML); and options.frame_rate. `layout` names the
  /// layout in the message for a missing SequenceOptions::read_camera_xml.
  void describe_calibration(const std::string& layout, const SequenceOptions& options, SequenceDescription& d) const;

  std::filesystem::path dir_;
};

}  // namespace icgp
