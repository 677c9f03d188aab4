// SPDX-License-Identifier: GPL-2.0-or-later
// vpMbIcgTracker: the model's edges for display, in one camera or several.
#include <visp3/core/vpDisplay.h>

#include "icgp/visp/conversions.h"

#include "vpMbIcgTracker_impl.h"

using icgp::visp_detail::guarded;

std::vector<std::vector<double>> vpMbIcgTracker::getModelForDisplay(unsigned int width, unsigned int height,
                                                                    const vpHomogeneousMatrix& cMo,
                                                                    const vpCameraParameters& cam,
                                                                    bool displayFullModel) {
  Impl& d = *impl_;
  if (d.mesh.parts.empty())
    throw vpTrackingException(vpTrackingException::initializationError,
                              "vpMbIcgTracker::getModelForDisplay: no model to display");
  icgp::require_image_size("getModelForDisplay", [] { return std::string("the image"); }, width, height);
  return guarded("getModelForDisplay", [&] {
    if (!d.edges) d.edges = std::make_unique<icgp::ModelEdges>(d.mesh);
    const icgp::Intrinsics k = icgp::to_intrinsics(cam, static_cast<int>(width), static_cast<int>(height));
    const icgp::Pose camera_T_body = icgp::to_pose(cMo);
    cv::Mat depth;
    if (!displayFullModel) depth = d.renderer->depth_of(Impl::kBody, d.mesh, k, camera_T_body);
    std::vector<std::vector<double>> lines;
    for (const icgp::ImageSegment& s : d.edges->project(k, camera_T_body, depth))
      lines.push_back({0.0, s.a.y(), s.a.x(), s.b.y(), s.b.x()});  // ViSP: i is the row (v), j the column (u)
    return lines;
  });
}

void vpMbIcgTracker::getModelForDisplay(std::map<std::string, std::vector<std::vector<double>>>& mapOfModels,
                                        const std::map<std::string, unsigned int>& mapOfwidths,
                                        const std::map<std::string, unsigned int>& mapOfheights,
                                        const std::map<std::string, vpHomogeneousMatrix>& mapOfcMos,
                                        const std::map<std::string, vpCameraParameters>& mapOfCams,
                                        bool displayFullModel) {
  mapOfModels.clear();
  for (const auto& [camera, cMo] : mapOfcMos) {
    impl_->rig.at(camera, "getModelForDisplay");
    const auto width = mapOfwidths.find(camera);
    const auto height = mapOfheights.find(camera);
    const auto cam = mapOfCams.find(camera);
    if (width == mapOfwidths.end() || height == mapOfheights.end() || cam == mapOfCams.end())
      throw vpException(vpException::badValue, "vpMbIcgTracker::getModelForDisplay: camera '" + camera +
                                                   "' has a pose but no width, height or camera parameters");
    mapOfModels[camera] = getModelForDisplay(width->second, height->second, cMo, cam->second, displayFullModel);
  }
}

namespace {

template <typename Image>
void draw_lines(const Image& I, const std::vector<std::vector<double>>& lines, const vpColor& color,
                unsigned int thickness) {
  for (const std::vector<double>& l : lines)
    vpDisplay::displayLine(I, vpImagePoint(l[1], l[2]), vpImagePoint(l[3], l[4]), color, thickness);
}

/// ViSP's colours for its features: moving edges green (red when down-weighted), KLT points red.
template <typename Image>
void draw_features(const Image& I, const std::vector<std::vector<double>>& features, unsigned int thickness) {
  for (const std::vector<double>& f : features) {
    const vpColor color = f[0] == 0.0 ? (f[3] == 0.0 ? vpColor::green : vpColor::red) : vpColor::red;
    vpDisplay::displayCross(I, vpImagePoint(f[1], f[2]), 3 + 2 * thickness, color, thickness);
  }
}

}  // namespace

void vpMbIcgTracker::display(const vpImage<unsigned char>& I, const vpHomogeneousMatrix& cMo,
                             const vpCameraParameters& cam, const vpColor& col, unsigned int thickness,
                             bool displayFullModel) {
  draw_lines(I, getModelForDisplay(I.getWidth(), I.getHeight(), cMo, cam, displayFullModel), col, thickness);
  if (displayFeatures) draw_features(I, getFeaturesForDisplay(), thickness);
}

