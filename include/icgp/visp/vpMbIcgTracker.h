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
#include <list>
#include <opencv2/core/types.hpp>
#include <visp3/klt/vpKltOpencv.h>
#include <visp3/mbt/vpMbTracker.h>
#include <visp3/mbt/vpMbtDistanceCircle.h>
#include <visp3/mbt/vpMbtDistanceCylinder.h>
#include <visp3/mbt/vpMbtDistanceKltCylinder.h>
#include <visp3/mbt/vpMbtDistanceKltPoints.h>
#include <visp3/mbt/vpMbtDistanceLine.h>
#include <visp3/mbt/vpMbtFaceDepthNormal.h>
#include <visp3/me/vpMe.h>

#include "icgp/tracker/cue_registry.h"
#include "icgp/tracker/tracker_config.h"

// The PCL overloads take clouds by shared pointer, which is what PCL 1.13's ConstPtr is;
// declaring the types here keeps PCL's slow headers out of every user of this class.
namespace pcl {
struct PointXYZ;
struct PointXYZRGBA;
template <typename PointT>
class PointCloud;
}  // namespace pcl

namespace icgp::visp_detail {
struct DepthInput;
}  // namespace icgp::visp_detail
class vpMbtXmlGenericParser;

/*!
  The ICG+ tracker (region, depth and texture cues fused in one regularised Newton
  optimisation) as a ViSP model-based tracker with vpMbGenericTracker's whole public API:
  a program written for vpMbGenericTracker runs with it by changing the class name.
  docs/visp.md tables every method and what it does here.

  Cameras are vpMbGenericTracker's: named, each with tracker types that say which cues
  read it, EDGE_TRACKER → region (the contour), KLT_TRACKER → texture (keypoints),
  DEPTH_NORMAL_TRACKER or DEPTH_DENSE_TRACKER → depth. The cues of every camera are fused
  in one Newton step; cMo is the reference camera's (the first name in sorted order, as
  in ViSP), the
  others placed with setCameraTransformationMatrix (c_M_reference). The default
  constructor gives one camera "Camera" with every cue (ICG+ on a colour image, and on a
  registered depth image when one is given); vpMbIcgTracker({EDGE_TRACKER | KLT_TRACKER,
  DEPTH_DENSE_TRACKER}) is the usual RGB-D pair "Camera1" (colour) + "Camera2" (depth).
  The cues of a YAML configuration (TrackerConfig::modalities) further select among them.
  A depth camera that gets no depth in a call (track(I), width and height 0) sits the frame
  out; a camera whose colour cues get no image is an error. Camera parameters are used
  without distortion; clouds are read as 3D points.

  Model: loadModel() takes ViSP .cao and .wrl files (parsed by ViSP itself, .wrl through
  Coin3D) and meshes that assimp reads (.obj, .ply, .stl, ...) by extension; repeated calls
  add parts to the same rigid object. The sparse viewpoint models are generated on the
  first initFromPose after a model or parameter change (with progress on std::cerr, a few
  seconds) and cached on disk (TrackerConfig::cache_dir).

  Initialisation is deferred like vpMbGenericTracker's RGB-D use: initFromPose() and
  setPose() store the pose; the next track() call starts the cues on its frame at that pose
  and then tracks that frame.

  ViSP settings of its own cues (moving edges, KLT, depth features, visibility and
  clipping) are stored and returned by their getters; where icgp has a parameter of that
  meaning they set it, otherwise the first call says once on std::cerr that it has no
  effect.

  Errors are ViSP exceptions, and only those (docs/visp.md, "Errors"), each message
  starting with the method's name: vpException::ioError for missing or unreadable files;
  vpException::badValue for unsupported extensions, bad configuration files, unknown camera
  names, invalid tracker types, and images, depth images or clouds of a wrong size (a cloud
  not width x height, a camera's depth not the size of its image, a side 0 or above
  16384); vpException::memoryAllocationError when memory runs out;
  vpTrackingException::initializationError for tracking before loadModel/initFromPose,
  notEnoughPointError when a frame's only data is depth without one valid measurement,
  fatalError when the cues fail on a frame (e.g. the object is out of view where they
  start) and from testTracking() when lost. Exceptions of icgp's core, OpenCV and yaml-cpp
  are translated at the public methods, their message kept.
*/
class vpMbIcgTracker : public vpMbTracker {
 public:
  /// vpMbGenericTracker's tracker types, with its values.
  enum vpTrackerType {
    EDGE_TRACKER = 1 << 0,
    KLT_TRACKER = 1 << 1,
    DEPTH_NORMAL_TRACKER = 1 << 2,
    DEPTH_DENSE_TRACKER = 1 << 3
  };

  /// One camera "Camera" with every cue: EDGE_TRACKER | KLT_TRACKER | DEPTH_DENSE_TRACKER.
  vpMbIcgTracker();
  /// nbCameras cameras of one type, named "Camera" (one) or "Camera1" ... "CameraN".
  vpMbIcgTracker(unsigned int nbCameras, int trackerType = EDGE_TRACKER);
  explicit vpMbIcgTracker(const std::vector<int>& trackerTypes);
  vpMbIcgTracker(const std::vector<std::string>& cameraNames, const std::vector<int>& trackerTypes);
  ~vpMbIcgTracker() override;
  vpMbIcgTracker(const vpMbIcgTracker&) = delete;
  vpMbIcgTracker& operator=(const vpMbIcgTracker&) = delete;

