// SPDX-License-Identifier: GPL-2.0-or-later
// vpMbIcgTracker's API is vpMbGenericTracker's (ViSP 3.5, installed header
// visp3/mbt/vpMbGenericTracker.h, built with KLT and GUI, without PCL and Ogre), so that it
// cannot silently shrink or drift from ViSP's:
//  * at compile time, every public method of that header, overload by overload, is taken
//    with ViSP's exact signature from BOTH classes (so the signature written here is proven
//    to be ViSP's, and vpMbIcgTracker proven to have it), the calls that rely on ViSP's
//    default arguments compile the same, and the enum values are ViSP's;
//  * at run time, every camera, two-camera and map overload is called and checked against
//    vpMbGenericTracker itself where ViSP answers the same question (its constructors and
//    settings are cheap), or against geometry; the settings without effect round-trip,
//    are reported once, and leave the tracked pose bit-identical; every refused call is a
//    vpException naming the call and the offending value, never a std:: exception.
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <sstream>
#include <type_traits>
#include <visp3/core/vpException.h>
#include <visp3/core/vpImageConvert.h>
#include <visp3/core/vpMeterPixelConversion.h>
#include <visp3/core/vpPolygon3D.h>
#include <visp3/core/vpPoseVector.h>
#include <visp3/core/vpTrackingException.h>
#include <visp3/mbt/vpMbGenericTracker.h>

#include "icgp/eval/metrics.h"
#include "icgp/visp/conversions.h"
#include "icgp/visp/rgbd_tracking_loop.h"
#include "icgp/base/standard_stream_capture.h"
#include "test_temp_dir.h"
#include "vpmbicgtracker_test_setup.h"

using namespace icgp;
using icgp::test::vp_exception_of;
using Catch::Matchers::Contains;

// =====================================================================================
// 1. Signatures, at compile time
// =====================================================================================
//
// Covered, grouped and ordered as in the installed vpMbGenericTracker.h (public section;
// the protected computeVVS*, init*, preTracking hooks are not API; the VISP_HAVE_PCL and
// VISP_HAVE_OGRE blocks are not compiled in Debian's ViSP 3.5, so not API either):
//   enum vpTrackerType: EDGE_TRACKER, KLT_TRACKER, DEPTH_NORMAL_TRACKER, DEPTH_DENSE_TRACKER
//   constructors: (), (unsigned int, int = EDGE_TRACKER), explicit (vector<int>),
//                 (vector<string>, vector<int>); virtual destructor
//   computeCurrentProjectionError: grey, RGBa
//   display: grey, RGBa, two grey, two RGBa, map grey, map RGBa
//   getCameraNames
//   getCameraParameters: (cam) [also vpMbTracker's via using], (cam1, cam2), (map)
//   getCameraTrackerTypes
//   getClipping: () [vpMbTracker's via using], (flag1, flag2), (map)
//   getError
//   getFaces: (), (name)
//   getFeaturesCircle, getFeaturesKltCylinder, getFeaturesKlt
//   getFeaturesForDisplay: (), (map)
//   getGoodMovingEdgesRatioThreshold
//   getKltImagePoints, getKltImagePointsWithId, getKltMaskBorder, getKltNbPoints
//   getKltOpencv: (), (klt1, klt2), (map)
//   getKltPoints, getKltThresholdAcceptation
//   getLcircle: (list, level), (name, list, level); getLcylinder: same two; getLline: same two
//   getModelForDisplay: (width, height, cMo, cam, full), (maps..., full)
//   getMovingEdge: (), (me1, me2), (map)
//   getNbFeaturesDepthDense, getNbFeaturesDepthNormal, getNbFeaturesEdge, getNbFeaturesKlt
//   getNbPoints: (level), (map, level)
//   getNbPolygon: (), (map)
//   getPolygon: (index), (name, index)
//   getPolygonFaces: (order, visibility, clip), (map, map, order, visibility, clip)
//   getPose: () [vpMbTracker's via using], (cMo), (c1Mo, c2Mo), (map)
//   getReferenceCameraName, getRobustWeights, getTrackerType
//   init
//   initClick [GUI]: vpMbTracker's via using: (I, file, help, T), (I_color, file, help, T),
//                    (I, points3D, displayFile), (I_color, points3D, displayFile);
//                    (I1, I2, ...), (I_color1, I_color2, ...), (map grey), (map RGBa)
//   initFromPoints: vpMbTracker's via using: (I, file), (I_color, file), (I, 2D, 3D),
//                   (I_color, 2D, 3D); (I1, I2, files), (I_color1, I_color2, files),
//                   (map grey), (map RGBa)
//   initFromPose: vpMbTracker's via using: (I, file), (I_color, file), (I_color, cMo),
//                 (I, vpPoseVector), (I_color, vpPoseVector); (I, cMo), (I1, I2, files),
//                 (I_color1, I_color2, files), (map grey, files), (map RGBa, files),
//                 (I1, I2, poses), (I_color1, I_color2, poses), (map grey, poses), (map RGBa, poses)
//   loadConfigFile: (file, verbose), (file1, file2, verbose), (map, verbose)
//   loadModel: (file, verbose, T), (file1, file2, verbose, T1, T2), (map, verbose, map T)
//   reInitModel: grey, RGBa, two grey, two RGBa, map grey, map RGBa
//   resetTracker
//   setAngleAppear, setAngleDisappear: (a), (a1, a2), (map) each
//   setCameraParameters: (cam), (cam1, cam2), (map)
//   setCameraTransformationMatrix: (name, M), (map)
//   setClipping: (flags), (flags1, flags2), (map)
//   setDepthDenseFilteringMaxDistance, ...Method, ...MinDistance, ...OccupancyRatio,
//   setDepthDenseSamplingStep
//   setDepthNormalFaceCentroidMethod, ...FeatureEstimationMethod, ...PclPlaneEstimationMethod,
//   ...PclPlaneEstimationRansacMaxIter, ...PclPlaneEstimationRansacThreshold, ...SamplingStep
//   setDisplayFeatures
//   setFarClippingDistance: (d), (d1, d2), (map)
//   setFeatureFactors (the map's key is the class's own vpTrackerType: see below)
//   setGoodMovingEdgesRatioThreshold
//   setKltMaskBorder: (e), (e1, e2), (map); setKltOpencv: (t), (t1, t2), (map);
//   setKltThresholdAcceptation
//   setLod, setMask, setMinLineLengthThresh, setMinPolygonAreaThresh
//   setMovingEdge: (me), (me1, me2), (map)
//   setNearClippingDistance: (d), (d1, d2), (map)
//   setOgreShowConfigDialog, setOgreVisibilityTest, setOptimizationMethod
//   setPose: grey, RGBa, two grey, two RGBa, map grey, map RGBa
//   setProjectionErrorComputation, setProjectionErrorDisplay,
//   setProjectionErrorDisplayArrowLength, setProjectionErrorDisplayArrowThickness
//   setReferenceCameraName, setScanLineVisibilityTest
//   setTrackerType: (type), (map)
//   setUseDepthDenseTracking, setUseDepthNormalTracking, setUseEdgeTracking, setUseKltTracking
//   testTracking
//   track: grey, RGBa, two grey, two RGBa, map grey, map RGBa, map grey + clouds,
//          map RGBa + clouds
// icgp's extensions (vpMbIcgTracker only): setTrackerConfig, getTrackerConfig,
// setModalities, getTrackingQuality, track(I, I_depth_raw, scale) grey and RGBa,
// track(registered XYZRGBA cloud), track(map, map of PCL XYZ clouds) grey and RGBa.

namespace api {

template <class T>
T& arg();  // only for unevaluated operands

using Grey = vpImage<unsigned char>;
using Rgba = vpImage<vpRGBa>;
using M = vpHomogeneousMatrix;
using Cam = vpCameraParameters;
using Str = std::string;
using GreyMap = std::map<std::string, const Grey*>;
using RgbaMap = std::map<std::string, const Rgba*>;
using StrMap = std::map<std::string, std::string>;
using PoseMap = std::map<std::string, vpHomogeneousMatrix>;
using CamMap = std::map<std::string, vpCameraParameters>;
using UIntMap = std::map<std::string, unsigned int>;
using DoubleMap = std::map<std::string, double>;
using IntMap = std::map<std::string, int>;
using Lines = std::vector<std::vector<double>>;
using LinesMap = std::map<std::string, Lines>;
using CloudMap = std::map<std::string, const std::vector<vpColVector>*>;
using PolygonsMap = std::map<std::string, std::vector<vpPolygon>>;
using PointsMap = std::map<std::string, std::vector<std::vector<vpPoint>>>;
using PolygonFaces = std::pair<std::vector<vpPolygon>, std::vector<std::vector<vpPoint>>>;
using KltMap = std::map<std::string, vpKltOpencv>;
using MeMap = std::map<std::string, vpMe>;
using IdPoints = std::map<int, vpImagePoint>;
using Faces = vpMbHiddenFaces<vpMbtPolygon>;
using Circles = std::list<vpMbtDistanceCircle*>;
using Cylinders = std::list<vpMbtDistanceCylinder*>;
using LinesList = std::list<vpMbtDistanceLine*>;
using KltCylinders = std::list<vpMbtDistanceKltCylinder*>;
using KltPoints = std::list<vpMbtDistanceKltPoints*>;
using Names = std::vector<std::string>;
using ImagePoints = std::vector<vpImagePoint>;
using Points3D = std::vector<vpPoint>;
using CvPoints = std::vector<cv::Point2f>;
using PclXyzMap = std::map<std::string, std::shared_ptr<const pcl::PointCloud<pcl::PointXYZ>>>;
using PclXyzrgba = std::shared_ptr<const pcl::PointCloud<pcl::PointXYZRGBA>>;
using Raw = vpImage<uint16_t>;

}  // namespace api

/// One overload, taken from both classes with the same member-function-pointer type: fails
/// to compile unless ViSP has exactly this signature and vpMbIcgTracker has it too.
#define ICGP_SAME_SIGNATURE(R, NAME, ARGS, ...)                                  \
  [] {                                                                           \
    R (vpMbGenericTracker::*visp) ARGS __VA_ARGS__ = &vpMbGenericTracker::NAME; \
    R (vpMbIcgTracker::*ours) ARGS __VA_ARGS__ = &vpMbIcgTracker::NAME;         \
    return visp != nullptr && ours != nullptr;                                   \
  }()

/// An icgp extension: vpMbIcgTracker only.
#define ICGP_EXTENSION(R, NAME, ARGS, ...)                               \
  [] {                                                                   \
    R (vpMbIcgTracker::*ours) ARGS __VA_ARGS__ = &vpMbIcgTracker::NAME; \
    return ours != nullptr;                                              \
  }()

