// SPDX-License-Identifier: GPL-2.0-or-later
// icgp.Sequence and icgp.Frame: the RGB-D sequences `icgp track` reads (ViSP's layouts and
// icgp's), frame by frame as NumPy arrays.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <filesystem>

#include "bindings.h"
#include "icgp/base/resource_limits.h"
#include "icgp/eval/make_sequence.h"
#include "icgp/eval/sequence.h"
#include "icgp/visp/cao_mesh_loader.h"
#include "icgp/visp/visp_camera_xml.h"
#include "numpy_conversions.h"

namespace icgp::python {
namespace {

namespace py = pybind11;

/// Each camera of a frame (ColorImage or DepthImage) as a dict of its name, image and
/// calibration.
template <typename Camera>
py::list camera_list(const std::vector<Camera>& cameras, cv::Mat Camera::*image) {
  py::list list;
  for (const Camera& c : cameras) {
    py::dict d;
    d["camera"] = c.camera;
    d["image"] = image_array(c.*image);
    d["K"] = camera_matrix(c.intrinsics);
    d["width"] = c.intrinsics.width;
    d["height"] = c.intrinsics.height;
    d["camera_T_color"] = matrix(c.camera_T_reference);
    list.append(d);
  }
  return list;
}

constexpr const char* kSequenceDoc = R"doc(An RGB-D sequence on disk, in any layout `icgp track` reads.

Sequence(path, *, color_intrinsics=None, depth_intrinsics=None, blender_principal_point=False,
         grey_without_depth=False, max_depth=10.0, frame_rate=30.0)

Layouts: icgp's own (sequence.yaml, as make_sequence writes it), ViSP's teabox-blender
(images/, depth/*.exr, camera_poses/) and ViSP's RealSense recordings. The ViSP layouts take
their intrinsics from the folder's <name>.xml / <name>_depth.xml, or from the files given.
The options are `icgp track`'s (--color-intrinsics, --blender-principal-point, ...).

    seq = icgp.Sequence("tests/data/teabox-blender")
    frame = seq[0]
    frame.color, frame.depth, frame.truth()      # NumPy arrays and the 4x4 ground truth
    seq.K_color, seq.K_depth, seq.depth_T_color  # calibration
)doc";

constexpr const char* kFrameDoc = R"doc(One instant of a sequence: every camera's image and the ground truth.

color and depth are the first colour and depth cameras' images (BGR uint8 or grey; float32
metres with 0 where there is no measurement); colors/depths list every camera with its
calibration. Hand a Frame to Tracker.track_frame, or its arrays to Tracker.track.
)doc";

/// The keyword's value, checked as the program checks its option:
/// "frames: expected an integer in [1, 100000], got 0".
template <typename T>
T checked(const char* keyword, const py::object& value, const yaml::Interval& range) {
  const bool integer = std::is_integral_v<T>;
  const std::string expected = std::string(keyword) + ": expected " + (integer ? "an integer in " : "a number in ") + range.text();
  if (integer ? !py::isinstance<py::int_>(value) || py::isinstance<py::bool_>(value)
              : !(py::isinstance<py::int_>(value) || py::isinstance<py::float_>(value)) || py::isinstance<py::bool_>(value))
    throw py::type_error(expected + ", got " + py::repr(value).cast<std::string>());
  const double number = value.cast<double>();
  if (!range.contains(number)) throw py::value_error(expected + ", got " + py::repr(value).cast<std::string>());
  return static_cast<T>(number);
}

yaml::Interval integers(long long min, long long max) {
  return {static_cast<double>(min), static_cast<double>(max)};
}

constexpr const char* kMakeSequenceDoc = R"doc(Renders an RGB-D sequence with exact ground truth and returns it opened.

make_sequence(out, model=None, *, scene=None, frames=100, rate=30, seed=1, speed=1,
              distance=0.5, width=640, height=480, focal=600, baseline=0, stereo_baseline=0,
              spin=0, scale=1, color_noise=0, depth_noise=0, depth_dropout=0,
              grazing_angle=90, depth_edge_holes=0, antialias=0, motion_blur=1, exposure=0.5)

What `icgp make-sequence` does, with its options as keywords and the same ranges: `model`
(a mesh or .cao, default models/textured_box) seen by a camera on a smooth random orbit, or
the bodies of a `scene` file (scenes/*.yaml). Writes icgp's layout into `out` (an earlier
sequence there is replaced), which Sequence and `icgp track` read.
)doc";

}  // namespace

void register_sequence(py::module_& m) {
  py::class_<Frame>(m, "Frame", kFrameDoc)
      .def_readonly("index", &Frame::index, "The frame's index in its sequence.")
      .def_readonly("timestamp", &Frame::timestamp, "Seconds from the first frame.")
      .def_property_readonly("color", [](const Frame& f) { return image_array(f.colors.at(0).image); },
                             "The first colour camera's image: uint8 (H, W, 3) BGR, or (H, W) grey.")
      .def_property_readonly("depth",
                             [](const Frame& f) -> py::object {
                               if (f.depths.empty()) return py::none();
                               return image_array(f.depths.front().depth);
                             },
                             "The first depth camera's image: float32 (H, W) metres, 0 = no measurement; None "
                             "without a depth camera.")
      .def_property_readonly("colors", [](const Frame& f) { return camera_list(f.colors, &ColorImage::image); },
                             "Every colour camera: dicts of camera, image, K, width, height, camera_T_color.")
      .def_property_readonly("depths", [](const Frame& f) { return camera_list(f.depths, &DepthImage::depth); },
                             "Every depth camera: dicts of camera, image, K, width, height, camera_T_color.")
      .def(
          "truth",
          [](const Frame& f, const std::string& object) -> py::object {
            const Pose* truth = f.truth(object);
            if (!truth) return py::none();
            return matrix(*truth);
          },
          py::arg("object") = "",
          "The ground-truth 4x4 pose of `object` (default: the only object), None when there is none.")
      .def_property_readonly("ground_truth",
                             [](const Frame& f) {
                               py::dict d;
                               for (const auto& [name, pose] : f.ground_truth) d[py::str(name)] = matrix(pose);
                               return d;
                             },
                             "Every object's ground-truth 4x4 pose, by name.")
      .def_readonly("joint_truth", &Frame::joint_ground_truth,
                    "Every link's ground-truth joint values (radians, metres), by name.")
      .def("__repr__", [](const Frame& f) { return "<icgp.Frame " + std::to_string(f.index) + ">"; });

  py::class_<Sequence>(m, "Sequence", kSequenceDoc)
      .def(py::init([](const std::filesystem::path& path, const std::optional<std::filesystem::path>& color_intrinsics,
                       const std::optional<std::filesystem::path>& depth_intrinsics, bool blender_principal_point,
                       bool grey_without_depth, double max_depth, double frame_rate) {
             SequenceOptions options = visp_sequence_options();
             if (color_intrinsics) options.color_intrinsics_file = color_intrinsics->string();
             if (depth_intrinsics) options.depth_intrinsics_file = depth_intrinsics->string();
             options.blender_principal_point = blender_principal_point;
             options.grey_without_depth = grey_without_depth;
             options.max_depth = max_depth;
             options.frame_rate = frame_rate;
             if (!std::filesystem::is_directory(path))
               throw std::runtime_error("the sequence folder " + path.string() + " does not exist");
             return Sequence::open(path.string(), options);
           }),
           py::arg("path"), py::kw_only(), py::arg("color_intrinsics") = py::none(),
           py::arg("depth_intrinsics") = py::none(), py::arg("blender_principal_point") = false,
           py::arg("grey_without_depth") = false, py::arg("max_depth") = 10.0, py::arg("frame_rate") = 30.0)
      .def("__len__", &Sequence::size)
      .def(
          "__getitem__",
          [](const Sequence& s, int index) {
            if (index < 0) index += s.size();
            if (index < 0 || index >= s.size()) throw py::index_error("frame index out of range");
            py::gil_scoped_release release;
            return s.load(index);
          },
          py::arg("index"), "Reads frame `index` (negative: from the end).")
      .def_property_readonly("path", &Sequence::directory, "The sequence's folder.")
      .def_property_readonly("layout", &Sequence::layout, "'icgp', 'visp-blender' or 'visp-realsense'.")
      .def_property_readonly("frame_rate", &Sequence::frame_rate, "Frames per second.")
      .def_property_readonly("K_color", [](const Sequence& s) { return camera_matrix(s.color_intrinsics()); },
                             "3x3 camera matrix of the colour images.")
      .def_property_readonly("K_depth", [](const Sequence& s) { return camera_matrix(s.depth_intrinsics()); },
                             "3x3 camera matrix of the depth images.")
      .def_property_readonly("depth_T_color", [](const Sequence& s) { return matrix(s.depth_T_color()); },
                             "4x4 colour camera -> depth camera (ViSP's depth_M_color).")
      .def_property_readonly("objects",
                             [](const Sequence& s) {
                               py::list objects;
                               for (const SequenceObject& o : s.objects()) {
                                 py::dict d;
                                 d["name"] = o.name;
                                 d["model"] = o.mesh_path;
                                 d["parent"] = o.joint ? py::object(py::str(o.joint->parent)) : py::object(py::none());
                                 objects.append(d);
                               }
                               return objects;
                             },
                             "The objects with ground truth: dicts of name, model (mesh file) and parent (links).")
      .def_property_readonly("has_ground_truth", &Sequence::has_ground_truth)
      .def("__repr__", [](const Sequence& s) {
        return "<icgp.Sequence " + s.directory() + " (" + s.layout() + ", " + std::to_string(s.size()) + " frames)>";
      });

  m.def(
      "make_sequence",
      [](const std::filesystem::path& out, const std::optional<std::filesystem::path>& model,
         const std::optional<std::filesystem::path>& scene, const py::kwargs& options) {
        namespace range = make_sequence_range;
        MakeSequenceRequest r;
        r.out = out.string();
        if (scene && model) throw py::value_error("make_sequence: give a model or a scene, not both");
        if (model) r.model = model->string();
        else if (!scene) r.model = models_dir() + "/textured_box/textured_box.obj";
        if (scene) r.scene = scene->string();
        for (const auto& [key, value] : options) {
          const std::string k = key.cast<std::string>();
          const py::object v = py::reinterpret_borrow<py::object>(value);
          if ((k == "scale" || k == "spin") && scene)
            throw py::value_error(k + ": a scene gives each body its mesh, scale and motion");
          if (k == "frames") r.writer.frame_count = checked<int>("frames", v, integers(1, range::kMaxFrames));
          else if (k == "rate") r.writer.frame_rate = checked<double>("rate", v, range::kRate);
          else if (k == "seed") r.writer.seed = checked<std::uint64_t>("seed", v, integers(0, std::numeric_limits<unsigned>::max()));
          else if (k == "speed") r.writer.motion.speed = checked<double>("speed", v, range::kSpeed);
          else if (k == "distance") r.writer.motion.distance = checked<double>("distance", v, range::kDistance);
          else if (k == "width") r.width = checked<int>("width", v, integers(1, kMaxImageSide));
          else if (k == "height") r.height = checked<int>("height", v, integers(1, kMaxImageSide));
          else if (k == "focal") r.focal = checked<double>("focal", v, range::kFocal);
          else if (k == "baseline") r.baseline = checked<double>("baseline", v, range::kBaseline);
          else if (k == "stereo_baseline") r.stereo_baseline = checked<double>("stereo_baseline", v, range::kBaseline);
          else if (k == "spin") r.spin = checked<double>("spin", v, range::kSpin);
          else if (k == "scale") r.scale = checked<double>("scale", v, range::kScale);
          else if (k == "color_noise") r.writer.noise.color_sigma = checked<double>("color_noise", v, range::kColorNoise);
          else if (k == "depth_noise") r.writer.noise.depth_sigma_at_1m = checked<double>("depth_noise", v, range::kDepthNoise);
          else if (k == "depth_dropout") r.writer.noise.depth_dropout = checked<double>("depth_dropout", v, range::kDepthDropout);
          else if (k == "grazing_angle") r.writer.noise.grazing_angle_deg = checked<double>("grazing_angle", v, range::kGrazingAngle);
          else if (k == "depth_edge_holes")
            r.writer.noise.depth_edge_holes_px = checked<int>("depth_edge_holes", v, integers(0, range::kMaxDepthEdgeHoles));
          else if (k == "antialias")
            r.writer.antialias_samples = checked<int>("antialias", v, integers(0, range::kMaxAntialiasSamples));
          else if (k == "motion_blur")
            r.writer.motion_blur.samples = checked<int>("motion_blur", v, integers(1, range::kMaxMotionBlurSamples));
          else if (k == "exposure") r.writer.motion_blur.exposure = checked<double>("exposure", v, range::kExposure);
          else if (k == "progress") r.writer.progress = v.cast<bool>();
          else throw py::type_error("make_sequence() got an unexpected keyword argument '" + k + "'");
        }
        if (static_cast<long long>(r.width) * r.height > kMaxImagePixels)
          throw py::value_error("width " + std::to_string(r.width) + " x height " + std::to_string(r.height) +
                                ": more than the " + std::to_string(kMaxImagePixels) + " pixels an image may have");
        {
          py::gil_scoped_release release;
          make_sequence(r, models_dir(), [](const std::string& path, double scale) { return load_any_mesh(path, scale); });
        }
        return Sequence::open(r.out, visp_sequence_options());
      },
      py::arg("out"), py::arg("model") = py::none(), py::kw_only(), py::arg("scene") = py::none(), kMakeSequenceDoc);
}

}  // namespace icgp::python