  /** @name Parameters */
  //@{
  /// .yaml / .yml: icgp's tracker parameters (docs/configuration.md); .xml: a ViSP tracker
  /// XML file, whose <camera> block sets the reference camera's parameters.
  void loadConfigFile(const std::string& configFile, bool verbose = true) override;
  /// The first and the second camera's files (each a ViSP XML or icgp's YAML).
  virtual void loadConfigFile(const std::string& configFile1, const std::string& configFile2, bool verbose = true);
  virtual void loadConfigFile(const std::map<std::string, std::string>& mapOfConfigFiles, bool verbose = true);
  void setTrackerConfig(const icgp::TrackerConfig& config);
  const icgp::TrackerConfig& getTrackerConfig() const;
  /// The cues to fuse by name: "region", "depth", "texture", "flow", "edge" or a cue added
  /// with addCue (each on the cameras whose types it reads).
  void setModalities(const std::vector<std::string>& modalities);
  /// A cue of the program's own, fused with the others from now on: registered in
  /// icgp::CueRegistry (so that YAML files and setModalities select it by name, and the
  /// getNbFeatures* counters and getFeaturesForDisplay count and show it as its
  /// visp_features say), then added to this tracker's modalities. A cue registered already
  /// under that name by an earlier addCue is kept; a built-in cue's name is refused.
  void addCue(const icgp::CueEntry& cue);

  virtual void setTrackerType(int type);
  virtual void setTrackerType(const std::map<std::string, int>& mapOfTrackerTypes);
  virtual int getTrackerType() const;
  virtual std::map<std::string, int> getCameraTrackerTypes() const;
  //@}

  /** @name Model */
  //@{
  /// Adds the parts of a .cao / .wrl file or an assimp mesh to the object, placed with T
  /// (model frame points X become T X).
  void loadModel(const std::string& modelFile, bool verbose = false,
                 const vpHomogeneousMatrix& T = vpHomogeneousMatrix()) override;
  /// One rigid object is tracked by every camera: the reference camera's file is loaded.
  /// The others' files should describe the same object (as ViSP's .wrl + .cao of one
  /// object); bounding boxes that differ by more than 1 % of its size are said on std::cerr.
  virtual void loadModel(const std::string& modelFile1, const std::string& modelFile2, bool verbose = false,
                         const vpHomogeneousMatrix& T1 = vpHomogeneousMatrix(),
                         const vpHomogeneousMatrix& T2 = vpHomogeneousMatrix());
  virtual void loadModel(const std::map<std::string, std::string>& mapOfModelFiles, bool verbose = false,
                         const std::map<std::string, vpHomogeneousMatrix>& mapOfT =
                             std::map<std::string, vpHomogeneousMatrix>());
  /// Replaces the model and initialises at cMo.
  virtual void reInitModel(const vpImage<unsigned char>& I, const std::string& cad_name, const vpHomogeneousMatrix& cMo,
                           bool verbose = false, const vpHomogeneousMatrix& T = vpHomogeneousMatrix());
  virtual void reInitModel(const vpImage<vpRGBa>& I_color, const std::string& cad_name,
                           const vpHomogeneousMatrix& cMo, bool verbose = false,
                           const vpHomogeneousMatrix& T = vpHomogeneousMatrix());
  virtual void reInitModel(const vpImage<unsigned char>& I1, const vpImage<unsigned char>& I2,
                           const std::string& cad_name1, const std::string& cad_name2, const vpHomogeneousMatrix& c1Mo,
                           const vpHomogeneousMatrix& c2Mo, bool verbose = false,
                           const vpHomogeneousMatrix& T1 = vpHomogeneousMatrix(),
                           const vpHomogeneousMatrix& T2 = vpHomogeneousMatrix());
  virtual void reInitModel(const vpImage<vpRGBa>& I_color1, const vpImage<vpRGBa>& I_color2,
                           const std::string& cad_name1, const std::string& cad_name2, const vpHomogeneousMatrix& c1Mo,
                           const vpHomogeneousMatrix& c2Mo, bool verbose = false,
                           const vpHomogeneousMatrix& T1 = vpHomogeneousMatrix(),
                           const vpHomogeneousMatrix& T2 = vpHomogeneousMatrix());
  virtual void reInitModel(const std::map<std::string, const vpImage<unsigned char>*>& mapOfImages,
                           const std::map<std::string, std::string>& mapOfModelFiles,
                           const std::map<std::string, vpHomogeneousMatrix>& mapOfCameraPoses, bool verbose = false,
                           const std::map<std::string, vpHomogeneousMatrix>& mapOfT =
                               std::map<std::string, vpHomogeneousMatrix>());
  virtual void reInitModel(const std::map<std::string, const vpImage<vpRGBa>*>& mapOfColorImages,
                           const std::map<std::string, std::string>& mapOfModelFiles,
                           const std::map<std::string, vpHomogeneousMatrix>& mapOfCameraPoses, bool verbose = false,
                           const std::map<std::string, vpHomogeneousMatrix>& mapOfT =
                               std::map<std::string, vpHomogeneousMatrix>());
  /// ViSP's faces of the .cao / .wrl parts (one object: every camera has the same).
  using vpMbTracker::getFaces;
  virtual vpMbHiddenFaces<vpMbtPolygon>& getFaces(const std::string& cameraName);
  using vpMbTracker::getNbPolygon;
  virtual void getNbPolygon(std::map<std::string, unsigned int>& mapOfNbPolygons) const;
  using vpMbTracker::getPolygon;
  virtual vpMbtPolygon* getPolygon(const std::string& cameraName, unsigned int index);
  /// vpMbTracker's faces at the current pose; with useVisibility, ViSP's visibility test
  /// (angles appear/disappear) decides which, as ViSP's trackers compute it each frame.
  std::pair<std::vector<vpPolygon>, std::vector<std::vector<vpPoint>>> getPolygonFaces(
      bool orderPolygons = true, bool useVisibility = true, bool clipPolygon = false) override;
  virtual void getPolygonFaces(std::map<std::string, std::vector<vpPolygon>>& mapOfPolygons,
                               std::map<std::string, std::vector<std::vector<vpPoint>>>& mapOfPoints,
                               bool orderPolygons = true, bool useVisibility = true, bool clipPolygon = false);
  //@}

