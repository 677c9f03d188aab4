// SPDX-License-Identifier: GPL-2.0-or-later
// icgp.Tracker: the ICG+ tracker on NumPy images, configured from YAML or keyword
// arguments, with several bodies, per-cue diagnostics and the pose covariance.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>

#include "bindings.h"
#include "icgp/io/yaml_reader.h"
#include "icgp/eval/sequence.h"
#include "icgp/io/joint_yaml.h"
#include "icgp/optimizer/covariance.h"
#include "icgp/detection/recovery.h"
#include "icgp/tracker/tracker_builder.h"
#include "icgp/visp/cao_mesh_loader.h"
#include "numpy_conversions.h"
#include "python_yaml.h"

namespace icgp::python {
namespace {

namespace py = pybind11;

/// "a: 1\nb: [2, 3]\n": YAML text of a node built from Python values.
std::string yaml_text(const YAML::Node& node) {
  YAML::Emitter out;
  out << node;
  return out.c_str();
}

}  // namespace

TrackerConfig tracker_config(const py::object& config, const py::dict& settings) {
  TrackerConfig result;
  if (py::isinstance<py::dict>(config)) {
    result = read_tracker_config(yaml_text(yaml_node(config)), "config", std::filesystem::current_path().string());
  } else if (!config.is_none()) {
    result = load_tracker_config(py::str(config).cast<std::string>());
  }
  if (!settings.empty())
    result = read_tracker_config(yaml_text(yaml_node(settings)), "keyword arguments",
                                 std::filesystem::current_path().string(), result);
  return result;
}

namespace {

/// A joint given as a dict of the keys a configuration's body entry takes for it (parent,
/// joint, axis, origin, limits_deg, ...), read by the configuration's own reader.
Joint joint_from(const py::dict& keys, const std::string& body) {
  const std::string source = "add_body('" + body + "') joint";
  const yaml::Value value{yaml_node(keys), yaml::Location{source, "", {}}};
  std::optional<Joint> joint = read_joint(yaml::Map(value, joint_keys()));
  if (!joint) value.at.fail("expected a parent: the body this one hangs from");
  return *joint;
}

/// One frame's outcome for one body, as Python sees it: the C++ result and the name and
/// camera of each of its cues (dicts are made only when Python asks for them).
/// (cue, camera) of each of a body's modalities, in the order they were added.
using CueNames = std::vector<std::pair<std::string, std::string>>;

struct BodyOutcome {
  BodyResult result;
  std::shared_ptr<const CueNames> cue_names;  ///< as result.modalities; the tracker's, made once

  py::list cues() const {
    py::list cues;
    for (std::size_t i = 0; i < result.modalities.size(); ++i) {
      const ModalityQuality& q = result.modalities[i];
      py::dict d;
      d["cue"] = (*cue_names)[i].first;
      d["camera"] = (*cue_names)[i].second;
      d["score"] = q.score;
      d["sigma"] = q.sigma;
      d["valid_fraction"] = q.valid_fraction;
      d["n_valid"] = q.n_valid;
      d["abstained"] = q.abstained;
      cues.append(d);
    }
    return cues;
  }
  /// "'teabox' quality 0.81 tracked", for the results' __repr__.
  std::string describe() const {
    char quality[32];
    std::snprintf(quality, sizeof quality, "%.3f", result.quality);
    return "'" + result.body + "' quality " + quality + (result.tracked ? " tracked" : " LOST");
  }
};

/// What Tracker.track returns: every body's outcome, which is the main body's, and the time.
struct TrackOutcome {
  std::vector<BodyOutcome> bodies;
  std::size_t main = 0;
  double ms = 0.0;

  const BodyOutcome& main_body() const { return bodies.at(main); }
};

class PythonTracker {
 public:
  PythonTracker(const std::string& model, const py::object& config, const std::string& body, double scale,
                const py::kwargs& settings)
      : model_(model), config_(tracker_config(config, settings)), body_(body), mesh_(load_any_mesh(model, scale)) {}

  void add_body(const std::string& name, const std::filesystem::path& model, const std::optional<py::dict>& joint,
                double scale, bool occluder) {
    if (tracker_)
      throw std::invalid_argument("add_body('" + name + "'): bodies are added before the first track(), which builds the tracker");
    BodyConfig body;
    body.name = name;
    body.mesh = std::filesystem::absolute(model).lexically_normal().string();
    body.scale = scale;
    body.occluder = occluder;
    if (joint) body.joint = joint_from(*joint, name);
    config_.bodies.push_back(body);
    try {
      in_tree_order(config_.bodies, body_);  // names, parents and cycles, checked now
      validate(config_, "add_body('" + name + "')");
    } catch (...) {
      config_.bodies.pop_back();
      throw;
    }
  }

