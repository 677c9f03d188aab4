// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <vector>
#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpImage.h>
#include <visp3/core/vpRGBa.h>

#include "icgp/base/frame.h"

namespace icgp {

/// The largest image side, in pixels, vpMbIcgTracker takes (colour, depth, clouds, display):
/// the renderer draws the cues' views at the camera's image size, and 16384 is OpenGL's
/// texture limit on llvmpipe and on most GPUs; a larger side is a corrupt size, not a camera.
inline constexpr unsigned int kMaxImageSide = 16384;

/// Refuses, with vpException::badValue naming `call`, `what()` (e.g. "the depth of camera
/// 'Camera2'") and the size, a width or height of 0 or above kMaxImageSide. `what` makes its
/// text only for a size it refuses: track() checks every image of every frame.
void require_image_size(const std::string& call, const std::function<std::string()>& what, unsigned int width,
                        unsigned int height);

/// Builds the icgp::Frame a tracker reads from what ViSP users hold, camera by camera:
/// vpImage colour or grey images, organised point clouds, raw depth images. Buffers are
/// kept per camera from frame to frame, and a grey vpImage is wrapped without a copy.
/// Camera problems throw vpException naming the camera.
class FrameAssembler {
 public:
  /// Starts a frame in which no camera has delivered anything yet.
  void begin_frame();

  /// `camera_set` false: the user never gave the parameters (ViSP would silently use its
  /// defaults; icgp refuses).
  void set_color(const std::string& camera, const vpImage<unsigned char>& I, const vpCameraParameters& parameters,
                 bool camera_set, const vpHomogeneousMatrix& camera_M_reference);
  void set_color(const std::string& camera, const vpImage<vpRGBa>& I, const vpCameraParameters& parameters,
                 bool camera_set, const vpHomogeneousMatrix& camera_M_reference);

  /// Where a depth pixel comes from: metres at (row, col); 0, negative or not finite
  /// means no measurement.
  using DepthReader = std::function<float(int row, int col)>;
  /// A measured point at (row, col) in the camera frame (metres), for clouds whose points
  /// are not on the pinhole rays of their pixels.
  using PointReader = std::function<Eigen::Vector3f(int row, int col)>;
  /// Reads the points of many pixels in one pass (LazyDepthSource::ManyPointsReader); may be empty.
  using ManyPointsReader = LazyDepthSource::ManyPointsReader;
  /// The camera's depth image, converted from `read` on first read of each pixel (see
  /// DepthImage::source): the cues read a few thousand pixels, and reading a whole cloud
  /// of ViSP's vpColVectors would cost as much as tracking. With `read_many`, the pixels
  /// the camera's last frame read are read ahead at once. Both are used until
  /// end_depth_reads().
  void set_depth(const std::string& camera, unsigned int width, unsigned int height,
                 const vpCameraParameters& parameters, bool camera_set, const vpHomogeneousMatrix& camera_M_reference,
                 DepthReader read, ManyPointsReader read_many);
  void set_depth_points(const std::string& camera, unsigned int width, unsigned int height,
                        const vpCameraParameters& parameters, bool camera_set,
                        const vpHomogeneousMatrix& camera_M_reference, PointReader read, ManyPointsReader read_many);
  /// The depth camera delivers nothing this frame (DepthImage::delivered); the depth cue
  /// reading it sits the frame out.
  void set_no_depth(const std::string& camera);
  /// Drops the readers of set_depth (which usually refer to the caller's clouds): pixels not
  /// read so far read as "no measurement" from now on.
  void end_depth_reads();

  /// ViSP's setMask: the pixels every camera's cues may use (true), for every image of the
  /// mask's size; an empty mask allows all. A camera of another size uses every pixel, and
  /// says so once on std::cerr.
  void set_mask(const vpImage<bool>& mask);

  const Frame& frame() const { return frame_; }
  /// A colour camera's image of this frame as ViSP grey, for ViSP's projection error;
  /// nullptr when the camera delivered none.
  const vpImage<unsigned char>* grey_image(const std::string& camera);

 private:
  ColorImage& color_slot(const std::string& camera, const vpCameraParameters& parameters, bool camera_set,
                         const vpHomogeneousMatrix& camera_M_reference, unsigned int width, unsigned int height);
  DepthImage& depth_slot(const std::string& camera, const vpCameraParameters& parameters, bool camera_set,
                         const vpHomogeneousMatrix& camera_M_reference, unsigned int width, unsigned int height);
  /// The mask for a camera's image of width x height: none when the sizes differ.
  cv::Mat mask_for(const std::string& camera, int width, int height);

  Frame frame_;
  std::map<std::string, ColorImage> color_slots_;  ///< buffers kept across frames
  std::map<std::string, cv::Mat> depth_buffers_, ray_buffers_;
  cv::Mat mask_;
  std::set<std::string> cameras_without_mask_;  ///< already told their size differs
  vpImage<unsigned char> grey_;
};

}  // namespace icgp