  /** @name Cameras */
  //@{
  /// The reference camera's parameters.
  void setCameraParameters(const vpCameraParameters& camera) override;
  /// The first and the second camera's.
  virtual void setCameraParameters(const vpCameraParameters& camera1, const vpCameraParameters& camera2);
  virtual void setCameraParameters(const std::map<std::string, vpCameraParameters>& mapOfCameraParameters);
  void getCameraParameters(vpCameraParameters& camera) const override;
  virtual void getCameraParameters(vpCameraParameters& cam1, vpCameraParameters& cam2) const;
  virtual void getCameraParameters(std::map<std::string, vpCameraParameters>& mapOfCameraParameters) const;
  /// cameraName's pose relative to the reference camera (c_M_reference); the reference
  /// camera's must stay the identity.
  virtual void setCameraTransformationMatrix(const std::string& cameraName,
                                             const vpHomogeneousMatrix& cameraTransformationMatrix);
  virtual void setCameraTransformationMatrix(const std::map<std::string, vpHomogeneousMatrix>& mapOfTransformationMatrix);
  virtual std::vector<std::string> getCameraNames() const;
  virtual std::string getReferenceCameraName() const;
  /// Makes another camera the reference: cMo, and every c_M_reference, are then about it,
  /// as in ViSP (the matrices are not converted).
  virtual void setReferenceCameraName(const std::string& referenceCameraName);
  //@}

  /** @name Initialisation */
  //@{
  /// Makes the tracker ready at the current pose (m_cMo): builds the viewpoint models if
  /// needed; the cues start on the next track() call.
  void init(const vpImage<unsigned char>& I) override;
  void initFromPose(const vpImage<unsigned char>& I, const vpHomogeneousMatrix& cMo) override;
  void initFromPose(const vpImage<vpRGBa>& I_color, const vpHomogeneousMatrix& cMo) override;
  using vpMbTracker::initFromPose;
  /// The reference camera's pose file (a camera's other than the reference is moved into it).
  virtual void initFromPose(const vpImage<unsigned char>& I1, const vpImage<unsigned char>& I2,
                            const std::string& initFile1, const std::string& initFile2);
  virtual void initFromPose(const vpImage<vpRGBa>& I_color1, const vpImage<vpRGBa>& I_color2,
                            const std::string& initFile1, const std::string& initFile2);
  virtual void initFromPose(const std::map<std::string, const vpImage<unsigned char>*>& mapOfImages,
                            const std::map<std::string, std::string>& mapOfInitPoses);
  virtual void initFromPose(const std::map<std::string, const vpImage<vpRGBa>*>& mapOfColorImages,
                            const std::map<std::string, std::string>& mapOfInitPoses);
  virtual void initFromPose(const vpImage<unsigned char>& I1, const vpImage<unsigned char>& I2,
                            const vpHomogeneousMatrix& c1Mo, const vpHomogeneousMatrix& c2Mo);
  virtual void initFromPose(const vpImage<vpRGBa>& I_color1, const vpImage<vpRGBa>& I_color2,
                            const vpHomogeneousMatrix& c1Mo, const vpHomogeneousMatrix& c2Mo);
  virtual void initFromPose(const std::map<std::string, const vpImage<unsigned char>*>& mapOfImages,
                            const std::map<std::string, vpHomogeneousMatrix>& mapOfCameraPoses);
  virtual void initFromPose(const std::map<std::string, const vpImage<vpRGBa>*>& mapOfColorImages,
                            const std::map<std::string, vpHomogeneousMatrix>& mapOfCameraPoses);
  /// icgp's extension: finds the object in these images without a given pose
  /// (docs/detection.md) and, when found, starts tracking there (cMo set, the cues started
  /// on this frame; the next track() call follows on). Returns false, leaving cMo as it
  /// was, when nothing is verified: the reason is then in getDetectionMessage(). The
  /// forms mirror track(): the reference camera's grey or colour image, with a raw depth
  /// image, or maps of images and organised clouds. Builds the viewpoint models if needed,
  /// as initFromPose; throws as track() does for unknown cameras and bad depth.
  bool initFromDetection(const vpImage<unsigned char>& I);
  bool initFromDetection(const vpImage<vpRGBa>& I_color);
  bool initFromDetection(const vpImage<unsigned char>& I, const vpImage<uint16_t>& I_depth_raw, double depthScale);
  bool initFromDetection(const vpImage<vpRGBa>& I_color, const vpImage<uint16_t>& I_depth_raw, double depthScale);
  bool initFromDetection(std::map<std::string, const vpImage<unsigned char>*>& mapOfImages,
                         std::map<std::string, const std::vector<vpColVector>*>& mapOfPointClouds,
                         std::map<std::string, unsigned int>& mapOfPointCloudWidths,
                         std::map<std::string, unsigned int>& mapOfPointCloudHeights);
  bool initFromDetection(std::map<std::string, const vpImage<vpRGBa>*>& mapOfColorImages,
                         std::map<std::string, const std::vector<vpColVector>*>& mapOfPointClouds,
                         std::map<std::string, unsigned int>& mapOfPointCloudWidths,
                         std::map<std::string, unsigned int>& mapOfPointCloudHeights);
  /// The last detection's outcome in a sentence: the quality it was verified with, or why
  /// nothing was found.
  std::string getDetectionMessage() const;
  /// After initFromDetection found the object: other poses (cMo) it verified as well as
  /// getPose(), that a symmetry of the object makes indistinguishable from it. Empty for
  /// an object without symmetry, or when nothing was found. A program with a goal (a
  /// servo's desired pose) restarts with initFromPose at the one nearest to it.
  std::vector<vpHomogeneousMatrix> getDetectionEquivalentPoses() const;
  /// icgp's extension: after a loss, search for the object again in the following frames
  /// (near its last trusted pose every frame, the whole image every few), and resume
  /// tracking only on a verified pose; until then testTracking() reports it lost and
  /// getPose() gives the last trusted pose. On by default (TrackerConfig detection.recovery,
  /// docs/detection.md).
  void setRecovery(bool enable);
  bool getRecovery() const;
  using vpMbTracker::initClick;
  /// Clicks in the reference camera's image (or another camera's, moved into the
  /// reference), as ViSP does; needs a display on that image.
  virtual void initClick(const vpImage<unsigned char>& I1, const vpImage<unsigned char>& I2,
                         const std::string& initFile1, const std::string& initFile2, bool displayHelp = false,
                         const vpHomogeneousMatrix& T1 = vpHomogeneousMatrix(),
                         const vpHomogeneousMatrix& T2 = vpHomogeneousMatrix());
  virtual void initClick(const vpImage<vpRGBa>& I_color1, const vpImage<vpRGBa>& I_color2,
                         const std::string& initFile1, const std::string& initFile2, bool displayHelp = false,
                         const vpHomogeneousMatrix& T1 = vpHomogeneousMatrix(),
                         const vpHomogeneousMatrix& T2 = vpHomogeneousMatrix());
  virtual void initClick(const std::map<std::string, const vpImage<unsigned char>*>& mapOfImages,
                         const std::map<std::string, std::string>& mapOfInitFiles, bool displayHelp = false,
                         const std::map<std::string, vpHomogeneousMatrix>& mapOfT =
                             std::map<std::string, vpHomogeneousMatrix>());
  virtual void initClick(const std::map<std::string, const vpImage<vpRGBa>*>& mapOfImages,
                         const std::map<std::string, std::string>& mapOfInitFiles, bool displayHelp = false,
                         const std::map<std::string, vpHomogeneousMatrix>& mapOfT =
                             std::map<std::string, vpHomogeneousMatrix>());
  using vpMbTracker::initFromPoints;
  virtual void initFromPoints(const vpImage<unsigned char>& I1, const vpImage<unsigned char>& I2,
                              const std::string& initFile1, const std::string& initFile2);
  virtual void initFromPoints(const vpImage<vpRGBa>& I_color1, const vpImage<vpRGBa>& I_color2,
                              const std::string& initFile1, const std::string& initFile2);
  virtual void initFromPoints(const std::map<std::string, const vpImage<unsigned char>*>& mapOfImages,
                              const std::map<std::string, std::string>& mapOfInitPoints);
  virtual void initFromPoints(const std::map<std::string, const vpImage<vpRGBa>*>& mapOfColorImages,
                              const std::map<std::string, std::string>& mapOfInitPoints);
  /// Moves the estimate to cdMo; the cues restart there on the next track() call.
  void setPose(const vpImage<unsigned char>& I, const vpHomogeneousMatrix& cdMo) override;
  void setPose(const vpImage<vpRGBa>& I_color, const vpHomogeneousMatrix& cdMo) override;
  virtual void setPose(const vpImage<unsigned char>& I1, const vpImage<unsigned char>& I2,
                       const vpHomogeneousMatrix& c1Mo, const vpHomogeneousMatrix& c2Mo);
  virtual void setPose(const vpImage<vpRGBa>& I_color1, const vpImage<vpRGBa>& I_color2,
                       const vpHomogeneousMatrix& c1Mo, const vpHomogeneousMatrix& c2Mo);
  virtual void setPose(const std::map<std::string, const vpImage<unsigned char>*>& mapOfImages,
                       const std::map<std::string, vpHomogeneousMatrix>& mapOfCameraPoses);
  virtual void setPose(const std::map<std::string, const vpImage<vpRGBa>*>& mapOfColorImages,
                       const std::map<std::string, vpHomogeneousMatrix>& mapOfCameraPoses);
  /// Back to the constructed state: no model, default parameters, cameras' parameters
  /// unset; the cameras, their types and transformation matrices stay, as in ViSP.
  void resetTracker() override;
  //@}