  std::vector<std::string> body_names() const {
    std::vector<std::string> names{body_};
    for (const BodyConfig& b : config_.bodies) names.push_back(b.name);
    return names;
  }

  void set_pose(const py::handle& matrix, const std::optional<std::string>& body) {
    const std::string name = body.value_or(body_);
    const BodyConfig* config = body_config(name);
    if (config && config->joint)
      throw std::invalid_argument("set_pose('" + name + "'): a link's pose follows from its parent's and its joint values: "
                                  "set those (set_joint_values)");
    const Pose reference_T_body = icgp::python::pose(matrix, "pose");
    if (tracker_)
      tracker_->body(name).reference_T_body = reference_T_body;
    else
      pending_poses_[name] = reference_T_body;
    if (name == body_) has_initial_pose_ = true;
    // An occluder's pose is set every frame and restarts nothing; a tracked body's restarts
    // the cues there.
    if (!(config && config->occluder)) needs_start_ = true;
  }

  py::array_t<double> pose(const std::optional<std::string>& body) {
    const std::string name = body.value_or(body_);
    require_body(name);
    if (tracker_) return matrix(tracker_->body(name).reference_T_body);
    const auto it = pending_poses_.find(name);
    return matrix(it == pending_poses_.end() ? Pose() : it->second);
  }

  void set_joint_values(const std::string& body, std::vector<double> values) {
    const BodyConfig* config = body_config(body);
    if (!config || !config->joint)
      throw std::invalid_argument("set_joint_values('" + body + "'): not a link (a body added with a joint)");
    built().set_joint_values(body, std::move(values));
    needs_start_ = true;
  }

  std::vector<double> joint_values(const std::string& body) {
    require_body(body);
    return built().joint_values(body);
  }

  TrackOutcome track(const py::array& color, const std::optional<py::array>& depth, const py::handle& K_color,
                     const py::handle& K_depth, const py::handle& depth_T_color, const std::string& order,
                     double depth_scale) {
    return track_frame(frame_of(color, depth, K_color, K_depth, depth_T_color, order, depth_scale));
  }

  /// Finds the main body in these images without a given pose; when found, the tracker
  /// starts there (the next track() follows on).
  py::dict detect(const py::array& color, const std::optional<py::array>& depth, const py::handle& K_color,
                  const py::handle& K_depth, const py::handle& depth_T_color, const std::string& order,
                  double depth_scale) {
    const Frame frame = frame_of(color, depth, K_color, K_depth, depth_T_color, order, depth_scale);
    built();  // with the poses set so far (other bodies, occluders)
    Detection detection;
    {
      py::gil_scoped_release release;
      detection = recovery_->initialise(frame);
    }
    py::dict out;
    out["found"] = detection.found;
    out["pose"] = detection.found ? py::object(matrix(detection.reference_T_body)) : py::object(py::none());
    out["quality"] = detection.quality;
    py::list equivalents;
    for (const Pose& e : detection.equivalents) equivalents.append(matrix(e));
    out["equivalents"] = equivalents;
    out["why_not"] = detection.why_not;
    if (detection.found) {
      has_initial_pose_ = true;
      needs_start_ = false;  // started on this frame
      started_once_ = false;
    }
    return out;
  }

 private:
  Frame frame_of(const py::array& color, const std::optional<py::array>& depth, const py::handle& K_color,
                 const py::handle& K_depth, const py::handle& depth_T_color, const std::string& order,
                 double depth_scale) {
    Frame frame;
    ColorImage c;
    c.camera = config_.region.color_camera;
    c.image = color_image(color, "color", color_order(order));
    c.intrinsics = intrinsics(K_color, c.image.cols, c.image.rows, "K_color");
    frame.colors.push_back(std::move(c));
    if (depth) {
      DepthImage d;
      d.camera = config_.depth.depth_camera;
      d.depth = depth_image(*depth, "depth", depth_scale);
      d.intrinsics = intrinsics(K_depth.is_none() ? K_color : K_depth, d.depth.cols, d.depth.rows,
                                K_depth.is_none() ? "K_color (as the depth camera's)" : "K_depth");
      d.camera_T_reference = depth_T_color.is_none() ? Pose() : icgp::python::pose(depth_T_color, "depth_T_color");
      frame.depths.push_back(std::move(d));
    } else if (!K_depth.is_none() || !depth_T_color.is_none()) {
      throw py::value_error("K_depth and depth_T_color describe a depth image: give depth too");
    }
    frame.index = frames_;
    return frame;
  }

