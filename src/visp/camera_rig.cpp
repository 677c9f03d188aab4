// SPDX-License-Identifier: GPL-2.0-or-later
#include "camera_rig.h"

#include <visp3/core/vpException.h>

#include "icgp/modality/cue_kind.h"

namespace icgp {
namespace {

void require_types(int types, const std::string& call) {
  if (types == 0 || (types & ~CameraRig::kAllTypes) != 0)
    throw vpException(vpException::badValue,
                      "vpMbIcgTracker::" + call + ": tracker type " + std::to_string(types) +
                          " is not a combination of EDGE_TRACKER (1), KLT_TRACKER (2), DEPTH_NORMAL_TRACKER (4) "
                          "and DEPTH_DENSE_TRACKER (8)");
}

}  // namespace

std::vector<std::string> CameraRig::visp_names(std::size_t n) {
  if (n == 1) return {"Camera"};
  std::vector<std::string> names;
  for (std::size_t i = 1; i <= n; ++i) names.push_back("Camera" + std::to_string(i));
  return names;
}

CameraRig::CameraRig(const std::vector<std::string>& names, const std::vector<int>& types) {
  if (names.empty())
    throw vpException(vpException::badValue, "vpMbIcgTracker: a tracker needs at least one camera");
  if (names.size() != types.size())
    throw vpException(vpException::badValue, "vpMbIcgTracker: " + std::to_string(names.size()) +
                                                 " camera names but " + std::to_string(types.size()) +
                                                 " tracker types; give one type per camera");
  for (std::size_t i = 0; i < names.size(); ++i) {
    require_types(types[i], "vpMbIcgTracker");
    if (!cameras_.emplace(names[i], Camera{types[i]}).second)
      throw vpException(vpException::badValue, "vpMbIcgTracker: camera '" + names[i] + "' is named twice");
  }
  reference_ = cameras_.begin()->first;  // as ViSP: the first of its sorted map
}

void CameraRig::set_reference(const std::string& name) {
  at(name, "setReferenceCameraName");
  reference_ = name;
}

std::vector<std::string> CameraRig::names() const {
  std::vector<std::string> out;
  for (const auto& [name, camera] : cameras_) out.push_back(name);
  return out;
}

std::string CameraRig::quoted_names() const {
  std::string out;
  for (const auto& [name, camera] : cameras_) out += (out.empty() ? "\"" : ", \"") + name + "\"";
  return out;
}

CameraRig::Camera& CameraRig::at(const std::string& name, const std::string& call) {
  const auto it = cameras_.find(name);
  if (it == cameras_.end())
    throw vpException(vpException::badValue, "vpMbIcgTracker::" + call + ": unknown camera '" + name +
                                                 "' (this tracker's cameras: " + quoted_names() + ")");
  return it->second;
}

const CameraRig::Camera& CameraRig::at(const std::string& name, const std::string& call) const {
  return const_cast<CameraRig*>(this)->at(name, call);
}

std::pair<std::string, std::string> CameraRig::pair(const std::string& call) const {
  if (cameras_.size() != 2)
    throw vpException(vpException::badValue, "vpMbIcgTracker::" + call + ": the two-camera form needs a tracker of "
                                                 "two cameras; this one has " + std::to_string(cameras_.size()) +
                                                 " (" + quoted_names() + "); use the map form");
  return {cameras_.begin()->first, std::next(cameras_.begin())->first};
}

void CameraRig::set_types(const std::string& name, int types, const std::string& call) {
  require_types(types, call);
  at(name, call).types = types;
}

bool CameraRig::is_depth_camera(const std::string& name) const {
  return (cameras_.at(name).types & visp_type::kDepth) != 0;
}

std::vector<CameraCues> CameraRig::cues() const {
  std::string first_depth_camera;
  for (const auto& [name, camera] : cameras_)
    if (is_depth_camera(name) && first_depth_camera.empty()) first_depth_camera = name;
  std::vector<CameraCues> out;
  for (const auto& [name, camera] : cameras_) {
    CameraCues c{name, camera.types};
    c.occlusion_depth_camera = is_depth_camera(name) ? name : first_depth_camera;
    c.dense_depth_step = (camera.types & visp_type::kDepthDense) ? camera.dense_step : camera.normal_step;
    out.push_back(c);
  }
  return out;
}

}  // namespace icgp