void vpMbIcgTracker::display(const vpImage<vpRGBa>& I, const vpHomogeneousMatrix& cMo, const vpCameraParameters& cam,
                             const vpColor& col, unsigned int thickness, bool displayFullModel) {
  draw_lines(I, getModelForDisplay(I.getWidth(), I.getHeight(), cMo, cam, displayFullModel), col, thickness);
  if (displayFeatures) draw_features(I, getFeaturesForDisplay(), thickness);
}

// As vpMbGenericTracker's TrackerWrapper::display, each camera's image gets the model and
// that camera's own features (the single-image forms above draw the reference camera's);
// the two-camera forms are the map forms of the first and second camera.

void vpMbIcgTracker::display(const vpImage<unsigned char>& I1, const vpImage<unsigned char>& I2,
                             const vpHomogeneousMatrix& c1Mo, const vpHomogeneousMatrix& c2Mo,
                             const vpCameraParameters& cam1, const vpCameraParameters& cam2, const vpColor& color,
                             unsigned int thickness, bool displayFullModel) {
  const auto [first, second] = impl_->rig.pair("display");
  display(std::map<std::string, const vpImage<unsigned char>*>{{first, &I1}, {second, &I2}},
          {{first, c1Mo}, {second, c2Mo}}, {{first, cam1}, {second, cam2}}, color, thickness, displayFullModel);
}

void vpMbIcgTracker::display(const vpImage<vpRGBa>& I1, const vpImage<vpRGBa>& I2, const vpHomogeneousMatrix& c1Mo,
                             const vpHomogeneousMatrix& c2Mo, const vpCameraParameters& cam1,
                             const vpCameraParameters& cam2, const vpColor& color, unsigned int thickness,
                             bool displayFullModel) {
  const auto [first, second] = impl_->rig.pair("display");
  display(std::map<std::string, const vpImage<vpRGBa>*>{{first, &I1}, {second, &I2}}, {{first, c1Mo}, {second, c2Mo}},
          {{first, cam1}, {second, cam2}}, color, thickness, displayFullModel);
}

namespace {

/// Each camera with an image, a pose and parameters is drawn; the others, as in ViSP, not.
template <typename Image, typename Draw>
void display_each(const std::map<std::string, const Image*>& images,
                  const std::map<std::string, vpHomogeneousMatrix>& poses,
                  const std::map<std::string, vpCameraParameters>& cameras, Draw&& draw) {
  for (const auto& [name, image] : images) {
    const auto pose = poses.find(name);
    const auto camera = cameras.find(name);
    if (image && pose != poses.end() && camera != cameras.end()) draw(name, *image, pose->second, camera->second);
  }
}

}  // namespace

void vpMbIcgTracker::display(const std::map<std::string, const vpImage<unsigned char>*>& mapOfImages,
                             const std::map<std::string, vpHomogeneousMatrix>& mapOfCameraPoses,
                             const std::map<std::string, vpCameraParameters>& mapOfCameraParameters,
                             const vpColor& col, unsigned int thickness, bool displayFullModel) {
  for (const auto& [name, image] : mapOfImages) impl_->rig.at(name, "display");
  display_each(mapOfImages, mapOfCameraPoses, mapOfCameraParameters,
               [&](const std::string& name, const vpImage<unsigned char>& I, const vpHomogeneousMatrix& cMo,
                   const vpCameraParameters& cam) {
                 draw_lines(I, getModelForDisplay(I.getWidth(), I.getHeight(), cMo, cam, displayFullModel), col,
                            thickness);
                 if (displayFeatures) draw_features(I, features_for_display(name), thickness);
               });
}

void vpMbIcgTracker::display(const std::map<std::string, const vpImage<vpRGBa>*>& mapOfImages,
                             const std::map<std::string, vpHomogeneousMatrix>& mapOfCameraPoses,
                             const std::map<std::string, vpCameraParameters>& mapOfCameraParameters,
                             const vpColor& col, unsigned int thickness, bool displayFullModel) {
  for (const auto& [name, image] : mapOfImages) impl_->rig.at(name, "display");
  display_each(mapOfImages, mapOfCameraPoses, mapOfCameraParameters,
               [&](const std::string& name, const vpImage<vpRGBa>& I, const vpHomogeneousMatrix& cMo,
                   const vpCameraParameters& cam) {
                 draw_lines(I, getModelForDisplay(I.getWidth(), I.getHeight(), cMo, cam, displayFullModel), col,
                            thickness);
                 if (displayFeatures) draw_features(I, features_for_display(name), thickness);
               });
}