  /** @name Tracking */
  //@{
  /// The reference camera's image; other cameras' depth cues sit the frame out.
  void track(const vpImage<unsigned char>& I) override;
  void track(const vpImage<vpRGBa>& I_color) override;
  /// The first and the second camera's images.
  virtual void track(const vpImage<unsigned char>& I1, const vpImage<unsigned char>& I2);
  virtual void track(const vpImage<vpRGBa>& I_color1, const vpImage<vpRGBa>& I_color2);
  virtual void track(std::map<std::string, const vpImage<unsigned char>*>& mapOfImages);
  virtual void track(std::map<std::string, const vpImage<vpRGBa>*>& mapOfColorImages);
  /// Images and organised point clouds (row major, one vpColVector X, Y, Z in metres per
  /// pixel in the camera's frame; Z <= 0, or any coordinate NaN or infinite, for no
  /// measurement). Width and height 0 mean, as in ViSP, that the camera delivered no depth
  /// this frame; otherwise each is in [1, 16384], the cloud has width x height points, and a
  /// camera given an image too has its depth at the image's size. A depth without one valid
  /// measurement is none (said once on std::cerr); when nothing else has data the frame
  /// throws vpTrackingException::notEnoughPointError, as vpMbGenericTracker's depth trackers.
  virtual void track(std::map<std::string, const vpImage<unsigned char>*>& mapOfImages,
                     std::map<std::string, const std::vector<vpColVector>*>& mapOfPointClouds,
                     std::map<std::string, unsigned int>& mapOfPointCloudWidths,
                     std::map<std::string, unsigned int>& mapOfPointCloudHeights);
  virtual void track(std::map<std::string, const vpImage<vpRGBa>*>& mapOfColorImages,
                     std::map<std::string, const std::vector<vpColVector>*>& mapOfPointClouds,
                     std::map<std::string, unsigned int>& mapOfPointCloudWidths,
                     std::map<std::string, unsigned int>& mapOfPointCloudHeights);
  /// The same with organised PCL clouds (width x height as the cloud says).
  virtual void track(std::map<std::string, const vpImage<unsigned char>*>& mapOfImages,
                     std::map<std::string, std::shared_ptr<const pcl::PointCloud<pcl::PointXYZ>>>& mapOfPointClouds);
  virtual void track(std::map<std::string, const vpImage<vpRGBa>*>& mapOfColorImages,
                     std::map<std::string, std::shared_ptr<const pcl::PointCloud<pcl::PointXYZ>>>& mapOfPointClouds);
  /// icgp's extension: colour and depth of the reference camera from one organised,
  /// registered cloud (its RGB and its points).
  void track(const std::shared_ptr<const pcl::PointCloud<pcl::PointXYZRGBA>>& cloud);
  /// icgp's extension: the reference camera's image and a raw depth image (metres = raw *
  /// depthScale, 0: none) of the depth camera (the reference camera itself in a one-camera
  /// rig, else the first other camera with a depth type), without building a point cloud.
  void track(const vpImage<unsigned char>& I, const vpImage<uint16_t>& I_depth_raw, double depthScale);
  void track(const vpImage<vpRGBa>& I_color, const vpImage<uint16_t>& I_depth_raw, double depthScale);
  /// Throws vpTrackingException::fatalError when the last frame's quality is below the
  /// configured threshold (TrackerParams::quality_threshold).
  void testTracking() override;
  /// Median score in [0, 1] of the cues on the last frame (1: perfect fit), 0 before tracking.
  double getTrackingQuality() const;
  /// icgp's extension: how one of the object's cues fit the last frame tracked (the
  /// quality combines their scores): its name ("region", "depth", ...), the camera it reads,
  /// and its score, noise sigma, valid fraction and whether it had data
  /// (icgp::ModalityQuality).
  struct CueQuality {
    std::string cue;
    std::string camera;
    icgp::ModalityQuality quality;
  };
  /// The object's cues on the last frame tracked, in the order they were added; empty
  /// before the first track() (a detection alone tracks no frame).
  std::vector<CueQuality> getCueQualities() const;
  /// Pixels the cues may use (true), for every camera whose images have the mask's size.
  void setMask(const vpImage<bool>& mask) override;
  //@}

