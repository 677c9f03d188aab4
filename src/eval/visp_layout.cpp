// SPDX-License-Identifier: GPL-2.0-or-later
#include "visp_layout.h"

#include <algorithm>
#include <vector>

#include "sequence_files.h"

namespace icgp {

namespace fs = std::filesystem;

namespace {

struct IntrinsicsFiles {
  fs::path color, depth;
};

/// The `<name>.xml` files of `folder` that have a `<name>_depth.xml` beside them.
std::vector<IntrinsicsFiles> xml_pairs_in(const fs::path& folder) {
  std::vector<IntrinsicsFiles> pairs;
  if (!fs::is_directory(folder)) return pairs;
  for (const auto& entry : fs::directory_iterator(folder)) {
    const fs::path& p = entry.path();
    if (p.extension() != ".xml") continue;
    const std::string stem = p.stem().string();
    if (stem.size() > 6 && stem.compare(stem.size() - 6, 6, "_depth") == 0) continue;
    const fs::path depth = folder / (stem + "_depth.xml");
    if (fs::is_regular_file(depth)) pairs.push_back({p, depth});
  }
  std::sort(pairs.begin(), pairs.end(), [](const auto& a, const auto& b) { return a.color < b.color; });
  return pairs;
}

/// Relative option paths may be relative to the working directory or to the sequence.
fs::path resolve_option_path(const std::string& path, const fs::path& dir) {
  const fs::path given(path);
  if (given.is_absolute() || fs::exists(given)) return given;
  return dir / given;
}

IntrinsicsFiles find_intrinsics_files(const fs::path& dir, const SequenceOptions& options) {
  if (!options.color_intrinsics_file.empty()) {
    IntrinsicsFiles files;
    files.color = resolve_option_path(options.color_intrinsics_file, dir);
    files.depth = options.depth_intrinsics_file.empty()
                      ? files.color.parent_path() / (files.color.stem().string() + "_depth.xml")
                      : resolve_option_path(options.depth_intrinsics_file, dir);
    require_file(files.color, "colour intrinsics file (SequenceOptions::color_intrinsics_file)");
    require_file(files.depth, "depth intrinsics file (SequenceOptions::depth_intrinsics_file, or <stem>_depth.xml "
                              "beside the colour one)");
    return files;
  }
  if (!options.depth_intrinsics_file.empty())
    fail(dir, "SequenceOptions::depth_intrinsics_file is set but color_intrinsics_file is not");

  std::vector<IntrinsicsFiles> candidates = xml_pairs_in(dir);
  if (candidates.empty() && fs::is_directory(dir / "models")) {
    std::vector<fs::path> model_folders;
    for (const auto& entry : fs::directory_iterator(dir / "models"))
      if (entry.is_directory()) model_folders.push_back(entry.path());
    std::sort(model_folders.begin(), model_folders.end());
    for (const auto& folder : model_folders) {
      const auto pairs = xml_pairs_in(folder);
      candidates.insert(candidates.end(), pairs.begin(), pairs.end());
    }
  }
  if (candidates.size() == 1) return candidates.front();
  if (candidates.empty())
    fail(dir, "no intrinsics found: looked for a <name>.xml + <name>_depth.xml pair (ViSP <camera> blocks) in the "
              "folder and in models/*/; set SequenceOptions::color_intrinsics_file and depth_intrinsics_file");
  std::string list;
  for (const auto& c : candidates) list += "\n  " + c.color.string() + " + " + c.depth.filename().string();
  fail(dir, "ambiguous intrinsics, " + std::to_string(candidates.size()) + " candidate pairs:" + list +
                "\nchoose one with SequenceOptions::color_intrinsics_file and depth_intrinsics_file");
}

/// ViSP models of the sequence: the top-level .cao files, else the .cao named like the
/// colour intrinsics file beside it (models/cube/cube.xml -> models/cube/cube.cao).
std::vector<SequenceObject> find_visp_objects(const fs::path& dir, const fs::path& color_xml) {
  std::vector<SequenceObject> objects;
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.path().extension() == ".cao") objects.push_back({entry.path().stem().string(), entry.path().string()});
  std::sort(objects.begin(), objects.end(), [](const auto& a, const auto& b) { return a.name < b.name; });
  const fs::path beside = color_xml.parent_path() / (color_xml.stem().string() + ".cao");
  if (objects.empty() && fs::is_regular_file(beside)) objects.push_back({color_xml.stem().string(), beside.string()});
  return objects;
}

}  // namespace

void VispLayout::describe_calibration(const std::string& layout, const SequenceOptions& options,
                                      SequenceDescription& d) const {
  if (!options.read_camera_xml)
    fail(dir_, "a " + layout + " sequence keeps its intrinsics in ViSP XML files, which the core library does not "
               "read: set SequenceOptions::read_camera_xml, e.g. to icgp::read_visp_camera_xml of icgp::visp "
               "(icgp/visp/visp_camera_xml.h; icgp::visp_sequence_options() sets it)");
  const IntrinsicsFiles xml = find_intrinsics_files(dir_, options);
  d.color_intrinsics = options.read_camera_xml(xml.color.string());
  d.depth_intrinsics = options.read_camera_xml(xml.depth.string());
  require_file(dir_ / "depth_M_color.txt", "colour-to-depth transform");
  d.depth_T_color = read_pose_matrix_file((dir_ / "depth_M_color.txt").string());
  const cv::Mat color = read_color_image(color_file(0));
  d.color_intrinsics.width = color.cols;
  d.color_intrinsics.height = color.rows;
  const cv::Mat depth = read_depth(0);
  d.depth_intrinsics.width = depth.cols;
  d.depth_intrinsics.height = depth.rows;
  d.color_intrinsics.validate(xml.color.string());
  d.depth_intrinsics.validate(xml.depth.string());
  d.objects = find_visp_objects(dir_, xml.color);
  d.frame_rate = options.frame_rate;
}

}  // namespace icgp
