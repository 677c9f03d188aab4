// SPDX-License-Identifier: GPL-2.0-or-later
// icgp.Sequence and icgp.Frame: the RGB-D sequences `icgp track` reads (ViSP's layouts and
// icgp's), frame by frame as NumPy arrays.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <filesystem>

#include "bindings.h"
#include "icgp/eval/sequence.h"
#include "icgp/visp/visp_camera_xml.h"
#include "numpy_conversions.h"

namespace icgp::python {
namespace {

namespace py = pybind11;

py::dict camera_dict(const std::string& camera, const Intrinsics& k, const Pose& camera_T_reference) {
  py::dict d;
  d["camera"] = camera;
  d["K"] = camera_matrix(k);
  d["width"] = k.width;
  d["height"] = k.height;
  d["camera_T_color"] = matrix(camera_T_reference);
  return d;
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
      .def_property_readonly("colors",
                             [](const Frame& f) {
                               py::list cameras;
                               for (const ColorImage& c : f.colors) {
                                 py::dict d = camera_dict(c.camera, c.intrinsics, c.camera_T_reference);
                                 d["image"] = image_array(c.image);
                                 cameras.append(d);
                               }
                               return cameras;
                             },
                             "Every colour camera: dicts of camera, image, K, width, height, camera_T_color.")
      .def_property_readonly("depths",
                             [](const Frame& f) {
                               py::list cameras;
                               for (const DepthImage& d : f.depths) {
                                 py::dict e = camera_dict(d.camera, d.intrinsics, d.camera_T_reference);
                                 e["image"] = image_array(d.depth);
                                 cameras.append(e);
                               }
                               return cameras;
                             },
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
}

}  // namespace icgp::python