  /** @name icgp's extension: several bodies */
  //@{
  /// The name of the object whose pose is cMo (getPose, initFromPose): "object". Bodies
  /// added below may hang from it (Joint::parent).
  static const std::string& getReferenceBodyName();
  /// Tracks a further body (a mesh or .cao file, metres) with the same cues, in the same
  /// frames, alongside the object: a free body with its own 6-DoF pose (set it with
  /// setBodyPose before initFromPose), or, with a joint, a link of the kinematic tree of
  /// joint.parent (the object or another body), whose pose and joint values are solved
  /// together with its root's. Bodies of the YAML configuration's `bodies:` list are added
  /// the same way. Each body hides what lies behind it from the others' cues (modeled
  /// occlusions). Throws vpException::badValue naming the body and the field for a name
  /// already taken, an unknown parent, or limits with min > max; a mesh that cannot be
  /// read is reported by initFromPose(), naming the body.
  void addBody(const std::string& name, const std::string& modelFile);
  void addBody(const std::string& name, const std::string& modelFile, const icgp::Joint& joint);
  /// A body that is rendered (it hides the tracked bodies behind it: a hand, a tool, the
  /// robot's own links) but not tracked: set its pose with setBodyPose before each track().
  void addOccluder(const std::string& name, const std::string& modelFile);
  /// The names of the added bodies and occluders, in the order they were added.
  std::vector<std::string> getBodyNames() const;
  /// Sets body `name`'s pose in the reference camera (cMb): a free body's initial pose (as
  /// initFromPose sets cMo; also applied by a later initFromPose), or an occluder's pose
  /// for the next frames. The object's own name sets cMo. Links follow their joints.
  void setBodyPose(const std::string& name, const vpHomogeneousMatrix& cMb);
  /// Body `name`'s pose in the reference camera after the last frame (cMb): tracked, or as
  /// set for occluders; the object's name gives cMo.
  vpHomogeneousMatrix getBodyPose(const std::string& name) const;
  /// Whether body `name`'s quality on the last frame reached the quality threshold (the
  /// object's: testTracking()'s verdict), and that quality in [0, 1].
  bool isBodyTracked(const std::string& name) const;
  double getBodyTrackingQuality(const std::string& name) const;
  /// A link's joint values (radians, metres) after the last frame, in the order of its
  /// joint's directions; set them before initFromPose to start from them (clamped into the
  /// joint's limits).
  std::vector<double> getJointValues(const std::string& name) const;
  void setJointValues(const std::string& name, const std::vector<double>& values);
  //@}