/// A call written as ViSP programs write it, relying on ViSP's default arguments: it must
/// compile for both classes and have the same type.
#define ICGP_SAME_CALL(...)                                                                     \
  static_assert(std::is_same_v<decltype(api::arg<vpMbGenericTracker>().__VA_ARGS__),           \
                               decltype(api::arg<vpMbIcgTracker>().__VA_ARGS__)>,              \
                #__VA_ARGS__)

namespace {

using namespace api;

// ---- the enum, with ViSP's values
static_assert(int{vpMbIcgTracker::EDGE_TRACKER} == int{vpMbGenericTracker::EDGE_TRACKER});
static_assert(int{vpMbIcgTracker::KLT_TRACKER} == int{vpMbGenericTracker::KLT_TRACKER});
static_assert(int{vpMbIcgTracker::DEPTH_NORMAL_TRACKER} == int{vpMbGenericTracker::DEPTH_NORMAL_TRACKER});
static_assert(int{vpMbIcgTracker::DEPTH_DENSE_TRACKER} == int{vpMbGenericTracker::DEPTH_DENSE_TRACKER});

// ---- the class and its constructors, with ViSP's argument types and explicitness
static_assert(std::is_base_of_v<vpMbTracker, vpMbIcgTracker>);
static_assert(std::has_virtual_destructor_v<vpMbIcgTracker>);
static_assert(std::is_default_constructible_v<vpMbIcgTracker>);
static_assert(std::is_constructible_v<vpMbIcgTracker, unsigned int>);  // trackerType's default
static_assert(std::is_constructible_v<vpMbIcgTracker, unsigned int, int>);
static_assert(std::is_constructible_v<vpMbIcgTracker, const std::vector<int>&>);
static_assert(std::is_constructible_v<vpMbIcgTracker, const std::vector<std::string>&, const std::vector<int>&>);
static_assert(std::is_convertible_v<unsigned int, vpMbIcgTracker> ==
              std::is_convertible_v<unsigned int, vpMbGenericTracker>);
static_assert(std::is_convertible_v<const std::vector<int>&, vpMbIcgTracker> ==
              std::is_convertible_v<const std::vector<int>&, vpMbGenericTracker>);  // both explicit
// The same constructor calls compile for ViSP (so the argument lists above are ViSP's).
static_assert(std::is_constructible_v<vpMbGenericTracker, unsigned int> &&
              std::is_constructible_v<vpMbGenericTracker, unsigned int, int> &&
              std::is_constructible_v<vpMbGenericTracker, const std::vector<int>&> &&
              std::is_constructible_v<vpMbGenericTracker, const std::vector<std::string>&, const std::vector<int>&>);

// ---- the calls ViSP programs make with default arguments
ICGP_SAME_CALL(display(arg<const Grey>(), arg<const M>(), arg<const Cam>(), arg<const vpColor>()));
ICGP_SAME_CALL(display(arg<const Rgba>(), arg<const M>(), arg<const Cam>(), arg<const vpColor>(), 2));
ICGP_SAME_CALL(display(arg<const Grey>(), arg<const Grey>(), arg<const M>(), arg<const M>(), arg<const Cam>(),
                       arg<const Cam>(), arg<const vpColor>()));
ICGP_SAME_CALL(display(arg<const Rgba>(), arg<const Rgba>(), arg<const M>(), arg<const M>(), arg<const Cam>(),
                       arg<const Cam>(), arg<const vpColor>()));
ICGP_SAME_CALL(display(arg<const GreyMap>(), arg<const PoseMap>(), arg<const CamMap>(), arg<const vpColor>()));
ICGP_SAME_CALL(display(arg<const RgbaMap>(), arg<const PoseMap>(), arg<const CamMap>(), arg<const vpColor>()));
ICGP_SAME_CALL(getLcircle(arg<Circles>()));
ICGP_SAME_CALL(getLcircle(arg<const Str>(), arg<Circles>()));
ICGP_SAME_CALL(getLcylinder(arg<Cylinders>()));
ICGP_SAME_CALL(getLcylinder(arg<const Str>(), arg<Cylinders>()));
ICGP_SAME_CALL(getLline(arg<LinesList>()));
ICGP_SAME_CALL(getLline(arg<const Str>(), arg<LinesList>()));
ICGP_SAME_CALL(getModelForDisplay(640u, 480u, arg<const M>(), arg<const Cam>()));
ICGP_SAME_CALL(getModelForDisplay(arg<LinesMap>(), arg<const UIntMap>(), arg<const UIntMap>(), arg<const PoseMap>(),
                                  arg<const CamMap>()));
ICGP_SAME_CALL(getNbPoints());
ICGP_SAME_CALL(getNbPoints(arg<UIntMap>()));
ICGP_SAME_CALL(getPolygonFaces());
ICGP_SAME_CALL(getPolygonFaces(arg<PolygonsMap>(), arg<PointsMap>()));
ICGP_SAME_CALL(getPose());
ICGP_SAME_CALL(initClick(arg<const Grey>(), arg<const Str>()));
ICGP_SAME_CALL(initClick(arg<const Rgba>(), arg<const Str>()));
ICGP_SAME_CALL(initClick(arg<const Grey>(), arg<const Points3D>()));
ICGP_SAME_CALL(initClick(arg<const Rgba>(), arg<const Points3D>()));
ICGP_SAME_CALL(initClick(arg<const Grey>(), arg<const Grey>(), arg<const Str>(), arg<const Str>()));
ICGP_SAME_CALL(initClick(arg<const Rgba>(), arg<const Rgba>(), arg<const Str>(), arg<const Str>()));
ICGP_SAME_CALL(initClick(arg<const GreyMap>(), arg<const StrMap>()));
ICGP_SAME_CALL(initClick(arg<const RgbaMap>(), arg<const StrMap>()));
ICGP_SAME_CALL(loadConfigFile(arg<const Str>()));
ICGP_SAME_CALL(loadConfigFile(arg<const Str>(), arg<const Str>()));
ICGP_SAME_CALL(loadConfigFile(arg<const StrMap>()));
ICGP_SAME_CALL(loadModel(arg<const Str>()));
ICGP_SAME_CALL(loadModel(arg<const Str>(), arg<const Str>()));
ICGP_SAME_CALL(loadModel(arg<const StrMap>()));
ICGP_SAME_CALL(reInitModel(arg<const Grey>(), arg<const Str>(), arg<const M>()));
ICGP_SAME_CALL(reInitModel(arg<const Rgba>(), arg<const Str>(), arg<const M>()));
ICGP_SAME_CALL(reInitModel(arg<const Grey>(), arg<const Grey>(), arg<const Str>(), arg<const Str>(), arg<const M>(),
                           arg<const M>()));
ICGP_SAME_CALL(reInitModel(arg<const Rgba>(), arg<const Rgba>(), arg<const Str>(), arg<const Str>(), arg<const M>(),
                           arg<const M>()));
ICGP_SAME_CALL(reInitModel(arg<const GreyMap>(), arg<const StrMap>(), arg<const PoseMap>()));
ICGP_SAME_CALL(reInitModel(arg<const RgbaMap>(), arg<const StrMap>(), arg<const PoseMap>()));
ICGP_SAME_CALL(setLod(true));
ICGP_SAME_CALL(setMinLineLengthThresh(1.0));
ICGP_SAME_CALL(setMinPolygonAreaThresh(1.0));
// Plain values where ViSP takes const references, as programs pass them.
ICGP_SAME_CALL(setClipping(vpPolygon3D::FOV_CLIPPING));
ICGP_SAME_CALL(setAngleAppear(1.0));
ICGP_SAME_CALL(setKltMaskBorder(5u, 5u));
ICGP_SAME_CALL(setFeatureFactors({}));
// 46 ICGP_SAME_CALL lines above.

/// Every public method of the installed vpMbGenericTracker.h, in the header's order.
std::vector<bool> visp_signatures() {
  return {
      ICGP_SAME_SIGNATURE(double, computeCurrentProjectionError, (const Grey&, const M&, const Cam&)),
      ICGP_SAME_SIGNATURE(double, computeCurrentProjectionError, (const Rgba&, const M&, const Cam&)),
      ICGP_SAME_SIGNATURE(void, display, (const Grey&, const M&, const Cam&, const vpColor&, unsigned int, bool)),
      ICGP_SAME_SIGNATURE(void, display, (const Rgba&, const M&, const Cam&, const vpColor&, unsigned int, bool)),
      ICGP_SAME_SIGNATURE(void, display,
                          (const Grey&, const Grey&, const M&, const M&, const Cam&, const Cam&, const vpColor&,
                           unsigned int, bool)),
      ICGP_SAME_SIGNATURE(void, display,
                          (const Rgba&, const Rgba&, const M&, const M&, const Cam&, const Cam&, const vpColor&,
                           unsigned int, bool)),
      ICGP_SAME_SIGNATURE(void, display,
                          (const GreyMap&, const PoseMap&, const CamMap&, const vpColor&, unsigned int, bool)),
      ICGP_SAME_SIGNATURE(void, display,
                          (const RgbaMap&, const PoseMap&, const CamMap&, const vpColor&, unsigned int, bool)),
      ICGP_SAME_SIGNATURE(Names, getCameraNames, (), const),
      ICGP_SAME_SIGNATURE(void, getCameraParameters, (Cam&), const),
      ICGP_SAME_SIGNATURE(void, getCameraParameters, (Cam&, Cam&), const),
      ICGP_SAME_SIGNATURE(void, getCameraParameters, (CamMap&), const),
      ICGP_SAME_SIGNATURE(IntMap, getCameraTrackerTypes, (), const),
      ICGP_SAME_SIGNATURE(unsigned int, getClipping, (), const),
      ICGP_SAME_SIGNATURE(void, getClipping, (unsigned int&, unsigned int&), const),
      ICGP_SAME_SIGNATURE(void, getClipping, (UIntMap&), const),
      ICGP_SAME_SIGNATURE(vpColVector, getError, (), const),
      ICGP_SAME_SIGNATURE(Faces&, getFaces, ()),
      ICGP_SAME_SIGNATURE(Faces&, getFaces, (const Str&)),
      ICGP_SAME_SIGNATURE(Circles&, getFeaturesCircle, ()),
      ICGP_SAME_SIGNATURE(KltCylinders&, getFeaturesKltCylinder, ()),
      ICGP_SAME_SIGNATURE(KltPoints&, getFeaturesKlt, ()),
      ICGP_SAME_SIGNATURE(Lines, getFeaturesForDisplay, ()),
      ICGP_SAME_SIGNATURE(void, getFeaturesForDisplay, (LinesMap&)),
      ICGP_SAME_SIGNATURE(double, getGoodMovingEdgesRatioThreshold, (), const),
      ICGP_SAME_SIGNATURE(ImagePoints, getKltImagePoints, (), const),
      ICGP_SAME_SIGNATURE(IdPoints, getKltImagePointsWithId, (), const),
      ICGP_SAME_SIGNATURE(unsigned int, getKltMaskBorder, (), const),
      ICGP_SAME_SIGNATURE(int, getKltNbPoints, (), const),
      ICGP_SAME_SIGNATURE(vpKltOpencv, getKltOpencv, (), const),
      ICGP_SAME_SIGNATURE(void, getKltOpencv, (vpKltOpencv&, vpKltOpencv&), const),
      ICGP_SAME_SIGNATURE(void, getKltOpencv, (KltMap&), const),
      ICGP_SAME_SIGNATURE(CvPoints, getKltPoints, (), const),
      ICGP_SAME_SIGNATURE(double, getKltThresholdAcceptation, (), const),
      ICGP_SAME_SIGNATURE(void, getLcircle, (Circles&, unsigned int), const),
      ICGP_SAME_SIGNATURE(void, getLcircle, (const Str&, Circles&, unsigned int), const),
      ICGP_SAME_SIGNATURE(void, getLcylinder, (Cylinders&, unsigned int), const),
      ICGP_SAME_SIGNATURE(void, getLcylinder, (const Str&, Cylinders&, unsigned int), const),
      ICGP_SAME_SIGNATURE(void, getLline, (LinesList&, unsigned int), const),
      ICGP_SAME_SIGNATURE(void, getLline, (const Str&, LinesList&, unsigned int), const),
      ICGP_SAME_SIGNATURE(Lines, getModelForDisplay, (unsigned int, unsigned int, const M&, const Cam&, bool)),
      ICGP_SAME_SIGNATURE(void, getModelForDisplay,
                          (LinesMap&, const UIntMap&, const UIntMap&, const PoseMap&, const CamMap&, bool)),
      ICGP_SAME_SIGNATURE(vpMe, getMovingEdge, (), const),
      ICGP_SAME_SIGNATURE(void, getMovingEdge, (vpMe&, vpMe&), const),
      ICGP_SAME_SIGNATURE(void, getMovingEdge, (MeMap&), const),
      ICGP_SAME_SIGNATURE(unsigned int, getNbFeaturesDepthDense, (), const),
      ICGP_SAME_SIGNATURE(unsigned int, getNbFeaturesDepthNormal, (), const),
      ICGP_SAME_SIGNATURE(unsigned int, getNbFeaturesEdge, (), const),
      ICGP_SAME_SIGNATURE(unsigned int, getNbFeaturesKlt, (), const),
      ICGP_SAME_SIGNATURE(unsigned int, getNbPoints, (unsigned int), const),
      ICGP_SAME_SIGNATURE(void, getNbPoints, (UIntMap&, unsigned int), const),
      ICGP_SAME_SIGNATURE(unsigned int, getNbPolygon, (), const),
      ICGP_SAME_SIGNATURE(void, getNbPolygon, (UIntMap&), const),
      ICGP_SAME_SIGNATURE(vpMbtPolygon*, getPolygon, (unsigned int)),
      ICGP_SAME_SIGNATURE(vpMbtPolygon*, getPolygon, (const Str&, unsigned int)),
      ICGP_SAME_SIGNATURE(PolygonFaces, getPolygonFaces, (bool, bool, bool)),
      ICGP_SAME_SIGNATURE(void, getPolygonFaces, (PolygonsMap&, PointsMap&, bool, bool, bool)),
      ICGP_SAME_SIGNATURE(M, getPose, (), const),
      ICGP_SAME_SIGNATURE(void, getPose, (M&), const),
      ICGP_SAME_SIGNATURE(void, getPose, (M&, M&), const),
      ICGP_SAME_SIGNATURE(void, getPose, (PoseMap&), const),
      ICGP_SAME_SIGNATURE(Str, getReferenceCameraName, (), const),
      ICGP_SAME_SIGNATURE(vpColVector, getRobustWeights, (), const),
      ICGP_SAME_SIGNATURE(int, getTrackerType, (), const),
      ICGP_SAME_SIGNATURE(void, init, (const Grey&)),
      ICGP_SAME_SIGNATURE(void, initClick, (const Grey&, const Str&, bool, const M&)),
      ICGP_SAME_SIGNATURE(void, initClick, (const Rgba&, const Str&, bool, const M&)),
      ICGP_SAME_SIGNATURE(void, initClick, (const Grey&, const Points3D&, const Str&)),
      ICGP_SAME_SIGNATURE(void, initClick, (const Rgba&, const Points3D&, const Str&)),
      ICGP_SAME_SIGNATURE(void, initClick,
                          (const Grey&, const Grey&, const Str&, const Str&, bool, const M&, const M&)),
      ICGP_SAME_SIGNATURE(void, initClick,
                          (const Rgba&, const Rgba&, const Str&, const Str&, bool, const M&, const M&)),
      ICGP_SAME_SIGNATURE(void, initClick, (const GreyMap&, const StrMap&, bool, const PoseMap&)),
      ICGP_SAME_SIGNATURE(void, initClick, (const RgbaMap&, const StrMap&, bool, const PoseMap&)),
      ICGP_SAME_SIGNATURE(void, initFromPoints, (const Grey&, const Str&)),
      ICGP_SAME_SIGNATURE(void, initFromPoints, (const Rgba&, const Str&)),
      ICGP_SAME_SIGNATURE(void, initFromPoints, (const Grey&, const ImagePoints&, const Points3D&)),
      ICGP_SAME_SIGNATURE(void, initFromPoints, (const Rgba&, const ImagePoints&, const Points3D&)),
      ICGP_SAME_SIGNATURE(void, initFromPoints, (const Grey&, const Grey&, const Str&, const Str&)),
      ICGP_SAME_SIGNATURE(void, initFromPoints, (const Rgba&, const Rgba&, const Str&, const Str&)),
      ICGP_SAME_SIGNATURE(void, initFromPoints, (const GreyMap&, const StrMap&)),
      ICGP_SAME_SIGNATURE(void, initFromPoints, (const RgbaMap&, const StrMap&)),
      ICGP_SAME_SIGNATURE(void, initFromPose, (const Grey&, const Str&)),
      ICGP_SAME_SIGNATURE(void, initFromPose, (const Rgba&, const Str&)),
      ICGP_SAME_SIGNATURE(void, initFromPose, (const Rgba&, const M&)),
      ICGP_SAME_SIGNATURE(void, initFromPose, (const Grey&, const vpPoseVector&)),
      ICGP_SAME_SIGNATURE(void, initFromPose, (const Rgba&, const vpPoseVector&)),
      ICGP_SAME_SIGNATURE(void, initFromPose, (const Grey&, const M&)),
      ICGP_SAME_SIGNATURE(void, initFromPose, (const Grey&, const Grey&, const Str&, const Str&)),
      ICGP_SAME_SIGNATURE(void, initFromPose, (const Rgba&, const Rgba&, const Str&, const Str&)),
      ICGP_SAME_SIGNATURE(void, initFromPose, (const GreyMap&, const StrMap&)),
      ICGP_SAME_SIGNATURE(void, initFromPose, (const RgbaMap&, const StrMap&)),
      ICGP_SAME_SIGNATURE(void, initFromPose, (const Grey&, const Grey&, const M&, const M&)),
      ICGP_SAME_SIGNATURE(void, initFromPose, (const Rgba&, const Rgba&, const M&, const M&)),
      ICGP_SAME_SIGNATURE(void, initFromPose, (const GreyMap&, const PoseMap&)),
      ICGP_SAME_SIGNATURE(void, initFromPose, (const RgbaMap&, const PoseMap&)),
      ICGP_SAME_SIGNATURE(void, loadConfigFile, (const Str&, bool)),
      ICGP_SAME_SIGNATURE(void, loadConfigFile, (const Str&, const Str&, bool)),
      ICGP_SAME_SIGNATURE(void, loadConfigFile, (const StrMap&, bool)),
      ICGP_SAME_SIGNATURE(void, loadModel, (const Str&, bool, const M&)),
      ICGP_SAME_SIGNATURE(void, loadModel, (const Str&, const Str&, bool, const M&, const M&)),
      ICGP_SAME_SIGNATURE(void, loadModel, (const StrMap&, bool, const PoseMap&)),
      ICGP_SAME_SIGNATURE(void, reInitModel, (const Grey&, const Str&, const M&, bool, const M&)),
      ICGP_SAME_SIGNATURE(void, reInitModel, (const Rgba&, const Str&, const M&, bool, const M&)),
      ICGP_SAME_SIGNATURE(void, reInitModel,
                          (const Grey&, const Grey&, const Str&, const Str&, const M&, const M&, bool, const M&,
                           const M&)),
      ICGP_SAME_SIGNATURE(void, reInitModel,
                          (const Rgba&, const Rgba&, const Str&, const Str&, const M&, const M&, bool, const M&,
                           const M&)),
      ICGP_SAME_SIGNATURE(void, reInitModel, (const GreyMap&, const StrMap&, const PoseMap&, bool, const PoseMap&)),
      ICGP_SAME_SIGNATURE(void, reInitModel, (const RgbaMap&, const StrMap&, const PoseMap&, bool, const PoseMap&)),
      ICGP_SAME_SIGNATURE(void, resetTracker, ()),
      ICGP_SAME_SIGNATURE(void, setAngleAppear, (const double&)),
      ICGP_SAME_SIGNATURE(void, setAngleAppear, (const double&, const double&)),
      ICGP_SAME_SIGNATURE(void, setAngleAppear, (const DoubleMap&)),
      ICGP_SAME_SIGNATURE(void, setAngleDisappear, (const double&)),
      ICGP_SAME_SIGNATURE(void, setAngleDisappear, (const double&, const double&)),
      ICGP_SAME_SIGNATURE(void, setAngleDisappear, (const DoubleMap&)),
      ICGP_SAME_SIGNATURE(void, setCameraParameters, (const Cam&)),
      ICGP_SAME_SIGNATURE(void, setCameraParameters, (const Cam&, const Cam&)),
      ICGP_SAME_SIGNATURE(void, setCameraParameters, (const CamMap&)),
      ICGP_SAME_SIGNATURE(void, setCameraTransformationMatrix, (const Str&, const M&)),
      ICGP_SAME_SIGNATURE(void, setCameraTransformationMatrix, (const PoseMap&)),
      ICGP_SAME_SIGNATURE(void, setClipping, (const unsigned int&)),
      ICGP_SAME_SIGNATURE(void, setClipping, (const unsigned int&, const unsigned int&)),
      ICGP_SAME_SIGNATURE(void, setClipping, (const UIntMap&)),
      ICGP_SAME_SIGNATURE(void, setDepthDenseFilteringMaxDistance, (double)),
      ICGP_SAME_SIGNATURE(void, setDepthDenseFilteringMethod, (int)),
      ICGP_SAME_SIGNATURE(void, setDepthDenseFilteringMinDistance, (double)),
      ICGP_SAME_SIGNATURE(void, setDepthDenseFilteringOccupancyRatio, (double)),
      ICGP_SAME_SIGNATURE(void, setDepthDenseSamplingStep, (unsigned int, unsigned int)),
      ICGP_SAME_SIGNATURE(void, setDepthNormalFaceCentroidMethod, (const vpMbtFaceDepthNormal::vpFaceCentroidType&)),
      ICGP_SAME_SIGNATURE(void, setDepthNormalFeatureEstimationMethod,
                          (const vpMbtFaceDepthNormal::vpFeatureEstimationType&)),
      ICGP_SAME_SIGNATURE(void, setDepthNormalPclPlaneEstimationMethod, (int)),
      ICGP_SAME_SIGNATURE(void, setDepthNormalPclPlaneEstimationRansacMaxIter, (int)),
      ICGP_SAME_SIGNATURE(void, setDepthNormalPclPlaneEstimationRansacThreshold, (double)),
      ICGP_SAME_SIGNATURE(void, setDepthNormalSamplingStep, (unsigned int, unsigned int)),
      ICGP_SAME_SIGNATURE(void, setDisplayFeatures, (bool)),
      ICGP_SAME_SIGNATURE(void, setFarClippingDistance, (const double&)),
      ICGP_SAME_SIGNATURE(void, setFarClippingDistance, (const double&, const double&)),
      ICGP_SAME_SIGNATURE(void, setFarClippingDistance, (const DoubleMap&)),
      // setFeatureFactors: ViSP's map is keyed by vpMbGenericTracker::vpTrackerType, ours
      // by vpMbIcgTracker::vpTrackerType (same values): the same source after the class
      // name is swapped, which is what "drop-in" means for a nested type.
      [] {
        void (vpMbGenericTracker::*visp)(const std::map<vpMbGenericTracker::vpTrackerType, double>&) =
            &vpMbGenericTracker::setFeatureFactors;
        void (vpMbIcgTracker::*ours)(const std::map<vpMbIcgTracker::vpTrackerType, double>&) =
            &vpMbIcgTracker::setFeatureFactors;
        return visp != nullptr && ours != nullptr;
      }(),
      ICGP_SAME_SIGNATURE(void, setGoodMovingEdgesRatioThreshold, (double)),
      ICGP_SAME_SIGNATURE(void, setKltMaskBorder, (const unsigned int&)),
      ICGP_SAME_SIGNATURE(void, setKltMaskBorder, (const unsigned int&, const unsigned int&)),
      ICGP_SAME_SIGNATURE(void, setKltMaskBorder, (const UIntMap&)),
      ICGP_SAME_SIGNATURE(void, setKltOpencv, (const vpKltOpencv&)),
      ICGP_SAME_SIGNATURE(void, setKltOpencv, (const vpKltOpencv&, const vpKltOpencv&)),
      ICGP_SAME_SIGNATURE(void, setKltOpencv, (const KltMap&)),
      ICGP_SAME_SIGNATURE(void, setKltThresholdAcceptation, (double)),
      ICGP_SAME_SIGNATURE(void, setLod, (bool, const Str&)),
      ICGP_SAME_SIGNATURE(void, setMask, (const vpImage<bool>&)),
      ICGP_SAME_SIGNATURE(void, setMinLineLengthThresh, (double, const Str&)),
      ICGP_SAME_SIGNATURE(void, setMinPolygonAreaThresh, (double, const Str&)),
      ICGP_SAME_SIGNATURE(void, setMovingEdge, (const vpMe&)),
      ICGP_SAME_SIGNATURE(void, setMovingEdge, (const vpMe&, const vpMe&)),
      ICGP_SAME_SIGNATURE(void, setMovingEdge, (const MeMap&)),
      ICGP_SAME_SIGNATURE(void, setNearClippingDistance, (const double&)),
      ICGP_SAME_SIGNATURE(void, setNearClippingDistance, (const double&, const double&)),
      ICGP_SAME_SIGNATURE(void, setNearClippingDistance, (const DoubleMap&)),
      ICGP_SAME_SIGNATURE(void, setOgreShowConfigDialog, (bool)),
      ICGP_SAME_SIGNATURE(void, setOgreVisibilityTest, (const bool&)),
      ICGP_SAME_SIGNATURE(void, setOptimizationMethod, (const vpMbTracker::vpMbtOptimizationMethod&)),
      ICGP_SAME_SIGNATURE(void, setPose, (const Grey&, const M&)),
      ICGP_SAME_SIGNATURE(void, setPose, (const Rgba&, const M&)),
      ICGP_SAME_SIGNATURE(void, setPose, (const Grey&, const Grey&, const M&, const M&)),
      ICGP_SAME_SIGNATURE(void, setPose, (const Rgba&, const Rgba&, const M&, const M&)),
      ICGP_SAME_SIGNATURE(void, setPose, (const GreyMap&, const PoseMap&)),
      ICGP_SAME_SIGNATURE(void, setPose, (const RgbaMap&, const PoseMap&)),
      ICGP_SAME_SIGNATURE(void, setProjectionErrorComputation, (const bool&)),
      ICGP_SAME_SIGNATURE(void, setProjectionErrorDisplay, (bool)),
      ICGP_SAME_SIGNATURE(void, setProjectionErrorDisplayArrowLength, (unsigned int)),
      ICGP_SAME_SIGNATURE(void, setProjectionErrorDisplayArrowThickness, (unsigned int)),
      ICGP_SAME_SIGNATURE(void, setReferenceCameraName, (const Str&)),
      ICGP_SAME_SIGNATURE(void, setScanLineVisibilityTest, (const bool&)),
      ICGP_SAME_SIGNATURE(void, setTrackerType, (int)),
      ICGP_SAME_SIGNATURE(void, setTrackerType, (const IntMap&)),
      ICGP_SAME_SIGNATURE(void, setUseDepthDenseTracking, (const Str&, const bool&)),
      ICGP_SAME_SIGNATURE(void, setUseDepthNormalTracking, (const Str&, const bool&)),
      ICGP_SAME_SIGNATURE(void, setUseEdgeTracking, (const Str&, const bool&)),
      ICGP_SAME_SIGNATURE(void, setUseKltTracking, (const Str&, const bool&)),
      ICGP_SAME_SIGNATURE(void, testTracking, ()),
      ICGP_SAME_SIGNATURE(void, track, (const Grey&)),
      ICGP_SAME_SIGNATURE(void, track, (const Rgba&)),
      ICGP_SAME_SIGNATURE(void, track, (const Grey&, const Grey&)),
      ICGP_SAME_SIGNATURE(void, track, (const Rgba&, const Rgba&)),
      ICGP_SAME_SIGNATURE(void, track, (GreyMap&)),
      ICGP_SAME_SIGNATURE(void, track, (RgbaMap&)),
      ICGP_SAME_SIGNATURE(void, track, (GreyMap&, CloudMap&, UIntMap&, UIntMap&)),
      ICGP_SAME_SIGNATURE(void, track, (RgbaMap&, CloudMap&, UIntMap&, UIntMap&)),
  };
}

/// icgp's extensions.
std::vector<bool> extension_signatures() {
  return {
      ICGP_EXTENSION(void, setTrackerConfig, (const icgp::TrackerConfig&)),
      ICGP_EXTENSION(const icgp::TrackerConfig&, getTrackerConfig, (), const),
      ICGP_EXTENSION(void, setModalities, (const std::vector<std::string>&)),
      ICGP_EXTENSION(double, getTrackingQuality, (), const),
      ICGP_EXTENSION(void, track, (const Grey&, const Raw&, double)),
      ICGP_EXTENSION(void, track, (const Rgba&, const Raw&, double)),
      ICGP_EXTENSION(void, track, (const PclXyzrgba&)),
      ICGP_EXTENSION(void, track, (GreyMap&, PclXyzMap&)),
      ICGP_EXTENSION(void, track, (RgbaMap&, PclXyzMap&)),
  };
}

}  // namespace

TEST_CASE("vpMbIcgTracker has every public method of vpMbGenericTracker, with ViSP's signatures") {
  // The checks are the compilation of this file; these counts keep the lists from
  // shrinking unnoticed.
  const std::vector<bool> visp = visp_signatures();
  const std::vector<bool> extensions = extension_signatures();
  CHECK(visp.size() == 186);
  CHECK(extensions.size() == 9);
  for (bool taken : visp) CHECK(taken);
  for (bool taken : extensions) CHECK(taken);
}

// =====================================================================================
// 2. Calls, at run time
// =====================================================================================

namespace {

const std::string kTeaboxCao = (test::kTeaboxBlender / "teabox.cao").string();
const std::string kColorXml = (test::kTeaboxBlender / "teabox.xml").string();
const std::string kDepthXml = (test::kTeaboxBlender / "teabox_depth.xml").string();
const std::string kCubeCao =
    (std::filesystem::path(ICGP_TEST_DATA_DIR) / "realsense-cube" / "models" / "cube" / "cube.cao").string();
const std::string kCamera1 = kColorCamera;  // "Camera1": colour, EDGE_TRACKER | KLT_TRACKER, the reference
const std::string kCamera2 = kDepthCamera;  // "Camera2": DEPTH_DENSE_TRACKER
constexpr int kEdge = vpMbGenericTracker::EDGE_TRACKER, kKlt = vpMbGenericTracker::KLT_TRACKER,
              kDepthNormal = vpMbGenericTracker::DEPTH_NORMAL_TRACKER,
              kDepthDense = vpMbGenericTracker::DEPTH_DENSE_TRACKER;

/// `call` is refused with a vpException of `code` whose message names the call and `value`.
template <class Call>
void check_refused(const std::string& name, const std::string& value, Call&& call,
                   int code = vpException::badValue) {
  INFO("vpMbIcgTracker::" << name << " refusing " << value);
  const vpException e = vp_exception_of(call);
  CHECK(e.getCode() == code);
  CHECK_THAT(e.getStringMessage(), Contains("vpMbIcgTracker::" + name) && Contains(value));
}

std::size_t occurrences(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + what.size())) ++n;
  return n;
}

