// SPDX-License-Identifier: GPL-2.0-or-later
// Compares the result files of one ViSP program built twice (vpMbGenericTracker and
// vpMbIcgTracker), for CTest:
//
//   compare_results accuracy <visp errors> <icgp errors>
//     fails unless icgp's mean translation AND mean rotation errors are <= ViSP's;
//   compare_results agreement <visp pose> <icgp pose> <max mm> <max deg>
//     fails unless the two final poses (4x4 cMo files) agree within the bounds.
//
// The error files hold "key value" lines (mean_translation_mm, mean_rotation_deg, ...).
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

int agreement(const std::string &visp_file, const std::string &icgp_file, double max_mm, double max_deg)
{
  const vpHomogeneousMatrix visp = read_pose(visp_file), icgp = read_pose(icgp_file);
  const double t_mm = 1000.0 * (visp.getTranslationVector() - icgp.getTranslationVector()).frobeniusNorm();
  const vpThetaUVector tu(visp.getRotationMatrix() * icgp.getRotationMatrix().t());
  const double r_deg = vpMath::deg(std::sqrt(tu.sumSquare()));
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
    std::cerr << "Usage: " << argv[0] << " accuracy <visp errors> <icgp errors>\n"
              << "       " << argv[0] << " agreement <visp pose> <icgp pose> <max mm> <max deg>" << std::endl;
  } catch (const std::exception &e) {
    std::cerr << "compare_results: " << e.what() << std::endl;
  }
  return EXIT_FAILURE;
}