  /** @name Results of the last optimisation */
  //@{
  using vpMbTracker::getPose;
  /// The first and the second camera's poses of the object.
  virtual void getPose(vpHomogeneousMatrix& c1Mo, vpHomogeneousMatrix& c2Mo) const;
  virtual void getPose(std::map<std::string, vpHomogeneousMatrix>& mapOfCameraPoses) const;
  /// Residuals of every cue at the final pose, camera by camera in the order the cues were
  /// added (units: region pixels, depth metres, texture pixels).
  vpColVector getError() const override;
  /// Their weights in [0, 1], same order.
  vpColVector getRobustWeights() const override;
  /// Correspondences of the last frame: region contour points (ViSP's moving edges),
  /// texture matches (ViSP's KLT points), depth points.
  virtual unsigned int getNbFeaturesEdge() const;
  virtual unsigned int getNbFeaturesKlt() const;
  virtual unsigned int getNbFeaturesDepthNormal() const;
  virtual unsigned int getNbFeaturesDepthDense() const;
  /// The reference camera's region contour points (ViSP's moving edges).
  virtual unsigned int getNbPoints(unsigned int level = 0) const;
  virtual void getNbPoints(std::map<std::string, unsigned int>& mapOfNbPoints, unsigned int level = 0) const;
  /// ViSP's format, in the reference camera: {0, i, j, state} per region contour point
  /// (state 0, vpMeSite::NO_SUPPRESSION, for a correspondence of full weight, 4 (M_ESTIMATOR)
  /// for a down-weighted one), {1, i, j, id} per texture match.
  virtual std::vector<std::vector<double>> getFeaturesForDisplay();
  virtual void getFeaturesForDisplay(std::map<std::string, std::vector<std::vector<double>>>& mapOfFeatures);
  /// The reference camera's texture matches, as ViSP's KLT points.
  virtual std::vector<vpImagePoint> getKltImagePoints() const;
  virtual std::map<int, vpImagePoint> getKltImagePointsWithId() const;
  virtual int getKltNbPoints() const;
  virtual std::vector<cv::Point2f> getKltPoints() const;
  /// ViSP's projection error (mean angle in degrees between the model's projected edges and
  /// the image gradients), computed by vpMbTracker on the edges of the .cao / .wrl parts;
  /// throws vpException::notImplementedError when the model has none.
  double computeCurrentProjectionError(const vpImage<unsigned char>& I, const vpHomogeneousMatrix& cMo,
                                       const vpCameraParameters& cam) override;
  virtual double computeCurrentProjectionError(const vpImage<vpRGBa>& I, const vpHomogeneousMatrix& cMo,
                                               const vpCameraParameters& cam);
  /// Covariance of the pose in ViSP's convention: 6x6 over the camera-frame twist (v, ω),
  /// the inverse of the data Hessian of the last update (setCovarianceComputation(true)).
  vpMatrix getCovarianceMatrix() const override;
  /// ViSP's primitives of its own cues: icgp tracks none, so the lists are empty.
  virtual std::list<vpMbtDistanceCircle*>& getFeaturesCircle();
  virtual std::list<vpMbtDistanceKltCylinder*>& getFeaturesKltCylinder();
  virtual std::list<vpMbtDistanceKltPoints*>& getFeaturesKlt();
  virtual void getLcircle(std::list<vpMbtDistanceCircle*>& circlesList, unsigned int level = 0) const;
  virtual void getLcircle(const std::string& cameraName, std::list<vpMbtDistanceCircle*>& circlesList,
                          unsigned int level = 0) const;
  virtual void getLcylinder(std::list<vpMbtDistanceCylinder*>& cylindersList, unsigned int level = 0) const;
  virtual void getLcylinder(const std::string& cameraName, std::list<vpMbtDistanceCylinder*>& cylindersList,
                            unsigned int level = 0) const;
  virtual void getLline(std::list<vpMbtDistanceLine*>& linesList, unsigned int level = 0) const;
  virtual void getLline(const std::string& cameraName, std::list<vpMbtDistanceLine*>& linesList,
                        unsigned int level = 0) const;
  //@}

  /** @name Display */
  //@{
  /// Draws the model's visible edges (creases and silhouette) at cMo.
  void display(const vpImage<unsigned char>& I, const vpHomogeneousMatrix& cMo, const vpCameraParameters& cam,
               const vpColor& col, unsigned int thickness = 1, bool displayFullModel = false) override;
  void display(const vpImage<vpRGBa>& I, const vpHomogeneousMatrix& cMo, const vpCameraParameters& cam,
               const vpColor& col, unsigned int thickness = 1, bool displayFullModel = false) override;
  virtual void display(const vpImage<unsigned char>& I1, const vpImage<unsigned char>& I2,
                       const vpHomogeneousMatrix& c1Mo, const vpHomogeneousMatrix& c2Mo,
                       const vpCameraParameters& cam1, const vpCameraParameters& cam2, const vpColor& color,
                       unsigned int thickness = 1, bool displayFullModel = false);
  virtual void display(const vpImage<vpRGBa>& I1, const vpImage<vpRGBa>& I2, const vpHomogeneousMatrix& c1Mo,
                       const vpHomogeneousMatrix& c2Mo, const vpCameraParameters& cam1,
                       const vpCameraParameters& cam2, const vpColor& color, unsigned int thickness = 1,
                       bool displayFullModel = false);
  virtual void display(const std::map<std::string, const vpImage<unsigned char>*>& mapOfImages,
                       const std::map<std::string, vpHomogeneousMatrix>& mapOfCameraPoses,
                       const std::map<std::string, vpCameraParameters>& mapOfCameraParameters, const vpColor& col,
                       unsigned int thickness = 1, bool displayFullModel = false);
  virtual void display(const std::map<std::string, const vpImage<vpRGBa>*>& mapOfImages,
                       const std::map<std::string, vpHomogeneousMatrix>& mapOfCameraPoses,
                       const std::map<std::string, vpCameraParameters>& mapOfCameraParameters, const vpColor& col,
                       unsigned int thickness = 1, bool displayFullModel = false);
  /// ViSP's format: one {0, i1, j1, i2, j2} per visible edge segment (all edges with
  /// displayFullModel), in pixels of a width x height image.
  std::vector<std::vector<double>> getModelForDisplay(unsigned int width, unsigned int height,
                                                      const vpHomogeneousMatrix& cMo, const vpCameraParameters& cam,
                                                      bool displayFullModel = false) override;
  virtual void getModelForDisplay(std::map<std::string, std::vector<std::vector<double>>>& mapOfModels,
                                  const std::map<std::string, unsigned int>& mapOfwidths,
                                  const std::map<std::string, unsigned int>& mapOfheights,
                                  const std::map<std::string, vpHomogeneousMatrix>& mapOfcMos,
                                  const std::map<std::string, vpCameraParameters>& mapOfCams,
                                  bool displayFullModel = false);
  //@}