double max_difference(const vpHomogeneousMatrix& a, const vpHomogeneousMatrix& b) {
  double worst = 0.0;
  for (unsigned int i = 0; i < 4; ++i)
    for (unsigned int j = 0; j < 4; ++j) worst = std::max(worst, std::abs(a[i][j] - b[i][j]));
  return worst;
}

bool bit_identical(const vpHomogeneousMatrix& a, const vpHomogeneousMatrix& b) {
  for (unsigned int i = 0; i < 4; ++i)
    for (unsigned int j = 0; j < 4; ++j)
      if (!(a[i][j] == b[i][j])) return false;
  return true;
}

vpHomogeneousMatrix pose_of(const vpMbTracker& tracker) {
  vpHomogeneousMatrix cMo;
  tracker.getPose(cMo);
  return cMo;
}

bool same_camera(const vpCameraParameters& a, const vpCameraParameters& b) {
  return a.get_px() == b.get_px() && a.get_py() == b.get_py() && a.get_u0() == b.get_u0() && a.get_v0() == b.get_v0();
}

bool same_me(const vpMe& a, const vpMe& b) {
  return a.getRange() == b.getRange() && a.getThreshold() == b.getThreshold() && a.getMu1() == b.getMu1() &&
         a.getMu2() == b.getMu2() && a.getSampleStep() == b.getSampleStep() && a.getMaskSize() == b.getMaskSize() &&
         a.getMaskNumber() == b.getMaskNumber() && a.getStrip() == b.getStrip() &&
         a.getNbTotalSample() == b.getNbTotalSample() && a.getPointsToTrack() == b.getPointsToTrack();
}

bool same_klt(const vpKltOpencv& a, const vpKltOpencv& b) {
  return a.getMaxFeatures() == b.getMaxFeatures() && a.getWindowSize() == b.getWindowSize() &&
         a.getQuality() == b.getQuality() && a.getMinDistance() == b.getMinDistance() &&
         a.getHarrisFreeParameter() == b.getHarrisFreeParameter() && a.getBlockSize() == b.getBlockSize() &&
         a.getPyramidLevels() == b.getPyramidLevels();
}

/// The first frames of teabox-blender in ViSP's shapes, and its two cameras.
struct Rig {
  std::vector<Frame> frames;
  std::vector<VispRgbdFrame> inputs;       ///< grey image of the colour camera, cloud of the depth camera
  std::vector<vpImage<vpRGBa>> colors;     ///< the colour camera's image
  vpImage<unsigned char> depth_image;      ///< an image of the depth camera's size, for the calls that take one
  vpCameraParameters cam1, cam2;
  vpHomogeneousMatrix c2_M_c1;             ///< depth_M_color

  explicit Rig(int n) : frames(test::teabox_frames(n)), inputs(n), colors(n) {
    for (int i = 0; i < n; ++i) {
      inputs[i].convert(frames[i]);
      to_vp_image(frames[i].colors.front().image, colors[i]);
    }
    cam1 = to_camera_parameters(frames.front().colors.front().intrinsics);
    cam2 = to_camera_parameters(frames.front().depths.front().intrinsics);
    c2_M_c1 = to_homogeneous_matrix(frames.front().depths.front().camera_T_reference);
    depth_image.resize(inputs.front().depth_height, inputs.front().depth_width, 128);
  }

