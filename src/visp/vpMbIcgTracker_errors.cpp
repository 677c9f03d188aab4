// SPDX-License-Identifier: GPL-2.0-or-later
// vpMbIcgTracker's errors as ViSP's: what icgp's core and the libraries under it throw,
// rethrown as the vpException it means (nothing else may leave the class), and the file
// checks that raise ViSP's ioError before a parser sees a path.
#include <filesystem>
#include <fstream>
#include <new>
#include <opencv2/core.hpp>
#include <stdexcept>
#include <visp3/core/vpTrackingException.h>

#include "vpMbIcgTracker_impl.h"

using icgp::visp_detail::Failure;

void icgp::visp_detail::require_file(const std::string& path, const std::string& what) {
  std::error_code error;
  if (!std::filesystem::exists(path, error))
    throw vpException(vpException::ioError, "vpMbIcgTracker: " + what + " '" + path + "' does not exist");
  if (!std::filesystem::is_regular_file(path, error))
    throw vpException(vpException::ioError, "vpMbIcgTracker: " + what + " '" + path + "' is not a regular file");
  if (!std::ifstream(path))
    throw vpException(vpException::ioError, "vpMbIcgTracker: " + what + " '" + path + "' cannot be read");
}

namespace {

[[noreturn]] void throw_failure(Failure failure, const std::string& message) {
  if (failure == Failure::kTracking) throw vpTrackingException(vpTrackingException::fatalError, message);
  throw vpException(vpException::fatalError, message);
}

}  // namespace

void icgp::visp_detail::rethrow_as_visp_exception(const std::string& call, Failure failure) {
  const std::string prefix = "vpMbIcgTracker::" + call + ": ";
  try {
    throw;
  } catch (const vpException&) {
    throw;
  } catch (const std::invalid_argument& e) {
    throw vpException(vpException::badValue, prefix + e.what());
  } catch (const std::out_of_range& e) {
    throw vpException(vpException::badValue, prefix + e.what());
  } catch (const std::domain_error& e) {
    throw vpException(vpException::badValue, prefix + e.what());
  } catch (const std::bad_alloc& e) {
    throw vpException(vpException::memoryAllocationError, prefix + "out of memory (" + e.what() + ")");
  } catch (const std::length_error& e) {
    throw vpException(vpException::memoryAllocationError, prefix + "out of memory (" + e.what() + ")");
  } catch (const cv::Exception& e) {
    if (e.code == cv::Error::StsNoMem)
      throw vpException(vpException::memoryAllocationError, prefix + "out of memory (OpenCV: " + e.err + ")");
    throw_failure(failure, prefix + "OpenCV: " + e.err + " in " + e.func);
  } catch (const std::exception& e) {
    throw_failure(failure, prefix + e.what());
  } catch (...) {
    throw_failure(failure, prefix + "an exception that is not a std::exception");
  }
}