  /** @name Settings of ViSP's own cues: stored, mapped where icgp has that meaning */
  //@{
  void setAngleAppear(const double& a) override;
  virtual void setAngleAppear(const double& a1, const double& a2);
  virtual void setAngleAppear(const std::map<std::string, double>& mapOfAngles);
  void setAngleDisappear(const double& a) override;
  virtual void setAngleDisappear(const double& a1, const double& a2);
  virtual void setAngleDisappear(const std::map<std::string, double>& mapOfAngles);
  void setClipping(const unsigned int& flags) override;
  virtual void setClipping(const unsigned int& flags1, const unsigned int& flags2);
  virtual void setClipping(const std::map<std::string, unsigned int>& mapOfClippingFlags);
  using vpMbTracker::getClipping;
  virtual void getClipping(unsigned int& clippingFlag1, unsigned int& clippingFlag2) const;
  virtual void getClipping(std::map<std::string, unsigned int>& mapOfClippingFlags) const;
  void setNearClippingDistance(const double& dist) override;
  virtual void setNearClippingDistance(const double& dist1, const double& dist2);
  virtual void setNearClippingDistance(const std::map<std::string, double>& mapOfDists);
  void setFarClippingDistance(const double& dist) override;
  virtual void setFarClippingDistance(const double& dist1, const double& dist2);
  virtual void setFarClippingDistance(const std::map<std::string, double>& mapOfClippingDists);
  virtual void setDepthDenseFilteringMaxDistance(double maxDistance);
  virtual void setDepthDenseFilteringMethod(int method);
  virtual void setDepthDenseFilteringMinDistance(double minDistance);
  virtual void setDepthDenseFilteringOccupancyRatio(double occupancyRatio);
  virtual void setDepthDenseSamplingStep(unsigned int stepX, unsigned int stepY);
  virtual void setDepthNormalFaceCentroidMethod(const vpMbtFaceDepthNormal::vpFaceCentroidType& method);
  virtual void setDepthNormalFeatureEstimationMethod(const vpMbtFaceDepthNormal::vpFeatureEstimationType& method);
  virtual void setDepthNormalPclPlaneEstimationMethod(int method);
  virtual void setDepthNormalPclPlaneEstimationRansacMaxIter(int maxIter);
  virtual void setDepthNormalPclPlaneEstimationRansacThreshold(double threshold);
  virtual void setDepthNormalSamplingStep(unsigned int stepX, unsigned int stepY);
  void setDisplayFeatures(bool displayF) override;
  virtual void setFeatureFactors(const std::map<vpTrackerType, double>& mapOfFeatureFactors);
  virtual void setGoodMovingEdgesRatioThreshold(double threshold);
  virtual double getGoodMovingEdgesRatioThreshold() const;
  /// KLT's maximum number of features sets the texture cue's (TextureParams::orb_n_features).
  virtual void setKltOpencv(const vpKltOpencv& t);
  virtual void setKltOpencv(const vpKltOpencv& t1, const vpKltOpencv& t2);
  virtual void setKltOpencv(const std::map<std::string, vpKltOpencv>& mapOfKlts);
  virtual vpKltOpencv getKltOpencv() const;
  virtual void getKltOpencv(vpKltOpencv& klt1, vpKltOpencv& klt2) const;
  virtual void getKltOpencv(std::map<std::string, vpKltOpencv>& mapOfKlts) const;
  virtual void setKltMaskBorder(const unsigned int& e);
  virtual void setKltMaskBorder(const unsigned int& e1, const unsigned int& e2);
  virtual void setKltMaskBorder(const std::map<std::string, unsigned int>& mapOfErosions);
  virtual unsigned int getKltMaskBorder() const;
  virtual void setKltThresholdAcceptation(double th);
  virtual double getKltThresholdAcceptation() const;
  void setLod(bool useLod, const std::string& name = "") override;
  void setMinLineLengthThresh(double minLineLengthThresh, const std::string& name = "") override;
  void setMinPolygonAreaThresh(double minPolygonAreaThresh, const std::string& name = "") override;
  virtual void setMovingEdge(const vpMe& me);
  virtual void setMovingEdge(const vpMe& me1, const vpMe& me2);
  virtual void setMovingEdge(const std::map<std::string, vpMe>& mapOfMe);
  virtual vpMe getMovingEdge() const;
  virtual void getMovingEdge(vpMe& me1, vpMe& me2) const;
  virtual void getMovingEdge(std::map<std::string, vpMe>& mapOfMovingEdges) const;
  void setOgreShowConfigDialog(bool showConfigDialog) override;
  void setOgreVisibilityTest(const bool& v) override;
  void setOptimizationMethod(const vpMbtOptimizationMethod& opt) override;
  void setProjectionErrorComputation(const bool& flag) override;
  void setProjectionErrorDisplay(bool display) override;
  void setProjectionErrorDisplayArrowLength(unsigned int length) override;
  void setProjectionErrorDisplayArrowThickness(unsigned int thickness) override;
  /// Accepted, and reported once on stderr as having no effect: the cues' visibility comes
  /// from the viewpoint models rendered from the mesh, exact for every face.
  void setScanLineVisibilityTest(const bool& v) override;
  virtual void setUseDepthDenseTracking(const std::string& name, const bool& useDepthDenseTracking);
  virtual void setUseDepthNormalTracking(const std::string& name, const bool& useDepthNormalTracking);
  virtual void setUseEdgeTracking(const std::string& name, const bool& useEdgeTracking);
  virtual void setUseKltTracking(const std::string& name, const bool& useKltTracking);
  //@}