  /// As ViSP's RGB-D programs set a tracker up: the teabox for both cameras, their
  /// parameters, depth_M_color.
  template <class Tracker>
  void setup(Tracker& tracker) const {
    if constexpr (std::is_same_v<Tracker, vpMbIcgTracker>) test::configure_for_tests(tracker);
    {
      const detail::StdoutSilencer quiet_parser;
      tracker.loadModel(kTeaboxCao, kTeaboxCao);
    }
    tracker.setCameraParameters(cam1, cam2);
    tracker.setCameraTransformationMatrix(kCamera2, c2_M_c1);
  }

  const vpImage<unsigned char>& grey(int i) const { return inputs[i].grey; }
  vpHomogeneousMatrix truth(int i) const { return to_homogeneous_matrix(*frames[i].truth()); }

  /// The RGB-D call of ViSP's programs: the colour image and the depth camera's cloud.
  template <class Image>
  void track_rgbd(vpMbIcgTracker& tracker, int i, const Image& image) const {
    std::map<std::string, const Image*> images{{kCamera1, &image}};
    std::map<std::string, const std::vector<vpColVector>*> clouds{{kCamera2, &inputs[i].point_cloud}};
    std::map<std::string, unsigned int> widths{{kCamera2, inputs[i].depth_width}};
    std::map<std::string, unsigned int> heights{{kCamera2, inputs[i].depth_height}};
    tracker.track(images, clouds, widths, heights);
  }
  void track_rgbd(vpMbIcgTracker& tracker, int i) const { track_rgbd(tracker, i, grey(i)); }

  /// The tracked pose is the frame's truth (to 1 mm and 0.5 degree).
  void check_near_truth(const vpMbTracker& tracker, int i, double mm = 1.0, double deg = 0.5) const {
    const Pose cMo = to_pose(pose_of(tracker));
    CHECK(translation_error_mm(cMo, *frames[i].truth()) < mm);
    CHECK(rotation_error_deg(cMo, *frames[i].truth()) < deg);
  }
};

void check_same_cameras(const vpMbIcgTracker& ours, const vpMbGenericTracker& visp) {
  CHECK(ours.getCameraNames() == visp.getCameraNames());
  CHECK(ours.getReferenceCameraName() == visp.getReferenceCameraName());
  CHECK(ours.getCameraTrackerTypes() == visp.getCameraTrackerTypes());
  CHECK(ours.getTrackerType() == visp.getTrackerType());
}

}  // namespace

// ---------------------------------------------------------------------------- cameras

TEST_CASE("vpMbIcgTracker's constructors name and type the cameras as vpMbGenericTracker's") {
  SECTION("()") {
    const vpMbIcgTracker ours;
    const vpMbGenericTracker visp;
    CHECK(ours.getCameraNames() == visp.getCameraNames());
    CHECK(ours.getReferenceCameraName() == visp.getReferenceCameraName());
    // ViSP's default camera has EDGE_TRACKER alone; vpMbIcgTracker's, as documented, every cue.
    CHECK(ours.getCameraTrackerTypes() == std::map<std::string, int>{{"Camera", kEdge | kKlt | kDepthDense}});
  }
  SECTION("(nbCameras, trackerType)") {
    for (unsigned int n : {1u, 2u, 3u, 12u})  // 12: "Camera10" sorts before "Camera2", as in ViSP's map
      for (int type : {kEdge, kKlt | kDepthNormal, kDepthDense, kEdge | kKlt | kDepthNormal | kDepthDense}) {
        INFO(n << " cameras of type " << type);
        check_same_cameras(vpMbIcgTracker(n, type), vpMbGenericTracker(n, type));
      }
    check_same_cameras(vpMbIcgTracker(2u), vpMbGenericTracker(2u));  // trackerType's default
  }
  SECTION("(trackerTypes)") {
    for (const std::vector<int>& types : std::vector<std::vector<int>>{
             {kEdge}, kRgbdTrackerTypes, {kEdge | kKlt, kEdge | kKlt, kDepthNormal}, {kDepthDense, kEdge}}) {
      INFO(types.size() << " cameras");
      check_same_cameras(vpMbIcgTracker(types), vpMbGenericTracker(types));
    }
  }
  SECTION("(cameraNames, trackerTypes)") {
    const std::vector<std::pair<std::vector<std::string>, std::vector<int>>> cases = {
        {{"Camera1", "Camera2"}, kRgbdTrackerTypes},
        {{"Color", "Depth"}, {kEdge | kKlt, kDepthNormal}},
        {{"Left", "Right"}, {kEdge | kKlt, kEdge | kKlt}},
        {{"A"}, {kDepthDense}}};
    for (const auto& [names, types] : cases) {
      INFO(names.front());
      check_same_cameras(vpMbIcgTracker(names, types), vpMbGenericTracker(names, types));
    }
  }
}

TEST_CASE("vpMbIcgTracker's reference camera of unsorted names is ViSP's: the first in sorted order") {
  // vpMbGenericTracker(names, types) sets m_referenceCameraName = m_mapOfTrackers.begin()->first,
  // the first name in sorted order; CameraRig takes names.front().
  const std::vector<std::string> names{"Right", "Left"};
  const std::vector<int> types{kEdge | kKlt, kEdge | kKlt};
  CHECK(vpMbIcgTracker(names, types).getReferenceCameraName() ==
        vpMbGenericTracker(names, types).getReferenceCameraName());
}

TEST_CASE("setTrackerType, getTrackerType, setReferenceCameraName as in vpMbGenericTracker") {
  vpMbIcgTracker ours(kRgbdTrackerTypes);
  vpMbGenericTracker visp(kRgbdTrackerTypes);
  check_same_cameras(ours, visp);
  ours.setTrackerType(std::map<std::string, int>{{kCamera2, kDepthNormal}});
  visp.setTrackerType(std::map<std::string, int>{{kCamera2, kDepthNormal}});
  check_same_cameras(ours, visp);
  ours.setReferenceCameraName(kCamera2);
  visp.setReferenceCameraName(kCamera2);
  check_same_cameras(ours, visp);  // getTrackerType() is the reference camera's
  ours.setTrackerType(kEdge | kDepthDense);
  visp.setTrackerType(kEdge | kDepthDense);
  check_same_cameras(ours, visp);
  ours.setReferenceCameraName(kCamera1);
  visp.setReferenceCameraName(kCamera1);
  check_same_cameras(ours, visp);
  // resetTracker keeps the cameras and their types.
  ours.resetTracker();
  visp.resetTracker();
  check_same_cameras(ours, visp);
}

TEST_CASE("camera parameters and transformation matrices of two cameras, and the poses they give") {
  const Rig rig(2);
  vpMbIcgTracker ours(kRgbdTrackerTypes);
  vpMbGenericTracker visp(kRgbdTrackerTypes);
  rig.setup(ours);
  rig.setup(visp);

  // setCameraParameters(cam1, cam2) round trips through every getter, as in ViSP.
  vpCameraParameters single, first, second, visp_first, visp_second;
  ours.getCameraParameters(single);
  ours.getCameraParameters(first, second);
  visp.getCameraParameters(visp_first, visp_second);
  CHECK(same_camera(single, rig.cam1));
  CHECK(same_camera(first, rig.cam1));
  CHECK(same_camera(second, rig.cam2));
  CHECK(same_camera(first, visp_first));
  CHECK(same_camera(second, visp_second));
  std::map<std::string, vpCameraParameters> ours_map, visp_map;
  ours.getCameraParameters(ours_map);
  visp.getCameraParameters(visp_map);
  REQUIRE(ours_map.size() == visp_map.size());
  for (const auto& [name, camera] : visp_map) CHECK(same_camera(ours_map.at(name), camera));

  // The map form sets the named cameras only; the single form the reference camera.
  const vpCameraParameters other(500.0, 510.0, 300.0, 200.0);
  ours.setCameraParameters(std::map<std::string, vpCameraParameters>{{kCamera2, other}});
  visp.setCameraParameters(std::map<std::string, vpCameraParameters>{{kCamera2, other}});
  ours.getCameraParameters(first, second);
  CHECK(same_camera(first, rig.cam1));
  CHECK(same_camera(second, other));
  ours.getCameraParameters(ours_map);
  visp.getCameraParameters(visp_map);
  for (const auto& [name, camera] : visp_map) CHECK(same_camera(ours_map.at(name), camera));
  ours.setCameraParameters(other);
  ours.getCameraParameters(first, second);
  CHECK(same_camera(first, other));
  ours.setCameraParameters(std::map<std::string, vpCameraParameters>{{kCamera1, rig.cam1}, {kCamera2, rig.cam2}});
  ours.getCameraParameters(ours_map);
  CHECK(same_camera(ours_map.at(kCamera1), rig.cam1));
  CHECK(same_camera(ours_map.at(kCamera2), rig.cam2));

  // Both forms of setCameraTransformationMatrix; then every getPose form after a tracked
  // frame is c_M_reference * cMo.
  ours.setCameraTransformationMatrix(
      std::map<std::string, vpHomogeneousMatrix>{{kCamera1, vpHomogeneousMatrix()}, {kCamera2, rig.c2_M_c1}});
  ours.initFromPose(rig.grey(0), rig.truth(0));
  rig.track_rgbd(ours, 0);
  rig.track_rgbd(ours, 1);
  rig.check_near_truth(ours, 1);
  const vpHomogeneousMatrix cMo = pose_of(ours);
  CHECK(bit_identical(ours.getPose(), cMo));
  vpHomogeneousMatrix c1Mo, c2Mo;
  ours.getPose(c1Mo, c2Mo);
  CHECK(bit_identical(c1Mo, cMo));
  CHECK(max_difference(c2Mo, rig.c2_M_c1 * cMo) == 0.0);
  std::map<std::string, vpHomogeneousMatrix> poses;
  ours.getPose(poses);
  REQUIRE(poses.size() == 2);
  CHECK(bit_identical(poses.at(kCamera1), cMo));
  CHECK(max_difference(poses.at(kCamera2), rig.c2_M_c1 * cMo) == 0.0);
}

// ------------------------------------------------------------------- initialisation

namespace {

/// A pose file in ViSP's .pos format (tx ty tz tux tuy tuz, metres and radians); returns
/// the pose that vpMbTracker reads back from it.
vpHomogeneousMatrix write_pos(const std::string& path, const vpHomogeneousMatrix& cMo) {
  const vpPoseVector p(cMo);
  std::ofstream file(path);
  file << std::setprecision(std::numeric_limits<double>::max_digits10);
  for (unsigned int i = 0; i < 6; ++i) file << p[i] << "\n";
  return vpHomogeneousMatrix(p);
}

/// A vpMbTracker::initFromPoints file: the teabox's 8 corners and their pixels (row, column)
/// in `cam` at `cMo`; also returned as the lists the other initFromPoints forms take.
std::pair<std::vector<vpImagePoint>, std::vector<vpPoint>> write_points(const std::string& path,
                                                                        const vpHomogeneousMatrix& cMo,
                                                                        const vpCameraParameters& cam) {
  const std::vector<std::array<double, 3>> corners = {
      {0.031598, -0.04, 0.001594},     {0.034, 0.037166, 0.001594},  {0.034, 0.037166, 0.166594},
      {0.031598, -0.04, 0.166594},     {-0.034, -0.037166, 0.166594}, {-0.031598, 0.04, 0.166594},
      {-0.031598, 0.04, 0.001594},     {-0.034, -0.037166, 0.001594}};
  std::ofstream file(path);
  file << std::setprecision(std::numeric_limits<double>::max_digits10);
  file << corners.size() << "\n";
  for (const auto& X : corners) file << X[0] << " " << X[1] << " " << X[2] << "\n";
  file << corners.size() << "\n";
  std::pair<std::vector<vpImagePoint>, std::vector<vpPoint>> lists;
  for (const auto& X : corners) {
    vpPoint P(X[0], X[1], X[2]);
    P.track(cMo);
    double u = 0.0, v = 0.0;
    vpMeterPixelConversion::convertPoint(cam, P.get_x(), P.get_y(), u, v);
    file << v << " " << u << "\n";
    lists.first.emplace_back(v, u);
    lists.second.emplace_back(X[0], X[1], X[2]);
  }
  return lists;
}

}  // namespace

