// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>
#include <visp3/core/vpColVector.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpImage.h>
#include <visp3/mbt/vpMbTracker.h>

#include "icgp/tracker/tracker_config.h"

// The PCL overloads take clouds by shared pointer, which is what PCL 1.13's ConstPtr is;
// declaring the types here keeps PCL's slow headers out of every user of this class.
namespace pcl {
struct PointXYZ;
struct PointXYZRGBA;
template <typename PointT>
class PointCloud;
}  // namespace pcl

/*!
  The ICG+ tracker (region, depth and texture cues fused in one regularised Newton
  optimisation) as a ViSP model-based tracker: code written against vpMbTracker, or against
  vpMbGenericTracker's RGB-D calls, runs with it by changing the class name and the
  parameter file.

  Cameras have vpMbGenericTracker's names: "Camera1" is the colour camera and the reference
  (cMo is relative to it), "Camera2" the depth camera, placed with
  setCameraTransformationMatrix("Camera2", depth_M_color). Camera parameters are used
  without distortion. Which cues run is set by the parameter file (loadConfigFile with
  icgp's YAML, see docs/configuration.md) or setModalities(); the default is region +
  depth. Colour-only tracking (track(I)) needs a configuration without "depth".

  Model: loadModel() takes ViSP .cao files (parsed by vpMbTracker itself) and meshes that
  assimp reads (.obj, .ply, .stl, ...) by extension; repeated calls add parts to the same
  rigid object. The sparse viewpoint models are generated on the first initFromPose after a
  model or parameter change (with progress on std::cerr, a few seconds) and cached on disk
  (TrackerConfig::cache_dir), so later runs load them in milliseconds.

  Initialisation is deferred like vpMbGenericTracker's RGB-D use: initFromPose() and
  setPose() store the pose; the next track() call starts the cues (colour histograms,
  keyframes) on its frame at that pose and then tracks that frame.

  Errors are ViSP exceptions: vpException::ioError for missing or unreadable files,
  vpException::badValue for unsupported extensions, unknown camera names or clouds whose
  size is not width x height, vpTrackingException::initializationError for tracking before
  loadModel/initFromPose, vpTrackingException::fatalError from testTracking() when lost.
*/
class vpMbIcgTracker : public vpMbTracker {
 public:
  vpMbIcgTracker();
  ~vpMbIcgTracker() override;
  vpMbIcgTracker(const vpMbIcgTracker&) = delete;
  vpMbIcgTracker& operator=(const vpMbIcgTracker&) = delete;

  /** @name Parameters */
  //@{
  /// .yaml / .yml: icgp's tracker parameters (docs/configuration.md); .xml: a ViSP tracker
  /// XML file, of which the <camera> block sets the colour camera.
  void loadConfigFile(const std::string& configFile, bool verbose = true) override;
  /// vpMbGenericTracker's two-camera form: each file is a ViSP XML (its <camera> block sets
  /// that camera: colour, then depth) or icgp's YAML parameters.
  void loadConfigFile(const std::string& colorConfigFile, const std::string& depthConfigFile, bool verbose = true);
  void setTrackerConfig(const icgp::TrackerConfig& config);
  const icgp::TrackerConfig& getTrackerConfig() const;
  /// The cues to fuse: any of "region", "depth", "texture".
  void setModalities(const std::vector<std::string>& modalities);
  //@}

  /** @name Model */
  //@{
  /// Adds the parts of a .cao file or an assimp mesh to the object, placed with T (model
  /// frame points X become T X).
  void loadModel(const std::string& modelFile, bool verbose = false,
                 const vpHomogeneousMatrix& T = vpHomogeneousMatrix()) override;
  /// vpMbGenericTracker's two-camera form. One rigid object is tracked, so both files must
  /// describe the same model: the colour camera's file is loaded, the depth camera's must
  /// name the same file (or be empty).
  void loadModel(const std::string& colorModelFile, const std::string& depthModelFile, bool verbose = false,
                 const vpHomogeneousMatrix& colorT = vpHomogeneousMatrix(),
                 const vpHomogeneousMatrix& depthT = vpHomogeneousMatrix());
  //@}