 public:
  TrackOutcome track_frame(const Frame& frame) {
    if (!has_initial_pose_)
      throw std::invalid_argument("track: no initial pose: call set_pose(pose) first (the object in the colour camera, "
                                  "ViSP's cMo)");
    Tracker& tracker = built();
    ++frames_;
    std::vector<BodyResult> results;
    double ms = 0.0;
    {
      py::gil_scoped_release release;
      if (needs_start_) {
        tracker.start(frame);
        recovery_->reset();
      }
      const auto begin = std::chrono::steady_clock::now();
      results = tracker.track(frame);
      recovery_->after_track(frame, results);
      ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - begin).count();
    }
    needs_start_ = false;
    started_once_ = true;
    TrackOutcome outcome;
    outcome.ms = ms;
    for (BodyResult& r : results) {
      if (r.body == body_) outcome.main = outcome.bodies.size();
      std::shared_ptr<const CueNames> names = cue_names_.at(r.body);
      outcome.bodies.push_back({std::move(r), std::move(names)});
    }
    return outcome;
  }

  py::array_t<double> covariance(const std::optional<std::string>& body) {
    const std::string name = body.value_or(body_);
    require_body(name);
    if (!started_once_) throw std::invalid_argument("covariance: no frame has been tracked yet");
    const Mat66 covariance = camera_twist_covariance(tracker_->last_hessian(name), tracker_->body(name).reference_T_body);
    py::array_t<double> out({6, 6});
    for (int r = 0; r < 6; ++r)
      for (int c = 0; c < 6; ++c) out.mutable_at(r, c) = covariance(r, c);
    return out;
  }

  std::string config_yaml() const { return to_yaml(config_); }
  const std::string& model() const { return model_; }
  const std::string& body() const { return body_; }

 private:
  /// The tracker, built (viewpoint models loaded or generated) on first use, with the poses
  /// set so far.
  Tracker& built() {
    if (tracker_) return *tracker_;
    std::unique_ptr<Tracker> tracker;
    {
      py::gil_scoped_release release;
      tracker = build_tracker(config_, mesh_, body_, [](const std::string& path, double scale) { return load_any_mesh(path, scale); });
    }
    for (const auto& [name, reference_T_body] : pending_poses_) tracker->body(name).reference_T_body = reference_T_body;
    pending_poses_.clear();
    // The cues' names, for every frame's results: the modalities are fixed from here on.
    for (const Body* body : tracker->bodies()) {
      auto names = std::make_shared<CueNames>();
      for (const Modality* modality : tracker->modalities(body->name)) names->emplace_back(modality->name(), modality->camera());
      cue_names_.emplace(body->name, std::move(names));
    }
    tracker_ = std::move(tracker);
    recovery_ = std::make_unique<Recovery>(*tracker_, config_, body_, configured_cameras(config_));
    needs_start_ = true;
    return *tracker_;
  }

  /// The added body named `name`; null for the main body.
  const BodyConfig* body_config(const std::string& name) const {
    for (const BodyConfig& b : config_.bodies)
      if (b.name == name) return &b;
    if (name == body_) return nullptr;
    throw std::invalid_argument("no body named '" + name + "' (the bodies are " + yaml::join(body_names()) + ")");
  }
  /// Throws naming the bodies when there is none named `name`.
  void require_body(const std::string& name) const { body_config(name); }

  std::string model_;
  TrackerConfig config_;
  std::string body_;
  Mesh mesh_;
  std::unique_ptr<Tracker> tracker_;
  std::unique_ptr<Recovery> recovery_;  ///< detection and recovery, built with tracker_
  std::map<std::string, Pose> pending_poses_;  ///< set before the tracker was built
  std::map<std::string, std::shared_ptr<const CueNames>> cue_names_;  ///< per tracked body
  bool has_initial_pose_ = false;  ///< set_pose was called for the main body
  bool needs_start_ = true;
  bool started_once_ = false;
  int frames_ = 0;
};

constexpr const char* kTrackerDoc = R"doc(The ICG+ tracker: region, depth and texture cues fused in one Newton step.

Tracker(model, config=None, *, body="object", scale=1.0, **settings)

model     a mesh (.obj, .ply, ... anything assimp reads) or a ViSP .cao file, in metres
          times `scale`.
config    None (icgp's defaults), a YAML configuration file, or a dict of its keys
          (docs/configuration.md; `icgp config --defaults` prints them all).
body      the name of the tracked object (its results and poses are asked for by it).
settings  configuration keys read over `config`, checked as a file's are, e.g.
          modalities=["region", "depth"], preset="icg_reference",
          depth={"noise": {"estimate": False}}.

The viewpoint models are loaded from the cache (ICGP_CACHE_DIR, else ~/.cache/icgp) or
generated on the first track(). Poses are 4x4 NumPy arrays: the object in the colour
camera's frame (ViSP's cMo), metres.