TEST_CASE("initFromPose and setPose in every form: another camera's pose is moved into the reference camera") {
  Rig rig(1);
  vpMbIcgTracker t(kRgbdTrackerTypes);
  rig.setup(t);
  const test::TempDir dir("icgp-test-vpmbicgtracker-api");
  const vpHomogeneousMatrix a = rig.truth(0);
  const vpHomogeneousMatrix b = vpHomogeneousMatrix(0.004, -0.003, 0.002, 0.01, -0.02, 0.015) * a;
  const auto in_camera2 = [&](const vpHomogeneousMatrix& cMo) { return rig.c2_M_c1 * cMo; };
  // Given the depth camera's pose only, the reference pose is c2_M_c1^-1 * c2Mo.
  const auto from_camera2 = [&](const vpHomogeneousMatrix& c2Mo) { return rig.c2_M_c1.inverse() * c2Mo; };
  const vpImage<unsigned char>& I1 = rig.grey(0);
  const vpImage<unsigned char>& I2 = rig.depth_image;
  const vpImage<vpRGBa>& C1 = rig.colors[0];
  vpImage<vpRGBa> C2;
  vpImageConvert::convert(I2, C2);
  using GreyMap = std::map<std::string, const vpImage<unsigned char>*>;
  using RgbaMap = std::map<std::string, const vpImage<vpRGBa>*>;
  using PoseMap = std::map<std::string, vpHomogeneousMatrix>;
  using FileMap = std::map<std::string, std::string>;
  const GreyMap greys{{kCamera1, &I1}, {kCamera2, &I2}};
  const RgbaMap colors{{kCamera1, &C1}, {kCamera2, &C2}};

  const auto check_pose = [&](const vpHomogeneousMatrix& expected, double tolerance) {
    CHECK(max_difference(pose_of(t), expected) <= tolerance);
    vpHomogeneousMatrix c1Mo, c2Mo;
    t.getPose(c1Mo, c2Mo);
    CHECK(max_difference(c2Mo, rig.c2_M_c1 * pose_of(t)) == 0.0);
  };

  SECTION("poses") {
    t.initFromPose(I1, a);
    check_pose(a, 0.0);
    t.initFromPose(C1, b);
    check_pose(b, 0.0);
    t.initFromPose(I1, vpPoseVector(a));
    check_pose(vpHomogeneousMatrix(vpPoseVector(a)), 0.0);
    t.initFromPose(C1, vpPoseVector(b));
    check_pose(vpHomogeneousMatrix(vpPoseVector(b)), 0.0);
    t.initFromPose(I1, I2, a, in_camera2(a));
    check_pose(a, 0.0);
    t.initFromPose(C1, C2, b, in_camera2(b));
    check_pose(b, 0.0);
    t.initFromPose(greys, PoseMap{{kCamera1, a}, {kCamera2, in_camera2(a)}});
    check_pose(a, 0.0);
    t.initFromPose(greys, PoseMap{{kCamera2, in_camera2(b)}});
    check_pose(from_camera2(in_camera2(b)), 1e-9);
    check_pose(b, 1e-9);
    t.initFromPose(colors, PoseMap{{kCamera1, b}, {kCamera2, in_camera2(b)}});
    check_pose(b, 0.0);
    t.initFromPose(colors, PoseMap{{kCamera2, in_camera2(a)}});
    check_pose(from_camera2(in_camera2(a)), 1e-9);
    check_pose(a, 1e-9);
    // The tracker starts from there on the next frame.
    rig.track_rgbd(t, 0);
    rig.check_near_truth(t, 0);
  }
  SECTION("pose files") {
    const std::string file_a = dir.file("a.pos"), file_b = dir.file("b.pos");
    const std::string file_a2 = dir.file("a2.pos"), file_b2 = dir.file("b2.pos");
    const vpHomogeneousMatrix read_a = write_pos(file_a, a), read_b = write_pos(file_b, b);
    const vpHomogeneousMatrix read_a2 = write_pos(file_a2, in_camera2(a)), read_b2 = write_pos(file_b2, in_camera2(b));
    t.initFromPose(I1, file_a);
    check_pose(read_a, 0.0);
    t.initFromPose(C1, file_b);
    check_pose(read_b, 0.0);
    t.initFromPose(I1, dir.file("a"));  // ViSP's rule: ".pos" is added to a name without it
    check_pose(read_a, 0.0);
    t.initFromPose(I1, I2, file_b, file_b2);
    check_pose(read_b, 0.0);
    t.initFromPose(C1, C2, file_a, file_a2);
    check_pose(read_a, 0.0);
    t.initFromPose(greys, FileMap{{kCamera1, file_b}, {kCamera2, file_b2}});
    check_pose(read_b, 0.0);
    // (a .pos file holds a vpPoseVector, whose theta-u rotation ViSP converts to 1e-7)
    t.initFromPose(greys, FileMap{{kCamera2, file_a2}});
    check_pose(from_camera2(read_a2), 1e-9);
    check_pose(a, 1e-6);
    t.initFromPose(colors, FileMap{{kCamera2, file_b2}});
    check_pose(from_camera2(read_b2), 1e-9);
    check_pose(b, 1e-6);
    t.initFromPose(colors, FileMap{{kCamera1, file_a}});
    check_pose(read_a, 0.0);
    rig.track_rgbd(t, 0);
    rig.check_near_truth(t, 0);
  }
  SECTION("2D-3D point files") {
    // vpMbTracker::initFromPoints computes the pose from the corners' pixels in the camera
    // whose file is given: exact pixels give the pose to the solver's precision.
    const std::string points_a = dir.file("a.init"), points_b2 = dir.file("b2.init");
    const auto [points2D, points3D] = write_points(points_a, a, rig.cam1);
    write_points(points_b2, in_camera2(b), rig.cam2);
    const detail::StdoutSilencer quiet;  // vpMbTracker lists the points it reads
    t.initFromPoints(I1, points_a);
    check_pose(a, 1e-6);
    t.initFromPoints(C1, points_a);
    check_pose(a, 1e-6);
    t.initFromPoints(I1, points2D, points3D);
    check_pose(a, 1e-6);
    t.initFromPoints(C1, points2D, points3D);
    check_pose(a, 1e-6);
    t.initFromPoints(I1, I2, points_a, points_b2);
    check_pose(a, 1e-6);
    t.initFromPoints(C1, C2, points_a, points_b2);
    check_pose(a, 1e-6);
    t.initFromPoints(greys, FileMap{{kCamera2, points_b2}});
    check_pose(b, 1e-6);
    t.initFromPoints(colors, FileMap{{kCamera1, points_a}, {kCamera2, points_b2}});
    check_pose(a, 1e-6);
    t.initFromPoints(colors, FileMap{{kCamera2, points_b2}});
    check_pose(b, 1e-6);
  }
  SECTION("setPose") {
    t.initFromPose(I1, a);
    t.setPose(I1, b);
    check_pose(b, 0.0);
    t.setPose(C1, a);
    check_pose(a, 0.0);
    t.setPose(I1, I2, b, in_camera2(b));
    check_pose(b, 0.0);
    t.setPose(C1, C2, a, in_camera2(a));
    check_pose(a, 0.0);
    t.setPose(greys, PoseMap{{kCamera1, b}, {kCamera2, in_camera2(b)}});
    check_pose(b, 0.0);
    t.setPose(greys, PoseMap{{kCamera2, in_camera2(a)}});
    check_pose(from_camera2(in_camera2(a)), 1e-9);
    t.setPose(colors, PoseMap{{kCamera1, b}});
    check_pose(b, 0.0);
    t.setPose(colors, PoseMap{{kCamera2, in_camera2(a)}});
    check_pose(from_camera2(in_camera2(a)), 1e-9);
    check_pose(a, 1e-9);
    rig.track_rgbd(t, 0);
    rig.check_near_truth(t, 0);
    // init(I) restarts the cues at the current pose.
    const vpHomogeneousMatrix before = pose_of(t);
    t.init(I1);
    CHECK(bit_identical(pose_of(t), before));
  }
}

TEST_CASE("reInitModel in every form: the model is replaced and the pose is the given one") {
  Rig rig(1);
  vpMbIcgTracker t(kRgbdTrackerTypes);
  rig.setup(t);
  const unsigned int polygons = t.getNbPolygon();
  REQUIRE(polygons == 6);  // the teabox's faces
  const vpHomogeneousMatrix a = rig.truth(0);
  const vpHomogeneousMatrix b = vpHomogeneousMatrix(0.004, -0.003, 0.002, 0.01, -0.02, 0.015) * a;
  const vpHomogeneousMatrix a2 = rig.c2_M_c1 * a, b2 = rig.c2_M_c1 * b;
  const vpImage<unsigned char>& I1 = rig.grey(0);
  const vpImage<vpRGBa>& C1 = rig.colors[0];
  const detail::StdoutSilencer quiet_parser;

  t.reInitModel(I1, kTeaboxCao, a);
  CHECK(bit_identical(pose_of(t), a));
  CHECK(t.getNbPolygon() == polygons);  // replaced, not added to
  t.reInitModel(C1, kTeaboxCao, b);
  CHECK(bit_identical(pose_of(t), b));
  t.reInitModel(I1, rig.depth_image, kTeaboxCao, kTeaboxCao, a, a2);
  CHECK(bit_identical(pose_of(t), a));
  t.reInitModel(C1, C1, kTeaboxCao, kTeaboxCao, b, b2);
  CHECK(bit_identical(pose_of(t), b));
  t.reInitModel(std::map<std::string, const vpImage<unsigned char>*>{{kCamera1, &I1}, {kCamera2, &rig.depth_image}},
                std::map<std::string, std::string>{{kCamera1, kTeaboxCao}, {kCamera2, kTeaboxCao}},
                std::map<std::string, vpHomogeneousMatrix>{{kCamera2, a2}});
  CHECK(max_difference(pose_of(t), rig.c2_M_c1.inverse() * a2) <= 1e-9);
  t.reInitModel(std::map<std::string, const vpImage<vpRGBa>*>{{kCamera1, &C1}},
                std::map<std::string, std::string>{{kCamera1, kTeaboxCao}},
                std::map<std::string, vpHomogeneousMatrix>{{kCamera1, a}});
  CHECK(bit_identical(pose_of(t), a));
  CHECK(t.getNbPolygon() == polygons);
  rig.track_rgbd(t, 0);
  rig.check_near_truth(t, 0);
}

// ----------------------------------------------------------------- files and model

TEST_CASE("loadConfigFile's camera and two-camera forms read the cameras as vpMbGenericTracker does") {
  const auto same_cameras = [](const vpMbIcgTracker& ours, const vpMbGenericTracker& visp) {
    std::map<std::string, vpCameraParameters> o, v;
    ours.getCameraParameters(o);
    visp.getCameraParameters(v);
    REQUIRE(o.size() == v.size());
    for (const auto& [name, camera] : v) {
      INFO(name);
      CHECK(same_camera(o.at(name), camera));
    }
  };
  SECTION("map of ViSP XML files") {
    vpMbIcgTracker ours(kRgbdTrackerTypes);
    vpMbGenericTracker visp(kRgbdTrackerTypes);
    const std::map<std::string, std::string> files{{kCamera1, kColorXml}, {kCamera2, kDepthXml}};
    ours.loadConfigFile(files, false);
    visp.loadConfigFile(files, false);
    same_cameras(ours, visp);
  }
  SECTION("two ViSP XML files") {
    vpMbIcgTracker ours(kRgbdTrackerTypes);
    vpMbGenericTracker visp(kRgbdTrackerTypes);
    ours.loadConfigFile(kDepthXml, kColorXml, false);  // swapped, so that the order shows
    visp.loadConfigFile(kDepthXml, kColorXml, false);
    same_cameras(ours, visp);
  }
  SECTION("map with icgp's YAML") {
    vpMbIcgTracker ours(kRgbdTrackerTypes);
    CHECK(ours.getTrackerConfig().region_model.n_divides != 3);
    ours.loadConfigFile(std::map<std::string, std::string>{{kCamera1, ICGP_TEST_CONFIGS_DIR "/coarse_models.yaml"}},
                        false);
    CHECK(ours.getTrackerConfig().region_model.n_divides == 3);
  }
}

TEST_CASE("loadConfigFile(ViSP XML) sets ViSP's own settings for their getters, as vpMbGenericTracker does") {
  // vpMbIcgTracker reads the XML's <camera> block only: the <ecm>, <klt> and <face> blocks
  // (moving edges, KLT, angles and clipping) are not stored for their getters.
  vpMbIcgTracker ours(kRgbdTrackerTypes);
  vpMbGenericTracker visp(kRgbdTrackerTypes);
  const std::map<std::string, std::string> files{{kCamera1, kColorXml}, {kCamera2, kDepthXml}};
  ours.loadConfigFile(files, false);
  visp.loadConfigFile(files, false);
  CHECK(same_me(ours.getMovingEdge(), visp.getMovingEdge()));
  CHECK(same_klt(ours.getKltOpencv(), visp.getKltOpencv()));
  CHECK(ours.getAngleAppear() == visp.getAngleAppear());
  CHECK(ours.getNearClippingDistance() == visp.getNearClippingDistance());
  unsigned int o1 = 0, o2 = 0, v1 = 0, v2 = 0;
  ours.getClipping(o1, o2);
  visp.getClipping(v1, v2);
  CHECK(o1 == v1);
  CHECK(o2 == v2);
}

TEST_CASE("loadModel's two-camera and map forms describe one object: faces and polygons as in vpMbGenericTracker") {
  Rig rig(1);
  vpMbIcgTracker ours(kRgbdTrackerTypes);
  test::configure_for_tests(ours);
  vpMbGenericTracker visp(kRgbdTrackerTypes);
  const vpHomogeneousMatrix T(0.01, -0.02, 0.03, 0.0, 0.0, 0.2);
  const std::map<std::string, std::string> files{{kCamera1, kTeaboxCao}, {kCamera2, kTeaboxCao}};
  const std::map<std::string, vpHomogeneousMatrix> transforms{{kCamera1, T}, {kCamera2, T}};
  {
    const detail::StdoutSilencer quiet_parser;
    ours.loadModel(files, false, transforms);
    visp.loadModel(files, false, transforms);
  }
  ours.setCameraParameters(rig.cam1, rig.cam2);
  visp.setCameraParameters(rig.cam1, rig.cam2);
  ours.setCameraTransformationMatrix(kCamera2, rig.c2_M_c1);
  visp.setCameraTransformationMatrix(kCamera2, rig.c2_M_c1);
  // ViSP's per-camera polygon queries use each camera's pose: give both.
  const vpHomogeneousMatrix cMo = rig.truth(0) * T.inverse();
  const std::map<std::string, const vpImage<unsigned char>*> images{{kCamera1, &rig.grey(0)},
                                                                    {kCamera2, &rig.depth_image}};
  const std::map<std::string, vpHomogeneousMatrix> poses{{kCamera1, cMo}, {kCamera2, rig.c2_M_c1 * cMo}};
  ours.initFromPose(images, poses);
  visp.initFromPose(images, poses);

  CHECK(ours.getNbPolygon() == visp.getNbPolygon());
  std::map<std::string, unsigned int> ours_counts, visp_counts;
  ours.getNbPolygon(ours_counts);
  visp.getNbPolygon(visp_counts);
  CHECK(ours_counts == visp_counts);
  CHECK(ours.getFaces().size() == visp.getFaces().size());
  for (const std::string& camera : {kCamera1, kCamera2}) {
    INFO(camera);
    CHECK(ours.getFaces(camera).size() == visp.getFaces(camera).size());
    for (unsigned int i = 0; i < visp.getNbPolygon(); ++i) {
      vpMbtPolygon* o = ours.getPolygon(camera, i);
      vpMbtPolygon* v = visp.getPolygon(camera, i);
      REQUIRE(o != nullptr);
      REQUIRE(v != nullptr);
      REQUIRE(o->getNbPoint() == v->getNbPoint());
      for (unsigned int j = 0; j < v->getNbPoint(); ++j) {  // model points, placed by T
        CHECK(o->getPoint(j).get_oX() == Approx(v->getPoint(j).get_oX()).margin(1e-12));
        CHECK(o->getPoint(j).get_oY() == Approx(v->getPoint(j).get_oY()).margin(1e-12));
        CHECK(o->getPoint(j).get_oZ() == Approx(v->getPoint(j).get_oZ()).margin(1e-12));
      }
      CHECK(ours.getPolygon(i) == ours.getPolygon(kCamera1, i));
    }
  }

  // Every face's outline in every camera (without ViSP's visibility test).
  std::map<std::string, std::vector<vpPolygon>> ours_polygons, visp_polygons;
  std::map<std::string, std::vector<std::vector<vpPoint>>> ours_points, visp_points;
  ours.getPolygonFaces(ours_polygons, ours_points, true, false, false);
  visp.getPolygonFaces(visp_polygons, visp_points, true, false, false);
  REQUIRE(ours_polygons.size() == visp_polygons.size());
  for (const auto& [camera, polygons] : visp_polygons) {
    INFO(camera);
    REQUIRE(ours_polygons.at(camera).size() == polygons.size());
    REQUIRE(ours_points.at(camera).size() == visp_points.at(camera).size());
    for (std::size_t k = 0; k < polygons.size(); ++k) {
      const std::vector<vpImagePoint> o = ours_polygons.at(camera)[k].getCorners();
      const std::vector<vpImagePoint> v = polygons[k].getCorners();
      REQUIRE(o.size() == v.size());
      for (std::size_t j = 0; j < v.size(); ++j) {
        CHECK(o[j].get_i() == Approx(v[j].get_i()).margin(1e-9));
        CHECK(o[j].get_j() == Approx(v[j].get_j()).margin(1e-9));
      }
    }
  }
  const auto ours_reference = ours.getPolygonFaces(false, false, false);
  const auto visp_reference = visp.getPolygonFaces(false, false, false);
  CHECK(ours_reference.first.size() == visp_reference.first.size());

  // A file of another object for the second camera is said on stderr (one rigid object is
  // tracked by every camera, the reference camera's); the program goes on, as with ViSP.
  vpMbIcgTracker two_objects(kRgbdTrackerTypes);
  const detail::StdoutSilencer quiet_parser;
  std::string said;
  {
    const icgp::StandardStreamCapture stderr_text(std::cerr);
    two_objects.loadModel(kTeaboxCao, kCubeCao);
    two_objects.loadModel(std::map<std::string, std::string>{{kCamera1, kTeaboxCao}, {kCamera2, kCubeCao}});
    said = stderr_text.text();
  }
  CHECK_THAT(said, Contains("cube.cao") && Contains("does not describe the object"));
}

