// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/base/intrinsics.h"

#include <cmath>
#include <stdexcept>

namespace icgp {

void Intrinsics::validate(const std::string& what) const {
  const bool finite = std::isfinite(fu) && std::isfinite(fv) && std::isfinite(pu) && std::isfinite(pv);
  if (!finite || fu <= 0.0 || fv <= 0.0)
    throw std::invalid_argument(what + ": focal lengths must be positive and finite (got fu=" +
                                std::to_string(fu) + ", fv=" + std::to_string(fv) + ")");
  if (width <= 0 || height <= 0)
    throw std::invalid_argument(what + ": image size must be positive (got " + std::to_string(width) + "x" +
                                std::to_string(height) + ")");
}

Intrinsics Intrinsics::cropped(double u_min, double v_min, double crop_width, double crop_height, int out_width,
                               int out_height) const {
  // Pixel edges of the original image sit at u = j - 0.5. A crop edge e maps to output
  // edge -0.5, and lengths scale by s, so u_out = (u - e) * s - 0.5 with e = u_min - 0.5.
  const double su = out_width / crop_width;
  const double sv = out_height / crop_height;
  Intrinsics c;
  c.fu = fu * su;
  c.fv = fv * sv;
  c.pu = (pu - (u_min - 0.5)) * su - 0.5;
  c.pv = (pv - (v_min - 0.5)) * sv - 0.5;
  c.width = out_width;
  c.height = out_height;
  return c;
}

Intrinsics Intrinsics::scaled(int out_width, int out_height) const {
  return cropped(0.0, 0.0, width, height, out_width, out_height);
}

}  // namespace icgp