    tracker = icgp.Tracker("box.obj")
    tracker.set_pose(cMo)                  # where the object starts, or:
    tracker.detect(color, depth, K, K_depth, depth_T_color)   # found in the images
    for color, depth in frames:
        r = tracker.track(color, depth, K, K_depth, depth_T_color)
        print(r.pose, r.quality, r.tracked, r.cues)
)doc";

}  // namespace

void register_tracker(py::module_& m) {
  py::class_<BodyOutcome>(m, "BodyResult", "One body's outcome of a frame (see TrackResult).")
      .def_property_readonly("body", [](const BodyOutcome& b) { return b.result.body; }, "The body's name.")
      .def_property_readonly("pose", [](const BodyOutcome& b) { return matrix(b.result.reference_T_body); },
                             "4x4 pose of the body in the colour camera's frame (cMo), metres.")
      .def_property_readonly("quality", [](const BodyOutcome& b) { return b.result.quality; },
                             "Mean score of the cues that measured something, in [0, 1].")
      .def_property_readonly("tracked", [](const BodyOutcome& b) { return b.result.tracked; },
                             "False when the quality fell below the configured threshold (lost).")
      .def_property_readonly("cues", &BodyOutcome::cues,
                             "Per-cue diagnostics, one dict per cue: cue, camera, score, sigma (px; depth: m at 1 m), "
                             "valid_fraction, n_valid, abstained (nothing to measure).")
      .def_property_readonly("joint_values", [](const BodyOutcome& b) { return b.result.joint_values; },
                             "A link's joint values (radians, metres) in its joint's order; empty for a free body.")
      .def("__repr__", [](const BodyOutcome& b) { return "<icgp.BodyResult " + b.describe() + ">"; });

  py::class_<TrackOutcome>(m, "TrackResult", "What Tracker.track returns for one frame: the main body's outcome.")
      .def_property_readonly("pose", [](const TrackOutcome& t) { return matrix(t.main_body().result.reference_T_body); },
                             "4x4 pose of the main body in the colour camera's frame (cMo), metres.")
      .def_property_readonly("quality", [](const TrackOutcome& t) { return t.main_body().result.quality; },
                             "The main body's quality: the median score of its cues that measured something.")
      .def_property_readonly("tracked", [](const TrackOutcome& t) { return t.main_body().result.tracked; },
                             "False when the main body's quality fell below the threshold (lost).")
      .def_property_readonly("cues", [](const TrackOutcome& t) { return t.main_body().cues(); },
                             "The main body's per-cue diagnostics (see BodyResult.cues).")
      .def_property_readonly("bodies",
                             [](const TrackOutcome& t) {
                               py::dict bodies;
                               for (const BodyOutcome& b : t.bodies) bodies[py::str(b.result.body)] = py::cast(b);
                               return bodies;
                             },
                             "Every tracked body's BodyResult, by name.")
      .def_readonly("ms", &TrackOutcome::ms, "Milliseconds the C++ tracker spent on the frame.")
      .def("__repr__", [](const TrackOutcome& t) { return "<icgp.TrackResult " + t.main_body().describe() + ">"; });

  py::class_<PythonTracker>(m, "Tracker", kTrackerDoc)
      .def(py::init([](const std::filesystem::path& model, const py::object& config, const std::string& body, double scale,
                       const py::kwargs& settings) {
             return std::make_unique<PythonTracker>(model.string(), config, body, scale, settings);
           }),
           py::arg("model"), py::arg("config") = py::none(), py::kw_only(), py::arg("body") = "object",
           py::arg("scale") = 1.0)
      .def("set_pose", &PythonTracker::set_pose, py::arg("pose"), py::arg("body") = py::none(),
           "Puts a body (default: the main one) or an occluder at `pose` (4x4, colour camera frame). The next\n"
           "track() starts the cues there, as ViSP's initFromPose: call it to initialise and to restart after a\n"
           "loss. A link's pose follows from its parent's and its joint values.")
      .def("pose", &PythonTracker::pose, py::arg("body") = py::none(),
           "The current 4x4 pose of a body (default: the main one).")
      .def("track", &PythonTracker::track, py::arg("color"), py::arg("depth") = py::none(), py::arg("K_color"),
           py::arg("K_depth") = py::none(), py::arg("depth_T_color") = py::none(), py::kw_only(),
           py::arg("color_order") = "bgr", py::arg("depth_scale") = 0.001,
           "Tracks one frame and returns a TrackResult.\n\n"
           "color          uint8 (H, W, 3) in `color_order` ('bgr' as OpenCV reads, or 'rgb') or (H, W) grey.\n"
           "depth          None (colour only), float32/float64 (H, W) metres, or uint16 times `depth_scale`\n"
           "               metres; 0, NaN, inf and negative values are no measurement.\n"
           "K_color        3x3 camera matrix of the colour image [[fu, 0, pu], [0, fv, pv], [0, 0, 1]].\n"
           "K_depth        3x3 of the depth image (default: K_color).\n"
           "depth_T_color  4x4 colour camera -> depth camera (ViSP's depth_M_color; default: identity).\n\n"
           "C-contiguous uint8 BGR and float32 arrays are read in place, without a copy.")
      .def("detect", &PythonTracker::detect, py::arg("color"), py::arg("depth") = py::none(), py::arg("K_color"),
           py::arg("K_depth") = py::none(), py::arg("depth_T_color") = py::none(), py::kw_only(),
           py::arg("color_order") = "bgr", py::arg("depth_scale") = 0.001,
           "Finds the object in these images without a given pose (docs/detection.md), the arguments as "
           "track()'s. Returns a dict: found (bool), pose (4x4 cMo, or None), quality, equivalents (poses a "
           "symmetric model cannot tell apart from it), why_not (the reason when not found). When found, the "
           "tracker starts there and the next track() follows on.")
      .def("track_frame", &PythonTracker::track_frame, py::arg("frame"),
           "Tracks a Frame read by icgp.Sequence (every camera it has) and returns a TrackResult.")
      .def("covariance", &PythonTracker::covariance, py::arg("body") = py::none(),
           "6x6 covariance of a body's pose after the last frame, over the camera-frame twist (v, w) as ViSP\n"
           "orders it (vpMbIcgTracker.getCovarianceMatrix): the inverse of the last update's data Hessian.")
      .def("add_body", &PythonTracker::add_body, py::arg("name"), py::arg("model"), py::arg("joint") = py::none(),
           py::arg("scale") = 1.0, py::arg("occluder") = false,
           "Adds a body tracked beside the main one, before the first track(): free (no joint), a link of a\n"
           "kinematic tree hanging from another body by `joint`, or an occluder (rendered, not tracked: set its\n"
           "pose before each frame). `joint` is a dict of the keys a configuration's body entry takes for its\n"
           "joint (docs/configuration.md), e.g. {'parent': 'object', 'joint': 'revolute', 'axis': [1, 0, 0],\n"
           "'origin': {'t': [0, 0.05, 0.04], 'r_deg': [0, 0, 0]}, 'limits_deg': [0, 110]}.")
      .def("add_occluder", [](PythonTracker& t, const std::string& name, const std::filesystem::path& model, double scale) {
             t.add_body(name, model, std::nullopt, scale, true);
           }, py::arg("name"), py::arg("model"), py::arg("scale") = 1.0,
           "Adds a body that hides the tracked ones but is not tracked: set its pose before each track().")
      .def("set_joint_values", &PythonTracker::set_joint_values, py::arg("body"), py::arg("values"),
           "Sets a link's joint values (radians, metres; clamped into its limits); the next track() starts there.")
      .def("joint_values", &PythonTracker::joint_values, py::arg("body"), "A link's current joint values.")
      .def_property_readonly("body_names", &PythonTracker::body_names,
                             "The main body, then the added bodies and occluders, in the order added.")
      .def_property_readonly("body", &PythonTracker::body, "The main body's name.")
      .def_property_readonly("model", &PythonTracker::model, "The main body's model file.")
      .def_property_readonly("config", &PythonTracker::config_yaml,
                             "The effective configuration as YAML (every key), as `icgp config` prints it.")
      .def("__repr__", [](const PythonTracker& t) { return "<icgp.Tracker '" + t.body() + "' model " + t.model() + ">"; });
}

}  // namespace icgp::python
