// SPDX-License-Identifier: GPL-2.0-or-later
// Compares the result files of one ViSP program built twice (vpMbGenericTracker and
// vpMbIcgTracker), for CTest:
//
//   compare_results accuracy <visp errors> <icgp errors>
//     fails unless icgp's mean translation AND mean rotation errors are <= ViSP's;
//   compare_results agreement <visp pose> <icgp pose> <max mm> <max deg>
//     fails unless the two final poses (4x4 cMo files) agree within the bounds;
//   compare_results track-agreement <visp poses> <icgp poses> <max mean mm> <max mean deg>
//     fails unless the poses of every frame (lines "frame r11 r12 r13 tx ... r33 tz") differ
//     by at most the bounds on average, over the frames both files hold.
//
// The error files hold "key value" lines (mean_translation_mm, mean_rotation_deg, ...).
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>

#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpMath.h>

namespace
{
std::map<std::string, std::string> read_keys(const std::string &path)
{
  std::ifstream f(path.c_str());
  if (!f.is_open())
    throw std::runtime_error("cannot read " + path);
  std::map<std::string, std::string> keys;
  std::string line;
  while (std::getline(f, line)) {
    std::istringstream ss(line);
    std::string key, value;
    if (ss >> key >> value)
      keys[key] = value;
  }
  return keys;
}

double number(const std::map<std::string, std::string> &keys, const std::string &key, const std::string &path)
{
  std::map<std::string, std::string>::const_iterator it = keys.find(key);
  if (it == keys.end())
    throw std::runtime_error(path + " has no " + key);
  return std::atof(it->second.c_str());
}

vpHomogeneousMatrix read_pose(const std::string &path)
{
  std::ifstream f(path.c_str());
  if (!f.is_open())
    throw std::runtime_error("cannot read " + path);
  vpHomogeneousMatrix M;
  M.load(f);
  return M;
}

int accuracy(const std::string &visp_file, const std::string &icgp_file)
{
  const std::map<std::string, std::string> visp = read_keys(visp_file), icgp = read_keys(icgp_file);
  const double visp_t = number(visp, "mean_translation_mm", visp_file), visp_r = number(visp, "mean_rotation_deg", visp_file);
  const double icgp_t = number(icgp, "mean_translation_mm", icgp_file), icgp_r = number(icgp, "mean_rotation_deg", icgp_file);
  std::cout << "mean translation error: vpMbGenericTracker " << visp_t << " mm, vpMbIcgTracker " << icgp_t << " mm\n"
            << "mean rotation error:    vpMbGenericTracker " << visp_r << " deg, vpMbIcgTracker " << icgp_r << " deg"
            << std::endl;
  bool ok = true;
  if (!(icgp_t <= visp_t)) {
    std::cout << "FAIL: vpMbIcgTracker's mean translation error is larger (" << icgp_t << " > " << visp_t << " mm)"
              << std::endl;
    ok = false;
  }
  if (!(icgp_r <= visp_r)) {
    std::cout << "FAIL: vpMbIcgTracker's mean rotation error is larger (" << icgp_r << " > " << visp_r << " deg)"
              << std::endl;
    ok = false;
  }
  if (ok)
    std::cout << "vpMbIcgTracker is at least as accurate as vpMbGenericTracker" << std::endl;
  return ok ? EXIT_SUCCESS : EXIT_FAILURE;
}

//! Per-frame poses: lines "frame" followed by the first three rows of cMo.
std::map<int, vpHomogeneousMatrix> read_poses(const std::string &path)
{
  std::ifstream f(path.c_str());
  if (!f.is_open())
    throw std::runtime_error("cannot read " + path);
  std::map<int, vpHomogeneousMatrix> poses;
  std::string line;
  while (std::getline(f, line)) {
    std::istringstream ss(line);
    int frame = 0;
    vpHomogeneousMatrix M;
    bool ok = static_cast<bool>(ss >> frame);
    for (unsigned int i = 0; ok && i < 3; i++)
      for (unsigned int j = 0; ok && j < 4; j++)
        ok = static_cast<bool>(ss >> M[i][j]);
    if (!ok)
      throw std::runtime_error(path + ": expected lines of a frame number and 12 numbers, got '" + line + "'");
    poses[frame] = M;
  }
  return poses;
}

//! The distance between the translations (mm) and the angle between the rotations (deg).
void difference(const vpHomogeneousMatrix &a, const vpHomogeneousMatrix &b, double &t_mm, double &r_deg)
{
  t_mm = 1000.0 * (a.getTranslationVector() - b.getTranslationVector()).frobeniusNorm();
  const vpThetaUVector tu(a.getRotationMatrix() * b.getRotationMatrix().t());
  r_deg = vpMath::deg(std::sqrt(tu.sumSquare()));
}

int track_agreement(const std::string &visp_file, const std::string &icgp_file, double max_mm, double max_deg)
{
  const std::map<int, vpHomogeneousMatrix> visp = read_poses(visp_file), icgp = read_poses(icgp_file);
  double sum_mm = 0.0, sum_deg = 0.0, worst_mm = 0.0, worst_deg = 0.0;
  int n = 0;
  for (std::map<int, vpHomogeneousMatrix>::const_iterator it = visp.begin(); it != visp.end(); ++it) {
    const std::map<int, vpHomogeneousMatrix>::const_iterator other = icgp.find(it->first);
    if (other == icgp.end())
      continue;
    double t_mm = 0.0, r_deg = 0.0;
    difference(it->second, other->second, t_mm, r_deg);
    sum_mm += t_mm;
    sum_deg += r_deg;
    worst_mm = std::max(worst_mm, t_mm);
    worst_deg = std::max(worst_deg, r_deg);
    n++;
  }
  if (n == 0 || n < static_cast<int>(visp.size())) {
    std::cout << "FAIL: vpMbIcgTracker's poses cover " << n << " of the " << visp.size() << " frames" << std::endl;
    return EXIT_FAILURE;
  }
  const double mean_mm = sum_mm / n, mean_deg = sum_deg / n;
  std::cout << "over " << n << " frames the two trackers' poses differ by " << mean_mm << " mm and " << mean_deg
            << " deg on average (bounds " << max_mm << " mm, " << max_deg << " deg), at most " << worst_mm
            << " mm and " << worst_deg << " deg" << std::endl;
  if (!(mean_mm <= max_mm && mean_deg <= max_deg)) {
    std::cout << "FAIL: the two trackers' poses disagree" << std::endl;
    return EXIT_FAILURE;
  }
  return EXIT_SUCCESS;
}

int agreement(const std::string &visp_file, const std::string &icgp_file, double max_mm, double max_deg)
{
  const vpHomogeneousMatrix visp = read_pose(visp_file), icgp = read_pose(icgp_file);
  double t_mm = 0.0, r_deg = 0.0;
  difference(visp, icgp, t_mm, r_deg);
  std::cout << "final poses of vpMbGenericTracker and vpMbIcgTracker differ by " << t_mm << " mm and " << r_deg
            << " deg (bounds " << max_mm << " mm, " << max_deg << " deg)" << std::endl;
  if (!(t_mm <= max_mm && r_deg <= max_deg)) {
    std::cout << "FAIL: the two trackers' final poses disagree" << std::endl;
    return EXIT_FAILURE;
  }
  return EXIT_SUCCESS;
}
} // namespace

int main(int argc, char *argv[])
{
  try {
    const std::string mode = argc > 1 ? argv[1] : "";
    if (mode == "accuracy" && argc == 4)
      return accuracy(argv[2], argv[3]);
    if (mode == "agreement" && argc == 6)
      return agreement(argv[2], argv[3], std::atof(argv[4]), std::atof(argv[5]));
    if (mode == "track-agreement" && argc == 6)
      return track_agreement(argv[2], argv[3], std::atof(argv[4]), std::atof(argv[5]));
    std::cerr << "Usage: " << argv[0] << " accuracy <visp errors> <icgp errors>\n"
              << "       " << argv[0] << " agreement <visp pose> <icgp pose> <max mm> <max deg>\n"
              << "       " << argv[0] << " track-agreement <visp poses> <icgp poses> <max mean mm> <max mean deg>"
              << std::endl;
  } catch (const std::exception &e) {
    std::cerr << "compare_results: " << e.what() << std::endl;
  }
  return EXIT_FAILURE;
}