TEST_CASE("getPolygonFaces with ViSP's visibility test gives ViSP's visible faces") {
  // vpMbTracker::getPolygonFaces(useVisibility = true) keeps the faces whose visibility flag
  // the tracker computed; vpMbIcgTracker computes it for the call (its cues need none).
  Rig rig(1);
  vpMbIcgTracker ours(kRgbdTrackerTypes);
  vpMbGenericTracker visp(kRgbdTrackerTypes);
  rig.setup(ours);
  rig.setup(visp);
  const std::map<std::string, const vpImage<unsigned char>*> images{{kCamera1, &rig.grey(0)},
                                                                    {kCamera2, &rig.depth_image}};
  const std::map<std::string, vpHomogeneousMatrix> poses{{kCamera1, rig.truth(0)},
                                                         {kCamera2, rig.c2_M_c1 * rig.truth(0)}};
  ours.initFromPose(images, poses);
  visp.initFromPose(images, poses);
  const auto visp_visible = visp.getPolygonFaces();
  REQUIRE(!visp_visible.first.empty());
  CHECK(ours.getPolygonFaces().first.size() == visp_visible.first.size());
}

// ---------------------------------------------------------- results of tracked frames

TEST_CASE("every track form, and the features, counts, model and display of a tracked frame") {
  Rig rig(3);
  vpMbIcgTracker t(kRgbdTrackerTypes);
  rig.setup(t);
  const vpImage<unsigned char>& I2 = rig.depth_image;  // what the depth camera gets in the image-only forms
  const auto check_without_depth = [&](const char* form, int i) {
    INFO(form);
    rig.check_near_truth(t, i, 5.0, 1.0);  // region and texture alone: less exact along the line of sight
    CHECK(t.getNbFeaturesDepthDense() == 0);  // the depth camera, without depth this frame, sat out
  };
  // Colour images: the RGB-D form (with the depth camera's cloud), then the image-only forms.
  t.initFromPose(rig.colors[0], rig.truth(0));
  rig.track_rgbd(t, 0, rig.colors[0]);
  rig.check_near_truth(t, 0);
  vpImage<vpRGBa> C2;
  vpImageConvert::convert(I2, C2);
  std::map<std::string, const vpImage<vpRGBa>*> colors{{kCamera1, &rig.colors[1]}};
  t.track(rig.colors[1], C2);
  check_without_depth("track(I_color1, I_color2)", 1);
  t.track(colors);
  check_without_depth("track(mapOfColorImages)", 1);
  t.track(rig.colors[1]);
  check_without_depth("track(I_color)", 1);
  // Grey images (icgp's region cue does not switch between grey and colour images without
  // a new initialisation): the same forms.
  t.initFromPose(rig.grey(1), rig.truth(1));
  rig.track_rgbd(t, 1);
  rig.check_near_truth(t, 1);
  const vpImage<unsigned char>& I1 = rig.grey(2);
  const vpImage<vpRGBa>& C1 = rig.colors[2];
  std::map<std::string, const vpImage<unsigned char>*> greys{{kCamera1, &I1}, {kCamera2, &I2}};
  t.track(I1, I2);
  check_without_depth("track(I1, I2)", 2);
  t.track(greys);
  check_without_depth("track(mapOfImages)", 2);
  t.track(I1);
  check_without_depth("track(I)", 2);
  vpImage<bool> everywhere(I1.getHeight(), I1.getWidth(), true);  // every pixel may be used
  t.setMask(everywhere);
  rig.track_rgbd(t, 2);
  rig.check_near_truth(t, 2);
  CHECK_NOTHROW(t.testTracking());
  CHECK(t.getError().size() > 0);
  CHECK(t.getError().size() == t.getRobustWeights().size());

  // getFeaturesForDisplay: ViSP's {0, i, j, state} for moving edges (icgp: region contour
  // points) and {1, i, j, id} for KLT points (icgp: texture matches), in the image.
  const std::vector<std::vector<double>> features = t.getFeaturesForDisplay();
  REQUIRE(!features.empty());
  unsigned int edges = 0, klts = 0;
  std::map<int, vpImagePoint> klt_features;
  for (const std::vector<double>& f : features) {
    REQUIRE(f.size() == 4);
    CHECK((f[0] == 0.0 || f[0] == 1.0));
    CHECK(f[1] >= 0.0);
    CHECK(f[1] < I1.getHeight());
    CHECK(f[2] >= 0.0);
    CHECK(f[2] < I1.getWidth());
    if (f[0] == 0.0) {
      ++edges;
      CHECK((f[3] == 0.0 || f[3] == 4.0));  // vpMeSite::NO_SUPPRESSION, M_ESTIMATOR
    } else {
      ++klts;
      klt_features[static_cast<int>(f[3])] = vpImagePoint(f[1], f[2]);
    }
  }
  CHECK(edges > 0);
  CHECK(klts > 0);
  CHECK(t.getNbFeaturesEdge() == edges);  // one colour camera: all edges are the reference camera's
  CHECK(t.getNbFeaturesKlt() == 2 * klts);  // ViSP's count: x and y of each point
  CHECK(t.getNbFeaturesDepthDense() > 0);
  CHECK(t.getNbFeaturesDepthNormal() == 0);  // no camera is DEPTH_NORMAL_TRACKER
  std::map<std::string, std::vector<std::vector<double>>> features_of;
  t.getFeaturesForDisplay(features_of);
  REQUIRE(features_of.size() == 2);
  CHECK(features_of.at(kCamera1) == features);
  CHECK(features_of.at(kCamera2).empty());  // the depth camera has no image features
  CHECK(t.getNbPoints() == edges);
  std::map<std::string, unsigned int> points_of;
  t.getNbPoints(points_of);
  CHECK(points_of == std::map<std::string, unsigned int>{{kCamera1, edges}, {kCamera2, 0}});

  // The KLT getters agree with one another and with the features.
  const std::map<int, vpImagePoint> with_id = t.getKltImagePointsWithId();
  const std::vector<vpImagePoint> klt_points = t.getKltImagePoints();
  const std::vector<cv::Point2f> cv_points = t.getKltPoints();
  CHECK(t.getKltNbPoints() == static_cast<int>(klts));
  REQUIRE(with_id.size() == klts);
  REQUIRE(klt_points.size() == klts);
  REQUIRE(cv_points.size() == klts);
  std::size_t k = 0;
  for (const auto& [id, point] : with_id) {
    REQUIRE(klt_features.count(id) == 1);
    CHECK(klt_features.at(id) == point);
    CHECK(klt_points[k] == point);
    CHECK(cv_points[k].x == Approx(point.get_u()).margin(1e-3));  // cv::Point2f(u, v)
    CHECK(cv_points[k].y == Approx(point.get_v()).margin(1e-3));
    ++k;
  }

  // ViSP's lists of its own primitives: icgp tracks none.
  std::list<vpMbtDistanceCircle*> circles{nullptr};
  std::list<vpMbtDistanceCylinder*> cylinders{nullptr};
  std::list<vpMbtDistanceLine*> lines{nullptr};
  t.getLcircle(circles);
  t.getLcylinder(cylinders);
  t.getLline(lines);
  CHECK(circles.empty());
  CHECK(cylinders.empty());
  CHECK(lines.empty());
  for (const std::string& camera : {kCamera1, kCamera2}) {
    circles.push_back(nullptr);
    cylinders.push_back(nullptr);
    lines.push_back(nullptr);
    t.getLcircle(camera, circles);
    t.getLcylinder(camera, cylinders, 1);
    t.getLline(camera, lines, 2);
    CHECK(circles.empty());
    CHECK(cylinders.empty());
    CHECK(lines.empty());
  }
  CHECK(t.getFeaturesCircle().empty());
  CHECK(t.getFeaturesKlt().empty());
  CHECK(t.getFeaturesKltCylinder().empty());

  // The model for display: the map form is the single form camera by camera.
  vpHomogeneousMatrix c1Mo, c2Mo;
  t.getPose(c1Mo, c2Mo);
  for (bool full : {false, true}) {
    INFO("displayFullModel " << full);
    std::map<std::string, std::vector<std::vector<double>>> models;
    t.getModelForDisplay(models, {{kCamera1, I1.getWidth()}, {kCamera2, I2.getWidth()}},
                         {{kCamera1, I1.getHeight()}, {kCamera2, I2.getHeight()}},
                         {{kCamera1, c1Mo}, {kCamera2, c2Mo}}, {{kCamera1, rig.cam1}, {kCamera2, rig.cam2}}, full);
    REQUIRE(models.size() == 2);
    CHECK(!models.at(kCamera1).empty());
    CHECK(models.at(kCamera1) == t.getModelForDisplay(I1.getWidth(), I1.getHeight(), c1Mo, rig.cam1, full));
    CHECK(models.at(kCamera2) == t.getModelForDisplay(I2.getWidth(), I2.getHeight(), c2Mo, rig.cam2, full));
  }

  // display draws into images without a display window: ViSP's drawing calls do nothing
  // then, so every form must simply not throw and leave the images as they are.
  vpImage<unsigned char> D1 = I1, D2 = I2;
  vpImage<vpRGBa> E1 = C1, E2;
  vpImageConvert::convert(I2, E2);
  t.setDisplayFeatures(true);
  CHECK_NOTHROW(t.display(D1, c1Mo, rig.cam1, vpColor::red, 2));
  CHECK_NOTHROW(t.display(E1, c1Mo, rig.cam1, vpColor::red, 2, true));
  CHECK_NOTHROW(t.display(D1, D2, c1Mo, c2Mo, rig.cam1, rig.cam2, vpColor::red, 2));
  CHECK_NOTHROW(t.display(E1, E2, c1Mo, c2Mo, rig.cam1, rig.cam2, vpColor::red, 2, true));
  const std::map<std::string, vpHomogeneousMatrix> poses{{kCamera1, c1Mo}, {kCamera2, c2Mo}};
  const std::map<std::string, vpCameraParameters> cameras{{kCamera1, rig.cam1}, {kCamera2, rig.cam2}};
  CHECK_NOTHROW(t.display(std::map<std::string, const vpImage<unsigned char>*>{{kCamera1, &D1}, {kCamera2, &D2}},
                          poses, cameras, vpColor::green));
  CHECK_NOTHROW(t.display(std::map<std::string, const vpImage<vpRGBa>*>{{kCamera1, &E1}, {kCamera2, &E2}}, poses,
                          cameras, vpColor::green, 1, true));
  const bool grey_unchanged = D1 == I1, color_unchanged = E1 == C1;  // vpImage's == is not const
  CHECK(grey_unchanged);
  CHECK(color_unchanged);

  // ViSP's projection error: the same for a colour image and its grey levels.
  vpImage<unsigned char> grey_of_color;
  vpImageConvert::convert(C1, grey_of_color);
  const double from_grey = t.computeCurrentProjectionError(grey_of_color, c1Mo, rig.cam1);
  const double from_color = t.computeCurrentProjectionError(C1, c1Mo, rig.cam1);
  CHECK(from_grey == from_color);
  CHECK(from_grey >= 0.0);
  CHECK(from_grey < 10.0);  // degrees, at the tracked pose
}

// -------------------------------------------------- settings of ViSP's own cues