 protected:
  /// ViSP's virtual visual servoing hooks: icgp optimises differently (Tracker::track), so
  /// these only gather the final residuals and weights into m_error / m_w.
  void computeVVSInit() override;
  void computeVVSInteractionMatrixAndResidu() override;
  /// Called back by ViSP's .cao / .wrl parser for each primitive during loadModel, the one
  /// pass over the file. vpMbTracker has already put it in `faces` and in the
  /// projection-error model (so computeCurrentProjectionError works as in ViSP's trackers);
  /// these also mesh it into the triangles icgp tracks.
  void initCircle(const vpPoint& p1, const vpPoint& p2, const vpPoint& p3, double radius, int idFace = 0,
                  const std::string& name = "") override;
  void initCylinder(const vpPoint& p1, const vpPoint& p2, double radius, int idFace = 0,
                    const std::string& name = "") override;
  void initFaceFromCorners(vpMbtPolygon& polygon) override;
  void initFaceFromLines(vpMbtPolygon& polygon) override;

 private:
  /// addBody / addOccluder: the body appended to the configuration's list once its name,
  /// parent and joint are checked.
  void add_body_config(icgp::BodyConfig body);
  /// The configured body `name`; vpException::badValue listing the bodies otherwise.
  const icgp::BodyConfig& body_config(const std::string& name, const std::string& call) const;
  struct Impl;
  using DepthInput = icgp::visp_detail::DepthInput;
  /// One frame: the images go to their cameras, the depth inputs to theirs, every other
  /// depth camera delivers none; then the tracking step. Unknown cameras, and colour cues
  /// without an image, are refused naming `call`.
  template <typename Image>
  void track_frame(const std::map<std::string, const Image*>& images, const std::vector<DepthInput>& depths,
                   const std::string& call);
  /// The frame's images and depth by camera; the reference camera's grey image, if given.
  template <typename Image>
  const vpImage<unsigned char>* assemble_frame(const std::map<std::string, const Image*>& images,
                                               const std::vector<DepthInput>& depths, const std::string& call);
  template <typename Image>
  void init_from_poses(const std::map<std::string, const Image*>& images,
                       const std::map<std::string, vpHomogeneousMatrix>& poses, const std::string& call);
  template <typename Image>
  void init_from_pose_files(const std::map<std::string, const Image*>& images,
                            const std::map<std::string, std::string>& files, const std::string& call);
  /// initClick and initFromPoints of the maps, grey or colour: ViSP's own initialisation in
  /// the camera of the reference's file (else the first), then the reference's pose.
  template <typename Image>
  void init_click(const std::map<std::string, const Image*>& images, const std::map<std::string, std::string>& files,
                  bool displayHelp, const std::map<std::string, vpHomogeneousMatrix>& mapOfT);
  template <typename Image>
  void init_from_points(const std::map<std::string, const Image*>& images,
                        const std::map<std::string, std::string>& points);
  /// The reference camera's pose of the object from one camera's.
  vpHomogeneousMatrix reference_pose(const std::string& camera, const vpHomogeneousMatrix& cMo,
                                     const std::string& call) const;
  void track_step(const vpImage<unsigned char>* grey, const std::string& call);
  /// The depth inputs of ViSP's maps of organised clouds (checked: sizes, null clouds),
  /// read through the cameras' cloud readers, whose frames this starts.
  std::vector<DepthInput> cloud_depth_inputs(const std::map<std::string, const std::vector<vpColVector>*>& clouds,
                                             std::map<std::string, unsigned int>& widths,
                                             std::map<std::string, unsigned int>& heights);
  /// The depth input of a raw depth image (metres = raw * depthScale) of the raw-depth camera.
  DepthInput raw_depth_input(const vpImage<uint16_t>& I_depth_raw, double depthScale, const std::string& call) const;
  /// initFromDetection: the frame assembled as track() does, then detected.
  template <typename Image>
  bool detect_frame(const std::map<std::string, const Image*>& images, const std::vector<DepthInput>& depths,
                    const std::string& call);
  /// Builds the cues' tracker for the current model, configuration and rig, if needed.
  void build_tracker();
  /// The camera a raw depth image belongs to: the reference camera if it has a depth type,
  /// else the first camera that has one.
  std::string depth_camera_of_raw_depth() const;
  /// The tracker's cues that ViSP's `features` stand for (the cue registry's VispFeatures:
  /// region and edge for moving edges, texture and flow for KLT, ...), of `camera` or all.
  std::vector<const icgp::Modality*> cues_counted_as(icgp::VispFeatures features, const std::string& camera = "") const;
  /// The correspondences those cues summed over in the last update, of `camera` or all; for
  /// depth, of the cameras whose types count them as `depth_type` (0: all).
  unsigned int count_features(icgp::VispFeatures features, const std::string& camera = "", int depth_type = 0) const;
  /// ViSP's getFeaturesForDisplay format for one camera.
  std::vector<std::vector<double>> features_for_display(const std::string& camera) const;
  /// Keeps a ViSP XML file's settings of ViSP's own cues for their getters; the reference
  /// camera's KLT settings become the flow cue's.
  void store_visp_xml_settings(const std::string& camera, const vpMbtXmlGenericParser& parser);
  /// Gives the flow cue a KLT tracker's settings and mask border.
  void apply_klt_settings(const vpKltOpencv& klt, unsigned int mask_border);
  /// Forgets the model (reInitModel loads another).
  void clear_model();
  std::unique_ptr<Impl> impl_;
  vpColVector m_error, m_w;
};
