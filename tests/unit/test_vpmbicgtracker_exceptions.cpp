// SPDX-License-Identifier: GPL-2.0-or-later
// vpMbIcgTracker's exception contract: every error path a ViSP program can reach ends in a
// vpException (vpTrackingException for a frame that cannot be tracked) whose message names
// the method and what is at fault, never in another exception type, a crash or a hang.
#include <catch2/catch.hpp>

#include "vpmbicgtracker_test_setup.h"

using namespace icgp;

namespace {

const std::string kTeaboxCao = (test::kTeaboxBlender / "teabox.cao").string();

/// vpMbTracker's projection-error model (protected: ViSP offers no accessor).
class ProjectionErrorModel : public vpMbIcgTracker {
 public:
  std::size_t lines() const { return m_projectionErrorLines.size(); }
  std::size_t faces() { return m_projectionErrorFaces.size(); }
};

}  // namespace

TEST_CASE("vpMbIcgTracker: resetTracker and reInitModel forget ViSP's projection-error model") {
  ProjectionErrorModel tracker;
  test::configure_for_tests(tracker);
  tracker.loadModel(kTeaboxCao);
  // The teabox: 6 faces of 4 points, 12 edges.
  REQUIRE(tracker.lines() == 12);
  REQUIRE(tracker.faces() == 6);

  tracker.resetTracker();
  CHECK(tracker.lines() == 0);
  CHECK(tracker.faces() == 0);
  test::configure_for_tests(tracker);
  tracker.loadModel(kTeaboxCao);
  CHECK(tracker.lines() == 12);
  CHECK(tracker.faces() == 6);

  const vpImage<unsigned char> I(480, 640, 0);
  tracker.setCameraParameters(vpCameraParameters(600, 600, 320, 240));
  tracker.reInitModel(I, kTeaboxCao, vpHomogeneousMatrix(0, 0, 0.5, 0, 0, 0));
  CHECK(tracker.lines() == 12);
  CHECK(tracker.faces() == 6);
}