namespace {

/// Every setting of ViSP's own cues in every form, as a ViSP program writes them; the same
/// calls on vpMbGenericTracker and vpMbIcgTracker (two cameras, "Camera1" and "Camera2").
template <class Tracker>
void apply_settings(Tracker& t, bool with_klt) {
  vpMe me_all, me1, me2;
  me_all.setRange(6);
  me1.setRange(11);
  me1.setThreshold(5000);
  me1.setSampleStep(5);
  me2.setRange(13);
  me2.setMu1(0.7);
  me2.setMu2(0.6);
  t.setMovingEdge(me_all);
  t.setMovingEdge(me1, me2);
  t.setMovingEdge(std::map<std::string, vpMe>{{kCamera2, me_all}});  // now: Camera1 me1, Camera2 me_all

  if (with_klt) {
    vpKltOpencv klt_all, klt1, klt2;
    klt_all.setMaxFeatures(123);
    klt_all.setWindowSize(7);
    klt1.setMaxFeatures(150);
    klt1.setQuality(0.02);
    klt2.setMaxFeatures(77);
    klt2.setPyramidLevels(2);
    t.setKltOpencv(klt_all);
    t.setKltOpencv(klt1, klt2);
    t.setKltOpencv(std::map<std::string, vpKltOpencv>{{kCamera1, klt_all}});  // Camera1 klt_all, Camera2 klt2
    t.setKltMaskBorder(4u);
    t.setKltMaskBorder(6u, 7u);
    t.setKltMaskBorder(std::map<std::string, unsigned int>{{kCamera1, 8u}});  // Camera1 8, Camera2 7
  }
  t.setKltThresholdAcceptation(0.7);
  t.setGoodMovingEdgesRatioThreshold(0.3);

  t.setClipping(vpPolygon3D::FOV_CLIPPING);
  t.setClipping(vpPolygon3D::NO_CLIPPING, vpPolygon3D::NO_CLIPPING);
  t.setClipping(std::map<std::string, unsigned int>{{kCamera2, vpPolygon3D::FOV_CLIPPING}});
  t.setNearClippingDistance(std::map<std::string, double>{{kCamera2, 0.2}});
  t.setFarClippingDistance(4.0, 5.0);  // now: Camera1 FAR, Camera2 FOV | NEAR | FAR
  t.setAngleAppear(vpMath::rad(60));
  t.setAngleAppear(vpMath::rad(65), vpMath::rad(66));
  t.setAngleAppear(std::map<std::string, double>{{kCamera2, vpMath::rad(67)}});  // the reference's: 65
  t.setAngleDisappear(vpMath::rad(70));
  t.setAngleDisappear(vpMath::rad(75), vpMath::rad(76));
  t.setAngleDisappear(std::map<std::string, double>{{kCamera1, vpMath::rad(80)}});  // the reference's: 80

  t.setLod(true);
  t.setLod(false, "no such face");
  t.setMinLineLengthThresh(40.0);
  t.setMinLineLengthThresh(30.0, "no such face");
  t.setMinPolygonAreaThresh(2000.0);
  t.setMinPolygonAreaThresh(1000.0, "no such face");
  t.setOgreShowConfigDialog(false);
  t.setOgreVisibilityTest(true);
  t.setScanLineVisibilityTest(true);
  t.setOptimizationMethod(vpMbTracker::LEVENBERG_MARQUARDT_OPT);
  t.setProjectionErrorDisplay(true);
  t.setProjectionErrorDisplayArrowLength(20);
  t.setProjectionErrorDisplayArrowThickness(2);

  t.setDepthDenseFilteringMaxDistance(2.0);
  t.setDepthDenseFilteringMethod(2);
  t.setDepthDenseFilteringMinDistance(0.1);
  t.setDepthDenseFilteringOccupancyRatio(0.5);
  t.setDepthDenseSamplingStep(2, 2);
  t.setDepthNormalFaceCentroidMethod(vpMbtFaceDepthNormal::MEAN_CENTROID);
  t.setDepthNormalFeatureEstimationMethod(vpMbtFaceDepthNormal::ROBUST_SVD_PLANE_ESTIMATION);
  t.setDepthNormalPclPlaneEstimationMethod(2);
  t.setDepthNormalPclPlaneEstimationRansacMaxIter(100);
  t.setDepthNormalPclPlaneEstimationRansacThreshold(0.002);
  t.setDepthNormalSamplingStep(3, 3);
  t.setFeatureFactors(std::map<typename Tracker::vpTrackerType, double>{{Tracker::EDGE_TRACKER, 2.0},
                                                                         {Tracker::DEPTH_DENSE_TRACKER, 0.5}});
  t.setUseDepthDenseTracking("no such face", false);
  t.setUseDepthNormalTracking("no such face", false);
  t.setUseEdgeTracking("no such face", false);
  t.setUseKltTracking("no such face", false);
}

/// The settings' getters answer as vpMbGenericTracker's.
void check_same_settings(const vpMbIcgTracker& ours, const vpMbGenericTracker& visp) {
  CHECK(same_me(ours.getMovingEdge(), visp.getMovingEdge()));
  vpMe o1, o2, v1, v2;
  ours.getMovingEdge(o1, o2);
  visp.getMovingEdge(v1, v2);
  CHECK(same_me(o1, v1));
  CHECK(same_me(o2, v2));
  std::map<std::string, vpMe> ours_me, visp_me;
  ours.getMovingEdge(ours_me);
  visp.getMovingEdge(visp_me);
  REQUIRE(ours_me.size() == visp_me.size());
  for (const auto& [name, me] : visp_me) CHECK(same_me(ours_me.at(name), me));

  CHECK(same_klt(ours.getKltOpencv(), visp.getKltOpencv()));
  vpKltOpencv k1, k2, l1, l2;
  ours.getKltOpencv(k1, k2);
  visp.getKltOpencv(l1, l2);
  CHECK(same_klt(k1, l1));
  CHECK(same_klt(k2, l2));
  std::map<std::string, vpKltOpencv> ours_klt, visp_klt;
  ours.getKltOpencv(ours_klt);
  visp.getKltOpencv(visp_klt);
  REQUIRE(ours_klt.size() == visp_klt.size());
  for (const auto& [name, klt] : visp_klt) CHECK(same_klt(ours_klt.at(name), klt));

  CHECK(ours.getKltMaskBorder() == visp.getKltMaskBorder());
  CHECK(ours.getGoodMovingEdgesRatioThreshold() == visp.getGoodMovingEdgesRatioThreshold());

  unsigned int f1 = 0, f2 = 0, g1 = 0, g2 = 0;
  ours.getClipping(f1, f2);
  visp.getClipping(g1, g2);
  CHECK(f1 == g1);
  CHECK(f2 == g2);
  std::map<std::string, unsigned int> ours_flags, visp_flags;
  ours.getClipping(ours_flags);
  visp.getClipping(visp_flags);
  CHECK(ours_flags == visp_flags);
  CHECK(ours.getNearClippingDistance() == visp.getNearClippingDistance());
  CHECK(ours.getFarClippingDistance() == visp.getFarClippingDistance());
  CHECK(ours.getAngleAppear() == visp.getAngleAppear());
  CHECK(ours.getAngleDisappear() == visp.getAngleDisappear());
  CHECK(ours.getOptimizationMethod() == visp.getOptimizationMethod());
}

/// The settings reported once as having no effect. (The depth sampling steps act when depth
/// is the only cue; with the fused cues applied here they leave the pose bit-identical.)
const std::vector<std::string> kWithoutEffect = {
    "setMovingEdge", "setKltThresholdAcceptation", "setGoodMovingEdgesRatioThreshold",
    "setClipping", "setNearClippingDistance", "setFarClippingDistance", "setAngleAppear", "setAngleDisappear",
    "setLod", "setMinLineLengthThresh", "setMinPolygonAreaThresh", "setOgreShowConfigDialog",
    "setOgreVisibilityTest", "setScanLineVisibilityTest", "setOptimizationMethod", "setProjectionErrorDisplay",
    "setProjectionErrorDisplayArrowLength", "setProjectionErrorDisplayArrowThickness",
    "setDepthDenseFilteringMaxDistance", "setDepthDenseFilteringMethod", "setDepthDenseFilteringMinDistance",
    "setDepthDenseFilteringOccupancyRatio", "setDepthNormalFaceCentroidMethod",
    "setDepthNormalFeatureEstimationMethod", "setDepthNormalPclPlaneEstimationMethod",
    "setDepthNormalPclPlaneEstimationRansacMaxIter", "setDepthNormalPclPlaneEstimationRansacThreshold",
    "setFeatureFactors", "setUseDepthDenseTracking", "setUseDepthNormalTracking",
    "setUseEdgeTracking", "setUseKltTracking"};

}  // namespace

TEST_CASE("the settings of ViSP's own cues round-trip through their getters as in vpMbGenericTracker") {
  vpMbIcgTracker ours(kRgbdTrackerTypes);
  vpMbGenericTracker visp(kRgbdTrackerTypes);
  {
    INFO("defaults");
    check_same_settings(ours, visp);
    CHECK(ours.getClipping() == visp.getClipping());
  }
  {
    const StandardStreamCapture quiet(std::cerr);
    apply_settings(ours, true);
    apply_settings(visp, true);
  }
  {
    INFO("after every form of every setting");
    check_same_settings(ours, visp);
    CHECK(ours.getKltThresholdAcceptation() == visp.getKltThresholdAcceptation());
  }
  ours.setReferenceCameraName(kCamera2);
  visp.setReferenceCameraName(kCamera2);
  {
    INFO("the single-value getters are the reference camera's");
    check_same_settings(ours, visp);
  }
}

TEST_CASE("the single-value clipping settings apply to every camera, as in vpMbGenericTracker") {
  vpMbIcgTracker ours(kRgbdTrackerTypes);
  vpMbGenericTracker visp(kRgbdTrackerTypes);
  const StandardStreamCapture quiet(std::cerr);  // the reports, and vpMbTracker's notes on the refused distances
  const auto check_same = [&](const char* step) {
    INFO(step);
    CHECK(ours.getClipping() == visp.getClipping());
    unsigned int f1 = 0, f2 = 0, g1 = 0, g2 = 0;
    ours.getClipping(f1, f2);
    visp.getClipping(g1, g2);
    CHECK(f1 == g1);
    CHECK(f2 == g2);
    CHECK(ours.getNearClippingDistance() == visp.getNearClippingDistance());
    CHECK(ours.getFarClippingDistance() == visp.getFarClippingDistance());
  };
  ours.setClipping(vpPolygon3D::NEAR_CLIPPING, vpPolygon3D::FOV_CLIPPING);
  visp.setClipping(vpPolygon3D::NEAR_CLIPPING, vpPolygon3D::FOV_CLIPPING);
  check_same("setClipping(NEAR_CLIPPING, FOV_CLIPPING)");
  ours.setClipping(vpPolygon3D::NO_CLIPPING);
  visp.setClipping(vpPolygon3D::NO_CLIPPING);
  check_same("setClipping(NO_CLIPPING)");
  ours.setNearClippingDistance(0.05);
  visp.setNearClippingDistance(0.05);
  check_same("setNearClippingDistance(0.05)");
  ours.setFarClippingDistance(3.0);
  visp.setFarClippingDistance(3.0);
  check_same("setFarClippingDistance(3.0)");
  ours.setNearClippingDistance(-1.0);
  visp.setNearClippingDistance(-1.0);
  check_same("setNearClippingDistance(-1.0), refused");
  ours.setNearClippingDistance(10.0);
  visp.setNearClippingDistance(10.0);
  check_same("setNearClippingDistance(10.0), beyond the far distance, refused");
  ours.setFarClippingDistance(0.01);
  visp.setFarClippingDistance(0.01);
  check_same("setFarClippingDistance(0.01), before the near distance, refused");
  ours.setClipping(vpPolygon3D::FOV_CLIPPING);
  visp.setClipping(vpPolygon3D::FOV_CLIPPING);
  ours.setNearClippingDistance(0.1);
  visp.setNearClippingDistance(0.1);
  check_same("setClipping(FOV_CLIPPING), setNearClippingDistance(0.1)");
}

TEST_CASE("getKltThresholdAcceptation's default is vpMbGenericTracker's") {
  // vpMbGenericTracker's m_thresholdOutlier starts at 0.5; Impl::VispSettings at 0.0.
  CHECK(vpMbIcgTracker(kRgbdTrackerTypes).getKltThresholdAcceptation() ==
        vpMbGenericTracker(kRgbdTrackerTypes).getKltThresholdAcceptation());
}

TEST_CASE("settings without effect: each reported once on std::cerr, and the tracked pose bit-identical") {
  Rig rig(3);
  vpMbIcgTracker plain(kRgbdTrackerTypes), again(kRgbdTrackerTypes), tuned(kRgbdTrackerTypes);
  for (vpMbIcgTracker* t : {&plain, &again, &tuned}) rig.setup(*t);
  std::string said;
  {
    const StandardStreamCapture capture(std::cerr);
    apply_settings(tuned, false);
    apply_settings(tuned, false);  // every call twice: still reported once
    said = capture.text();
  }
  for (const std::string& name : kWithoutEffect) {
    INFO(name);
    CHECK(occurrences(said, "vpMbIcgTracker::" + name + ": no effect (") == 1);
  }
  CHECK(occurrences(said, "vpMbIcgTracker::") == kWithoutEffect.size());  // nothing else

  // The settings that act are not reported.
  {
    const StandardStreamCapture capture(std::cerr);
    vpMbIcgTracker t(kRgbdTrackerTypes);
    vpKltOpencv klt;
    klt.setMaxFeatures(200);
    t.setKltOpencv(klt);
    t.setDisplayFeatures(true);
    t.setProjectionErrorComputation(true);
    CHECK(capture.text().find("vpMbIcgTracker::") == std::string::npos);
  }

  for (vpMbIcgTracker* t : {&plain, &again, &tuned}) t->initFromPose(rig.grey(0), rig.truth(0));
  for (int i = 0; i < 3; ++i) {
    for (vpMbIcgTracker* t : {&plain, &again, &tuned}) rig.track_rgbd(*t, i);
    INFO("frame " << i);
    rig.check_near_truth(plain, i);
    REQUIRE(bit_identical(pose_of(again), pose_of(plain)));  // tracking is deterministic, so
    CHECK(bit_identical(pose_of(tuned), pose_of(plain)));   // any difference would be the settings'
  }
}

TEST_CASE("setKltOpencv's maximum number of features is the texture cue's") {
  vpMbIcgTracker t(kRgbdTrackerTypes);
  vpKltOpencv klt;
  klt.setMaxFeatures(123);
  t.setKltOpencv(klt);
  CHECK(t.getTrackerConfig().texture.orb_n_features == 123);
  CHECK(t.getKltOpencv().getMaxFeatures() == 123);
  vpKltOpencv first, second;
  first.setMaxFeatures(150);
  second.setMaxFeatures(77);
  t.setKltOpencv(first, second);
  CHECK(t.getTrackerConfig().texture.orb_n_features == 150);  // the reference camera's
  t.setKltOpencv(std::map<std::string, vpKltOpencv>{});       // nothing to set
  CHECK(t.getTrackerConfig().texture.orb_n_features == 150);
}

// --------------------------------------------------------------------- refused calls

TEST_CASE("vpMbIcgTracker refuses invalid cameras with a vpException naming the value") {
  using Names = std::vector<std::string>;
  using Types = std::vector<int>;
  const auto check_constructor = [](const std::string& value, auto&& construct) {
    INFO("vpMbIcgTracker(...) refusing " << value);
    const vpException e = vp_exception_of(construct);
    CHECK(e.getCode() == vpException::badValue);
    CHECK_THAT(e.getStringMessage(), Contains("vpMbIcgTracker") && Contains(value));
  };
  check_constructor("at least one camera", [] { vpMbIcgTracker t(0u); });
  check_constructor("at least one camera", [] { vpMbIcgTracker t(0u, kEdge); });
  check_constructor("at least one camera", [] { vpMbIcgTracker t(Types{}); });
  check_constructor("at least one camera", [] { vpMbIcgTracker t(Names{}, Types{}); });
  check_constructor("2 camera names but 1 tracker types", [] { vpMbIcgTracker t(Names{"A", "B"}, Types{kEdge}); });
  check_constructor("1 camera names but 2 tracker types", [] { vpMbIcgTracker t(Names{"A"}, Types{kEdge, kKlt}); });
  check_constructor("tracker type 0", [] { vpMbIcgTracker t(1u, 0); });
  check_constructor("tracker type 16", [] { vpMbIcgTracker t(2u, 16); });
  check_constructor("tracker type 0", [] { vpMbIcgTracker t(Types{0}); });
  check_constructor("tracker type 16", [] { vpMbIcgTracker t(Types{kEdge, 16}); });
  check_constructor("tracker type 33", [] { vpMbIcgTracker t(Types{kEdge | 32}); });
  check_constructor("tracker type 0", [] { vpMbIcgTracker t(Names{"A"}, Types{0}); });
  check_constructor("tracker type 16", [] { vpMbIcgTracker t(Names{"A"}, Types{16}); });
  check_constructor("'A' is named twice", [] { vpMbIcgTracker t(Names{"A", "A"}, Types{kEdge, kEdge}); });

  vpMbIcgTracker t(kRgbdTrackerTypes);
  check_refused("setTrackerType", "tracker type 0", [&] { t.setTrackerType(0); });
  check_refused("setTrackerType", "tracker type 16", [&] { t.setTrackerType(16); });
  check_refused("setTrackerType", "tracker type 16",
                [&] { t.setTrackerType(std::map<std::string, int>{{kCamera1, 16}}); });
  check_refused("setCameraTransformationMatrix", kCamera1, [&] {
    t.setCameraTransformationMatrix(kCamera1, vpHomogeneousMatrix(0.1, 0.0, 0.0, 0.0, 0.0, 0.0));
  });
  check_same_cameras(t, vpMbGenericTracker(kRgbdTrackerTypes));  // unchanged
}