  /** @name Cameras */
  //@{
  void setCameraParameters(const vpCameraParameters& colorCamera) override;
  void setCameraParameters(const vpCameraParameters& colorCamera, const vpCameraParameters& depthCamera);
  void setCameraParameters(const std::map<std::string, vpCameraParameters>& mapOfCameraParameters);
  using vpMbTracker::getCameraParameters;
  void getCameraParameters(vpCameraParameters& colorCamera, vpCameraParameters& depthCamera) const;
  /// cameraName's pose relative to the colour camera (c_M_color); "Camera1" must stay the identity.
  void setCameraTransformationMatrix(const std::string& cameraName, const vpHomogeneousMatrix& cameraTransformationMatrix);
  void setCameraTransformationMatrix(const std::map<std::string, vpHomogeneousMatrix>& mapOfTransformationMatrix);
  std::vector<std::string> getCameraNames() const;
  std::string getReferenceCameraName() const;
  //@}

  /** @name Initialisation */
  //@{
  /// Makes the tracker ready at the current pose (m_cMo): builds the viewpoint models if
  /// needed; the cues start on the next track() call.
  void init(const vpImage<unsigned char>& I) override;
  void initFromPose(const vpImage<unsigned char>& I, const vpHomogeneousMatrix& cMo) override;
  void initFromPose(const vpImage<vpRGBa>& I_color, const vpHomogeneousMatrix& cMo) override;
  using vpMbTracker::initFromPose;
  /// Moves the estimate to cdMo; the cues restart there on the next track() call.
  void setPose(const vpImage<unsigned char>& I, const vpHomogeneousMatrix& cdMo) override;
  void setPose(const vpImage<vpRGBa>& I_color, const vpHomogeneousMatrix& cdMo) override;
  /// Back to a freshly constructed tracker: no model, default parameters and cameras; the
  /// depth camera's transformation matrix stays, as in vpMbGenericTracker.
  void resetTracker() override;
  /// Accepted, and reported once on stderr as having no effect: the cues' visibility comes
  /// from the viewpoint models rendered from the mesh, exact for every face, so there is
  /// no polygon visibility test to refine.
  void setScanLineVisibilityTest(const bool& v) override;
  //@}

  /** @name Tracking */
  //@{
  void track(const vpImage<unsigned char>& I) override;
  void track(const vpImage<vpRGBa>& I_color) override;
  /// vpMbGenericTracker's RGB-D call: images of "Camera1", organised point clouds (row
  /// major, one vpColVector X, Y, Z in metres per pixel, Z <= 0 or NaN for no measurement)
  /// of "Camera2" in its own frame. Width and height 0 mean, as in ViSP, that the depth
  /// camera delivered nothing this frame: the depth cue sits it out.
  void track(std::map<std::string, const vpImage<unsigned char>*>& mapOfImages,
             std::map<std::string, const std::vector<vpColVector>*>& mapOfPointClouds,
             std::map<std::string, unsigned int>& mapOfPointCloudWidths,
             std::map<std::string, unsigned int>& mapOfPointCloudHeights);
  void track(std::map<std::string, const vpImage<vpRGBa>*>& mapOfColorImages,
             std::map<std::string, const std::vector<vpColVector>*>& mapOfPointClouds,
             std::map<std::string, unsigned int>& mapOfPointCloudWidths,
             std::map<std::string, unsigned int>& mapOfPointCloudHeights);
  /// The same with organised PCL clouds (width x height as the cloud says).
  void track(std::map<std::string, const vpImage<unsigned char>*>& mapOfImages,
             std::map<std::string, std::shared_ptr<const pcl::PointCloud<pcl::PointXYZ>>>& mapOfPointClouds);
  void track(std::map<std::string, const vpImage<vpRGBa>*>& mapOfColorImages,
             std::map<std::string, std::shared_ptr<const pcl::PointCloud<pcl::PointXYZ>>>& mapOfPointClouds);
  /// Colour and depth from one organised, registered cloud: the colour image is the points'
  /// RGB, the depth their Z, both seen by "Camera1" (its parameters serve for the depth).
  void track(const std::shared_ptr<const pcl::PointCloud<pcl::PointXYZRGBA>>& cloud);
  /// A raw depth image of "Camera2" (depth in metres = raw * depthScale, 0: none), without
  /// building a point cloud.
  void track(const vpImage<unsigned char>& I, const vpImage<uint16_t>& I_depth_raw, double depthScale);
  void track(const vpImage<vpRGBa>& I_color, const vpImage<uint16_t>& I_depth_raw, double depthScale);
  /// Throws vpTrackingException::fatalError when the last frame's quality is below the
  /// configured threshold (TrackerParams::quality_threshold).
  void testTracking() override;
  /// Mean score in [0, 1] of the cues on the last frame (1: perfect fit), 0 before tracking.
  double getTrackingQuality() const;
  //@}

