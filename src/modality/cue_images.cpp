// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/modality/cue_images.h"

#include <stdexcept>

namespace icgp {

const ColorImage& cue_color_image(const Frame& frame, const std::string& camera, const std::string& cue,
                                  const Body& body) {
  const ColorImage* color = frame.find_color(camera);
  if (!color)
    throw std::invalid_argument(cue + " modality of '" + body.name + "': the frame has no colour camera '" + camera +
                                "'");
  if ((color->image.type() != CV_8UC3 && color->image.type() != CV_8UC1) || color->image.empty())
    throw std::invalid_argument(cue + " modality of '" + body.name + "': camera '" + camera +
                                "' must give a CV_8UC3 or CV_8UC1 image");
  return *color;
}

}  // namespace icgp
