// SPDX-License-Identifier: GPL-2.0-or-later
// DepthStandIn: a cue that works only in frames without depth, restarting after it sat out.
#include <catch2/catch.hpp>

#include "icgp/modality/depth_stand_in.h"

using namespace icgp;

namespace {

/// A cue that records what it is asked and answers with values it can be recognised by:
/// render requests of a size per stage (start 11, correspondences 22, finish 33).
class RecordingCue final : public Modality {
 public:
  struct Calls {
    int starts = 0, correspondences = 0, finishes = 0;
  };

  RecordingCue(Body& body, Calls& calls) : Modality(body), calls_(calls) {}

  std::string name() const override { return "flow"; }
  const std::string& camera() const override { return camera_; }
  std::vector<RenderRequest> render_requests(const Frame&, Stage stage) const override {
    RenderRequest r;
    r.size = stage.kind == Stage::kStart ? 11 : stage.kind == Stage::kCorrespondences ? 22 : 33;
    return {r};
  }
  void start(const Frame&, const Renders&) override { ++calls_.starts; }
  void correspondences(const Frame&, const Renders&, int) override { ++calls_.correspondences; }
  CueTerms gradient_hessian(int, int) override {
    CueTerms terms;
    terms.gradient.setConstant(1.0);
    terms.hessian = -Mat66::Identity();
    terms.n_correspondences = 7;
    return terms;
  }
  double log_likelihood(int) const override { return -2.0; }
  void finish(const Frame&, const Renders&) override { ++calls_.finishes; }
  ModalityQuality quality() const override {
    ModalityQuality q;
    q.score = 0.9;
    q.n_valid = 7;
    return q;
  }
  void append_residuals(std::vector<double>& residuals, std::vector<double>& weights) const override {
    residuals.push_back(0.5);
    weights.push_back(1.0);
  }
  void append_image_features(std::vector<ImageFeature>& features) const override {
    features.push_back({Eigen::Vector2d(1.0, 2.0), 1.0});
  }

 private:
  Calls& calls_;
  std::string camera_ = "Camera1";
};

/// A frame whose depth camera "Camera2" delivers depth, or delivers none (ViSP's cloud of
/// width and height 0).
Frame frame_with_depth(bool delivered) {
  Frame frame;
  DepthImage depth;
  depth.camera = "Camera2";
  if (delivered) depth.depth = cv::Mat(4, 4, CV_32FC1, cv::Scalar(0.5f));
  frame.depths.push_back(depth);
  return frame;
}

std::vector<int> sizes(const std::vector<RenderRequest>& requests) {
  std::vector<int> out;
  for (const RenderRequest& r : requests) out.push_back(r.size);
  return out;
}

/// One frame as Tracker::track runs it: two correspondence iterations of one update each.
void track(DepthStandIn& cue, const Frame& frame) {
  const Renders none;
  for (int c = 0; c < 2; ++c) {
    cue.correspondences(frame, none, c);
    cue.gradient_hessian(c, 0);
  }
  cue.finish(frame, none);
}

}  // namespace

TEST_CASE("DepthStandIn: sits out frames with depth, works in frames without, and starts at the end of the first") {
  Body body{"box", Mesh(), Pose()};
  RecordingCue::Calls calls;
  DepthStandIn cue(std::make_unique<RecordingCue>(body, calls), {"Camera2"});
  CHECK(cue.name() == "flow");
  CHECK(cue.camera() == "Camera1");
  const Frame with = frame_with_depth(true), without = frame_with_depth(false);
  const Renders none;

  // Started on a frame with depth: nothing is asked of the cue, and it says nothing.
  CHECK(cue.render_requests(with, {Stage::kStart}).empty());
  cue.start(with, none);
  CHECK(cue.render_requests(with, {Stage::kCorrespondences, 0}).empty());
  track(cue, with);
  CHECK(cue.render_requests(with, {Stage::kFinish}).empty());
  CHECK(calls.starts == 0);
  CHECK(calls.correspondences == 0);
  CHECK(calls.finishes == 0);
  CHECK_FALSE(cue.working());
  CHECK(cue.gradient_hessian(0, 0).n_correspondences == 0);
  CHECK(cue.gradient_hessian(0, 0).hessian.isZero());
  CHECK(cue.log_likelihood(0) == 0.0);
  CHECK(cue.quality().abstained);
  std::vector<double> residuals, weights;
  std::vector<ImageFeature> features;
  cue.append_residuals(residuals, weights);
  cue.append_image_features(features);
  CHECK(residuals.empty());
  CHECK(features.empty());

  // The first frame without depth: the cue has nothing from the frame before, so it adds
  // nothing this frame and starts at its end, asking for what it renders to start.
  CHECK(cue.render_requests(without, {Stage::kCorrespondences, 0}).empty());
  const Renders renders;
  cue.correspondences(without, renders, 0);
  CHECK_FALSE(cue.working());
  CHECK(cue.gradient_hessian(0, 0).n_correspondences == 0);
  CHECK(sizes(cue.render_requests(without, {Stage::kFinish})) == std::vector<int>{11});
  cue.finish(without, renders);
  CHECK(calls.starts == 1);
  CHECK(calls.correspondences == 0);
  CHECK(calls.finishes == 0);
  CHECK(cue.quality().abstained);

  // Still without depth: it works as itself.
  CHECK(sizes(cue.render_requests(without, {Stage::kCorrespondences, 0})) == std::vector<int>{22});
  track(cue, without);
  CHECK(calls.starts == 1);
  CHECK(calls.correspondences == 2);
  CHECK(calls.finishes == 1);
  CHECK(cue.working());
  CHECK(cue.gradient_hessian(1, 0).n_correspondences == 7);
  CHECK(cue.log_likelihood(1) == -2.0);
  CHECK(cue.quality().score == 0.9);
  CHECK_FALSE(cue.quality().abstained);
  cue.append_image_features(features);
  CHECK(features.size() == 1);
  CHECK(sizes(cue.render_requests(without, {Stage::kFinish})) == std::vector<int>{33});
  track(cue, without);
  CHECK(calls.starts == 1);
  CHECK(calls.correspondences == 4);

  // Depth again: it sits out, and the next frame without depth starts it again at its end.
  track(cue, with);
  CHECK_FALSE(cue.working());
  CHECK(calls.correspondences == 4);
  track(cue, without);
  CHECK(calls.starts == 2);
  CHECK(calls.correspondences == 4);
  track(cue, without);
  CHECK(calls.correspondences == 6);

  // A tracker's start on a frame without depth starts it at once: it works in the next.
  track(cue, with);
  cue.start(without, none);
  CHECK(calls.starts == 3);
  track(cue, without);
  CHECK(calls.starts == 3);
  CHECK(calls.correspondences == 8);
}

TEST_CASE("DepthStandIn: a frame without the depth camera at all counts as without depth; no depth camera is refused") {
  Body body{"box", Mesh(), Pose()};
  RecordingCue::Calls calls;
  DepthStandIn cue(std::make_unique<RecordingCue>(body, calls), {"Camera2"});
  cue.start(Frame(), Renders());
  CHECK(calls.starts == 1);
  track(cue, Frame());
  CHECK(cue.working());
  CHECK(calls.correspondences == 2);

  CHECK_THROWS_WITH(DepthStandIn(std::make_unique<RecordingCue>(body, calls), {}),
                    Catch::Contains("the flow cue of 'box' stands in for depth, but no depth camera is given"));
  CHECK_THROWS_WITH(DepthStandIn(nullptr, {"Camera2"}), Catch::Contains("no cue given"));
}