  /** @name Results of the last optimisation */
  //@{
  /// Residuals of every cue at the final pose, stacked in the order the cues were added
  /// (units: region pixels, depth metres, texture pixels).
  vpColVector getError() const override;
  /// Their weights in [0, 1], same order.
  vpColVector getRobustWeights() const override;
  /// ViSP's projection error (mean angle in degrees between the model's projected edges and
  /// the image gradients), computed by vpMbTracker on the edges of the .cao files loaded;
  /// throws vpException::notImplementedError when the model has no .cao part.
  double computeCurrentProjectionError(const vpImage<unsigned char>& I, const vpHomogeneousMatrix& cMo,
                                       const vpCameraParameters& cam) override;
  /// Covariance of the pose in ViSP's convention: 6x6 over the camera-frame twist (v, ω),
  /// the inverse of the data Hessian of the last update (setCovarianceComputation(true)).
  vpMatrix getCovarianceMatrix() const override;
  //@}

  /** @name Display */
  //@{
  /// Draws the model's visible edges (creases and silhouette) at cMo.
  void display(const vpImage<unsigned char>& I, const vpHomogeneousMatrix& cMo, const vpCameraParameters& cam,
               const vpColor& col, unsigned int thickness = 1, bool displayFullModel = false) override;
  void display(const vpImage<vpRGBa>& I, const vpHomogeneousMatrix& cMo, const vpCameraParameters& cam,
               const vpColor& col, unsigned int thickness = 1, bool displayFullModel = false) override;
  /// ViSP's format: one {0, i1, j1, i2, j2} per visible edge segment (all edges with
  /// displayFullModel), in pixels of a width x height image.
  std::vector<std::vector<double>> getModelForDisplay(unsigned int width, unsigned int height,
                                                      const vpHomogeneousMatrix& cMo, const vpCameraParameters& cam,
                                                      bool displayFullModel = false) override;
  //@}

 protected:
  /// ViSP's virtual visual servoing hooks: icgp optimises differently (Tracker::track), so
  /// these only gather the final residuals and weights into m_error / m_w.
  void computeVVSInit() override;
  void computeVVSInteractionMatrixAndResidu() override;
  /// Called back by ViSP's .cao parser for each primitive. vpMbTracker has already put the
  /// primitive in `faces` and in the projection-error model (so computeCurrentProjectionError
  /// works as in ViSP's trackers); the triangles icgp tracks come from icgp::load_cao_mesh,
  /// so there is nothing left to do here.
  void initCircle(const vpPoint& p1, const vpPoint& p2, const vpPoint& p3, double radius, int idFace = 0,
                  const std::string& name = "") override;
  void initCylinder(const vpPoint& p1, const vpPoint& p2, double radius, int idFace = 0,
                    const std::string& name = "") override;
  void initFaceFromCorners(vpMbtPolygon& polygon) override;
  void initFaceFromLines(vpMbtPolygon& polygon) override;

 private:
  struct Impl;
  /// The measured depth at a depth pixel (metres; 0, negative or not finite: none), read
  /// only where the cues look.
  using DepthReader = std::function<float(int row, int col)>;
  /// Tracks the colour camera's image with a depth image of depthWidth x depthHeight read
  /// through `read`; `depthFromColorCamera`: seen by "Camera1" itself (one registered cloud).
  /// The map-of-clouds calls of both image types: "Camera2"'s organised cloud, size checked.
  template <typename Image>
  void track_with_clouds(std::map<std::string, const Image*>& images,
                         std::map<std::string, const std::vector<vpColVector>*>& clouds,
                         std::map<std::string, unsigned int>& widths, std::map<std::string, unsigned int>& heights);
  template <typename Image>
  void track_with_depth(std::map<std::string, const Image*>& images, unsigned int depthWidth,
                        unsigned int depthHeight, DepthReader read);
  void track_with_depth(const vpImage<unsigned char>& I, unsigned int depthWidth, unsigned int depthHeight,
                        DepthReader read, bool depthFromColorCamera = false);
  void track_with_depth(const vpImage<vpRGBa>& I, unsigned int depthWidth, unsigned int depthHeight,
                        DepthReader read, bool depthFromColorCamera = false);
  void set_depth(unsigned int width, unsigned int height, DepthReader read, bool depthFromColorCamera);
  void track_current_frame(const vpImage<unsigned char>* grey);
  std::unique_ptr<Impl> impl_;
  vpColVector m_error, m_w;
};
