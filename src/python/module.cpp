// SPDX-License-Identifier: GPL-2.0-or-later
// icgp._icgp: the C++ side of the icgp Python package. Every error of icgp's C++ code
// (files, YAML keys, scenarios, tracking, ViSP) arrives as icgp.Error with the message the
// command line prints after "icgp: error: "; bad arguments of a binding arrive as
// ValueError or TypeError naming the argument.
#include <pybind11/pybind11.h>

#include <cstdlib>
#include <dlfcn.h>
#include <filesystem>
#include <new>
#include <omp.h>
#include <opencv2/core/utility.hpp>
#include <visp3/core/vpException.h>

#include "bindings.h"

namespace icgp::python {

namespace py = pybind11;

std::string models_dir() {
  namespace fs = std::filesystem;
  if (const char* env = std::getenv("ICGP_MODELS_DIR")) return env;
  // Installed: <prefix>/lib/python3/dist-packages/icgp/_icgp*.so beside <prefix>/share/icgp/models.
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&models_dir), &info) && info.dli_fname) {
    const fs::path installed = fs::path(info.dli_fname).parent_path() / "../../../../share/icgp/models";
    std::error_code ec;
    if (fs::is_directory(installed, ec)) return fs::weakly_canonical(installed, ec).string();
  }
  return ICGP_SOURCE_MODELS_DIR;
}

}  // namespace icgp::python

PYBIND11_MODULE(_icgp, m) {
  namespace py = pybind11;
  m.doc() = "icgp's C++ core: the ICG+ tracker, sequences and the servo simulator (use the icgp package)";
  m.attr("__version__") = ICGP_VERSION;

  static py::handle error = PyErr_NewExceptionWithDoc(
      "icgp.Error",
      "An error of icgp: a file, a YAML key, a scenario or a tracking call that cannot be used. The message is "
      "the one the icgp program prints, naming the file, key or value and what was expected.",
      PyExc_RuntimeError, nullptr);
  m.attr("Error") = error;
  py::register_exception_translator([](std::exception_ptr raised) {
    try {
      if (raised) std::rethrow_exception(raised);
    } catch (const py::builtin_exception&) {
      throw;  // pybind11's own (ValueError, TypeError, ...): the next translator sets them
    } catch (const py::error_already_set&) {
      throw;  // a Python exception from a callback: it goes on as it was raised
    } catch (const std::bad_alloc&) {
      throw;
    } catch (const vpException& e) {
      PyErr_SetString(error.ptr(), e.what());
    } catch (const std::exception& e) {
      PyErr_SetString(error.ptr(), e.what());
    }
  });

  m.def("models_dir", &icgp::python::models_dir, "The folder of icgp's models (textured_box, ...).");
  m.def(
      "set_num_threads",
      [](int threads) {
        if (threads < 1) throw py::value_error("threads: expected a positive integer, got " + std::to_string(threads));
        // ViSP's OpenMP loops and OpenCV's pool; icgp's own code is single-threaded.
        omp_set_num_threads(threads);
        cv::setNumThreads(threads);
      },
      py::arg("threads"),
      "Threads OpenMP (ViSP) and OpenCV may use. The icgp program tracks and times with 1, as the paper does.");
  icgp::python::register_tracker(m);
  icgp::python::register_sequence(m);
  icgp::python::register_evaluation(m);
  icgp::python::register_servo(m);
  icgp::python::register_trials(m);
}