TEST_CASE("every map overload refuses an unknown camera with a vpException naming the call and the camera") {
  Rig rig(1);
  vpMbIcgTracker t(kRgbdTrackerTypes);
  rig.setup(t);
  t.initFromPose(rig.grey(0), rig.truth(0));
  const std::string u = "Camera3";
  const test::TempDir dir("icgp-test-vpmbicgtracker-api");
  const std::string pose_file = dir.file("a.pos");
  write_pos(pose_file, rig.truth(0));
  const vpImage<unsigned char>& I = rig.grey(0);
  const vpImage<vpRGBa>& C = rig.colors[0];
  const vpHomogeneousMatrix a = rig.truth(0);
  using GreyMap = std::map<std::string, const vpImage<unsigned char>*>;
  using RgbaMap = std::map<std::string, const vpImage<vpRGBa>*>;
  using PoseMap = std::map<std::string, vpHomogeneousMatrix>;
  using FileMap = std::map<std::string, std::string>;
  using UIntMap = std::map<std::string, unsigned int>;
  using DoubleMap = std::map<std::string, double>;
  const GreyMap unknown_grey{{u, &I}};
  const RgbaMap unknown_rgba{{u, &C}};
  const GreyMap grey_and_unknown{{kCamera1, &I}, {u, &I}};
  const RgbaMap rgba_and_unknown{{kCamera1, &C}, {u, &C}};
  const detail::StdoutSilencer quiet;

  check_refused("setTrackerType", u, [&] { t.setTrackerType(std::map<std::string, int>{{u, kEdge}}); });
  check_refused("loadConfigFile", u, [&] { t.loadConfigFile(FileMap{{u, kColorXml}}, false); });
  check_refused("loadModel", u, [&] { t.loadModel(FileMap{{u, kTeaboxCao}}); });
  check_refused("loadModel", u, [&] { t.loadModel(FileMap{{kCamera1, kTeaboxCao}}, false, PoseMap{{u, a}}); });
  {
    vpMbIcgTracker victim(kRgbdTrackerTypes);
    rig.setup(victim);
    check_refused("reInitModel", u, [&] { victim.reInitModel(unknown_grey, FileMap{{u, kTeaboxCao}}, PoseMap{{u, a}}); });
    check_refused("reInitModel", u, [&] { victim.reInitModel(unknown_rgba, FileMap{{u, kTeaboxCao}}, PoseMap{{u, a}}); });
  }
  check_refused("getFaces", u, [&] { t.getFaces(u); });
  check_refused("getPolygon", u, [&] { t.getPolygon(u, 0); });
  check_refused("setCameraParameters", u,
                [&] { t.setCameraParameters(std::map<std::string, vpCameraParameters>{{u, rig.cam1}}); });
  check_refused("setCameraTransformationMatrix", u, [&] { t.setCameraTransformationMatrix(u, a); });
  check_refused("setCameraTransformationMatrix", u, [&] { t.setCameraTransformationMatrix(PoseMap{{u, a}}); });
  check_refused("setReferenceCameraName", u, [&] { t.setReferenceCameraName(u); });
  CHECK(t.getReferenceCameraName() == kCamera1);

  check_refused("initFromPose", u, [&] { t.initFromPose(unknown_grey, PoseMap{{u, a}}); });
  check_refused("initFromPose", u, [&] { t.initFromPose(grey_and_unknown, PoseMap{{kCamera1, a}}); });
  check_refused("initFromPose", u, [&] { t.initFromPose(unknown_rgba, PoseMap{{u, a}}); });
  check_refused("initFromPose", u, [&] { t.initFromPose(rgba_and_unknown, PoseMap{{kCamera1, a}}); });
  check_refused("initFromPose", u, [&] { t.initFromPose(unknown_grey, FileMap{{u, pose_file}}); });
  check_refused("initFromPose", u, [&] { t.initFromPose(unknown_rgba, FileMap{{u, pose_file}}); });
  check_refused("initClick", u, [&] { t.initClick(unknown_grey, FileMap{{u, "teabox"}}); });
  check_refused("initClick", u, [&] { t.initClick(unknown_rgba, FileMap{{u, "teabox"}}); });
  check_refused("initFromPoints", u, [&] { t.initFromPoints(unknown_grey, FileMap{{u, "teabox.init"}}); });
  check_refused("initFromPoints", u, [&] { t.initFromPoints(unknown_rgba, FileMap{{u, "teabox.init"}}); });
  t.initFromPose(I, a);
  check_refused("setPose", u, [&] { t.setPose(unknown_grey, PoseMap{{u, a}}); });
  check_refused("setPose", u, [&] { t.setPose(grey_and_unknown, PoseMap{{kCamera1, a}}); });
  check_refused("setPose", u, [&] { t.setPose(unknown_rgba, PoseMap{{u, a}}); });
  check_refused("setPose", u, [&] { t.setPose(rgba_and_unknown, PoseMap{{kCamera1, a}}); });

  GreyMap greys = grey_and_unknown;
  RgbaMap colors = rgba_and_unknown;
  check_refused("track", u, [&] { t.track(greys); });
  check_refused("track", u, [&] { t.track(colors); });
  std::map<std::string, const std::vector<vpColVector>*> clouds{{u, &rig.inputs[0].point_cloud}};
  UIntMap widths{{u, rig.inputs[0].depth_width}}, heights{{u, rig.inputs[0].depth_height}};
  GreyMap grey_only{{kCamera1, &I}};
  RgbaMap rgba_only{{kCamera1, &C}};
  check_refused("track", u, [&] { t.track(grey_only, clouds, widths, heights); });
  check_refused("track", u, [&] { t.track(rgba_only, clouds, widths, heights); });
  std::map<std::string, std::shared_ptr<const pcl::PointCloud<pcl::PointXYZ>>> pcl_clouds{{u, nullptr}};
  check_refused("track", u, [&] { t.track(grey_only, pcl_clouds); });
  check_refused("track", u, [&] { t.track(rgba_only, pcl_clouds); });

  check_refused("display", u, [&] {
    t.display(unknown_grey, PoseMap{{u, a}}, std::map<std::string, vpCameraParameters>{{u, rig.cam1}}, vpColor::red);
  });
  check_refused("display", u, [&] {
    t.display(unknown_rgba, PoseMap{{u, a}}, std::map<std::string, vpCameraParameters>{{u, rig.cam1}}, vpColor::red);
  });
  std::map<std::string, std::vector<std::vector<double>>> models;
  check_refused("getModelForDisplay", u, [&] {
    t.getModelForDisplay(models, UIntMap{{u, 640}}, UIntMap{{u, 480}}, PoseMap{{u, a}},
                         std::map<std::string, vpCameraParameters>{{u, rig.cam1}});
  });

  const StandardStreamCapture reports(std::cerr);
  check_refused("setAngleAppear", u, [&] { t.setAngleAppear(DoubleMap{{u, 1.0}}); });
  check_refused("setAngleDisappear", u, [&] { t.setAngleDisappear(DoubleMap{{u, 1.0}}); });
  check_refused("setClipping", u, [&] { t.setClipping(UIntMap{{u, 0u}}); });
  check_refused("setNearClippingDistance", u, [&] { t.setNearClippingDistance(DoubleMap{{u, 0.1}}); });
  check_refused("setFarClippingDistance", u, [&] { t.setFarClippingDistance(DoubleMap{{u, 10.0}}); });
  check_refused("setKltOpencv", u, [&] { t.setKltOpencv(std::map<std::string, vpKltOpencv>{{u, vpKltOpencv()}}); });
  check_refused("setKltMaskBorder", u, [&] { t.setKltMaskBorder(UIntMap{{u, 5u}}); });
  check_refused("setMovingEdge", u, [&] { t.setMovingEdge(std::map<std::string, vpMe>{{u, vpMe()}}); });
  std::list<vpMbtDistanceCircle*> circles;
  std::list<vpMbtDistanceCylinder*> cylinders;
  std::list<vpMbtDistanceLine*> lines;
  check_refused("getLcircle", u, [&] { t.getLcircle(u, circles); });
  check_refused("getLcylinder", u, [&] { t.getLcylinder(u, cylinders); });
  check_refused("getLline", u, [&] { t.getLline(u, lines); });
}

TEST_CASE("the pose-file forms of initFromPose refuse an unknown camera in the image map") {
  // The pose forms check every camera of the image map; the pose-file forms only the camera
  // whose file they read.
  Rig rig(1);
  vpMbIcgTracker t(kRgbdTrackerTypes);
  rig.setup(t);
  const test::TempDir dir("icgp-test-vpmbicgtracker-api");
  const std::string pose_file = dir.file("a.pos");
  write_pos(pose_file, rig.truth(0));
  const std::map<std::string, const vpImage<unsigned char>*> images{{kCamera1, &rig.grey(0)},
                                                                    {"Camera3", &rig.grey(0)}};
  check_refused("initFromPose", "Camera3",
                [&] { t.initFromPose(images, std::map<std::string, std::string>{{kCamera1, pose_file}}); });
}

TEST_CASE("every two-camera overload refuses a tracker of one camera with a vpException naming the call") {
  Rig rig(1);
  vpMbIcgTracker t;  // one camera, "Camera"
  test::configure_for_tests(t);
  {
    const detail::StdoutSilencer quiet_parser;
    t.loadModel(kTeaboxCao);
  }
  t.setCameraParameters(rig.cam1);
  t.initFromPose(rig.grey(0), rig.truth(0));
  const vpImage<unsigned char>& I = rig.grey(0);
  const vpImage<vpRGBa>& C = rig.colors[0];
  const vpHomogeneousMatrix a = rig.truth(0);
  const std::string one = "has 1";  // the message says how many cameras the tracker has
  vpCameraParameters cam;
  vpHomogeneousMatrix M1, M2;
  unsigned int f1 = 0, f2 = 0;
  vpKltOpencv k1, k2;
  vpMe me1, me2;

  check_refused("loadConfigFile", one, [&] { t.loadConfigFile(kColorXml, kDepthXml, false); });
  check_refused("loadModel", one, [&] { t.loadModel(kTeaboxCao, kTeaboxCao); });
  check_refused("reInitModel", one, [&] { t.reInitModel(I, I, kTeaboxCao, kTeaboxCao, a, a); });
  check_refused("reInitModel", one, [&] { t.reInitModel(C, C, kTeaboxCao, kTeaboxCao, a, a); });
  check_refused("setCameraParameters", one, [&] { t.setCameraParameters(rig.cam1, rig.cam2); });
  check_refused("getCameraParameters", one, [&] { t.getCameraParameters(cam, cam); });
  check_refused("initClick", one, [&] { t.initClick(I, I, "teabox", "teabox"); });
  check_refused("initClick", one, [&] { t.initClick(C, C, "teabox", "teabox"); });
  check_refused("initFromPoints", one, [&] { t.initFromPoints(I, I, "teabox.init", "teabox.init"); });
  check_refused("initFromPoints", one, [&] { t.initFromPoints(C, C, "teabox.init", "teabox.init"); });
  check_refused("initFromPose", one, [&] { t.initFromPose(I, I, "a.pos", "b.pos"); });
  check_refused("initFromPose", one, [&] { t.initFromPose(C, C, "a.pos", "b.pos"); });
  check_refused("initFromPose", one, [&] { t.initFromPose(I, I, a, a); });
  check_refused("initFromPose", one, [&] { t.initFromPose(C, C, a, a); });
  check_refused("track", one, [&] { t.track(I, I); });
  check_refused("track", one, [&] { t.track(C, C); });
  check_refused("getPose", one, [&] { t.getPose(M1, M2); });
  check_refused("display", one, [&] { t.display(I, I, a, a, rig.cam1, rig.cam1, vpColor::red); });
  check_refused("display", one, [&] { t.display(C, C, a, a, rig.cam1, rig.cam1, vpColor::red); });
  const StandardStreamCapture reports(std::cerr);
  check_refused("setAngleAppear", one, [&] { t.setAngleAppear(1.0, 1.0); });
  check_refused("setAngleDisappear", one, [&] { t.setAngleDisappear(1.0, 1.0); });
  check_refused("setClipping", one, [&] { t.setClipping(0u, 0u); });
  check_refused("getClipping", one, [&] { t.getClipping(f1, f2); });
  check_refused("setNearClippingDistance", one, [&] { t.setNearClippingDistance(0.1, 0.1); });
  check_refused("setFarClippingDistance", one, [&] { t.setFarClippingDistance(10.0, 10.0); });
  check_refused("setKltOpencv", one, [&] { t.setKltOpencv(k1, k2); });
  check_refused("getKltOpencv", one, [&] { t.getKltOpencv(k1, k2); });
  check_refused("setKltMaskBorder", one, [&] { t.setKltMaskBorder(5u, 5u); });
  check_refused("setMovingEdge", one, [&] { t.setMovingEdge(me1, me2); });
  check_refused("getMovingEdge", one, [&] { t.getMovingEdge(me1, me2); });
}

TEST_CASE("setPose's two-camera forms name setPose when refusing a tracker of one camera") {
  // vpMbIcgTracker::setPose(I1, I2, c1Mo, c2Mo) forwards to initFromPose, whose message names
  // initFromPose.
  Rig rig(1);
  vpMbIcgTracker t;
  test::configure_for_tests(t);
  {
    const detail::StdoutSilencer quiet_parser;
    t.loadModel(kTeaboxCao);
  }
  t.setCameraParameters(rig.cam1);
  t.initFromPose(rig.grey(0), rig.truth(0));
  const vpHomogeneousMatrix a = rig.truth(0);
  check_refused("setPose", "has 1", [&] { t.setPose(rig.grey(0), rig.grey(0), a, a); });
  check_refused("setPose", "has 1", [&] { t.setPose(rig.colors[0], rig.colors[0], a, a); });
}

TEST_CASE("grey and colour images may alternate from frame to frame, as with vpMbGenericTracker") {
  // vpMbGenericTracker converts colour images to grey levels, so a program may pass either on
  // any frame; icgp's region cue refuses the switch without a new initialisation.
  Rig rig(2);
  vpMbIcgTracker t(kRgbdTrackerTypes);
  rig.setup(t);
  t.initFromPose(rig.grey(0), rig.truth(0));
  rig.track_rgbd(t, 0);
  CHECK_NOTHROW(rig.track_rgbd(t, 1, rig.colors[1]));
}

TEST_CASE("reInitModel's map forms refuse an unknown camera naming reInitModel, and keep the model") {
  // reInitModel forgets the model, then loadModel refuses the camera: the message names
  // loadModel and the tracker is left without a model.
  Rig rig(1);
  vpMbIcgTracker t(kRgbdTrackerTypes);
  rig.setup(t);
  const std::map<std::string, const vpImage<unsigned char>*> images{{"Camera3", &rig.grey(0)}};
  check_refused("reInitModel", "Camera3", [&] {
    t.reInitModel(images, std::map<std::string, std::string>{{"Camera3", kTeaboxCao}},
                  std::map<std::string, vpHomogeneousMatrix>{{"Camera3", rig.truth(0)}});
  });
  CHECK(t.getNbPolygon() == 6);
}
