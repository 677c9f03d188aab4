// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/model/model_cache.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cmath>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <sstream>

#include "icgp/model/model_key.h"
#include "stored_model.h"

namespace icgp {
namespace {

namespace fs = std::filesystem;

// File layout, little-endian (the byte order of every machine this runs on; a big-endian
// reader sees a wrong version and regenerates):
//   magic[8] version:u32 kind:u32 key:u64
//   n_divides image_size image_margin n_points min_contour_length normal_chord_offset: i32
//   sphere_radius stride_depth_offset max_radius_depth_offset: f64   seed: u64
//   n_views n_points n_depth_offsets reserved: u32   payload_bytes: u64   checksum: u64
//   payload: stored_payload() (stored_model.h): views (direction xyz, measure: f32), point
//   counts (i32), points (position f32, normal in octahedral i16, foreground and
//   background distance f16), depth offsets (a byte each)
// The checksum covers the header before it and the payload.
constexpr char kMagic[8] = {'I', 'C', 'G', 'P', 'M', 'O', 'D', 'L'};
constexpr std::size_t kHeaderSize = 112;
constexpr std::size_t kChecksumOffset = kHeaderSize - 8;

/// A 64-bit checksum in the style of xxHash64: four independent lanes, so it runs at memory
/// speed (a byte-wise hash would take longer than reading the file). The header's sum seeds
/// the payload's.
std::uint64_t checksum(const void* data, std::size_t size, std::uint64_t seed) {
  constexpr std::uint64_t p1 = 11400714785074694791ull, p2 = 14029467366897019727ull, p3 = 1609587929392839161ull,
                          p4 = 9650029242287828579ull, p5 = 2870177450012600261ull;
  auto rotl = [](std::uint64_t x, int r) { return (x << r) | (x >> (64 - r)); };
  auto round = [&](std::uint64_t acc, std::uint64_t input) { return rotl(acc + input * p2, 31) * p1; };
  auto word = [](const unsigned char* p) {
    std::uint64_t w;
    std::memcpy(&w, p, sizeof w);
    return w;
  };
  const auto* p = static_cast<const unsigned char*>(data);
  const unsigned char* end = p + size;
  std::uint64_t lane[4] = {seed + p1 + p2, seed + p2, seed, seed - p1};
  for (; p + 32 <= end; p += 32)
    for (int l = 0; l < 4; ++l) lane[l] = round(lane[l], word(p + 8 * l));
  std::uint64_t h = rotl(lane[0], 1) + rotl(lane[1], 7) + rotl(lane[2], 12) + rotl(lane[3], 18) + size;
  for (; p + 8 <= end; p += 8) h = rotl(h ^ round(0, word(p)), 27) * p1 + p4;
  for (; p < end; ++p) h = rotl(h ^ (*p * p5), 11) * p1;
  h ^= h >> 33;
  h *= p2;
  h ^= h >> 29;
  h *= p3;
  return h ^ (h >> 32);
}

class HeaderWriter {
 public:
  template <typename T>
  HeaderWriter& operator<<(const T& value) {
    bytes_.append(reinterpret_cast<const char*>(&value), sizeof value);
    return *this;
  }
  std::string& bytes() { return bytes_; }

 private:
  std::string bytes_;
};

class HeaderReader {
 public:
  explicit HeaderReader(const unsigned char* bytes) : p_(bytes) {}
  template <typename T>
  HeaderReader& operator>>(T& value) {
    std::memcpy(&value, p_, sizeof value);
    p_ += sizeof value;
    return *this;
  }

 private:
  const unsigned char* p_;
};

std::string header(const ViewpointModel& m, const std::string& payload) {
  const ViewpointModelParams& p = m.params();
  HeaderWriter w;
  w.bytes().append(kMagic, sizeof kMagic);
  w << kViewpointModelVersion << static_cast<std::uint32_t>(m.kind()) << m.key();
  w << p.n_divides << p.image_size << p.image_margin << p.n_points << p.min_contour_length << p.normal_chord_offset;
  w << p.sphere_radius << p.stride_depth_offset << p.max_radius_depth_offset << p.seed;
  w << static_cast<std::uint32_t>(m.n_views()) << static_cast<std::uint32_t>(m.n_points())
    << static_cast<std::uint32_t>(m.n_depth_offsets()) << std::uint32_t{0};
  w << static_cast<std::uint64_t>(payload.size());
  std::string bytes = std::move(w.bytes());
  if (bytes.size() != kChecksumOffset) throw std::logic_error("model file header layout changed: update kHeaderSize");
  const std::uint64_t sum = checksum(payload.data(), payload.size(), checksum(bytes.data(), bytes.size(), 0));
  bytes.append(reinterpret_cast<const char*>(&sum), sizeof sum);
  return bytes;
}

ModelFileError file_error(const std::string& path, const std::string& why) {
  return ModelFileError("model file " + path + " " + why);
}

/// The file mapped read-only (and pre-faulted: its pages are in the page cache right after
/// a write, so this costs next to nothing).
class MappedFile {
 public:
  explicit MappedFile(const std::string& path) {
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0)
      throw file_error(path,
                       errno == ENOENT ? "does not exist" : std::string("cannot be read: ") + std::strerror(errno));
    struct stat st {};
    if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
      ::close(fd);
      throw file_error(path, "is not a regular file (expected an icgp model file)");
    }
    size_ = static_cast<std::size_t>(st.st_size);
    if (size_ > 0) {
      void* p = ::mmap(nullptr, size_, PROT_READ, MAP_PRIVATE | MAP_POPULATE, fd, 0);
      if (p != MAP_FAILED) data_ = static_cast<const unsigned char*>(p);
    }
    const int mmap_errno = errno;
    ::close(fd);
    if (size_ > 0 && !data_) throw file_error(path, std::string("cannot be mapped: ") + std::strerror(mmap_errno));
  }
  ~MappedFile() {
    if (data_) ::munmap(const_cast<unsigned char*>(data_), size_);
  }
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;

  const unsigned char* data() const { return data_; }
  std::size_t size() const { return size_; }

 private:
  const unsigned char* data_ = nullptr;
  std::size_t size_ = 0;
};

std::string sanitised(const std::string& name) {
  std::string out = name.empty() ? "mesh" : name;
  for (char& c : out)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '_' && c != '-') c = '_';
  return out;
}

std::string model_name(const Mesh& mesh, const ModelGenerationOptions& options) {
  return options.name.empty() ? fs::path(mesh.source).stem().string() : options.name;
}

void report(const std::string& line) { std::cerr << ("icgp: " + line + "\n") << std::flush; }

/// A valid checksum only says the file is as written: a file written by another program
/// (or a bug) can hold values no generator makes, which would track silently wrong. (Normals
/// and depth offsets are stored as codes that only decode to valid values.)
void check_contents(const ViewpointModel& model, const std::string& path) {
  const auto corrupted = [&](int view, const std::string& what) {
    throw file_error(path, "is corrupted (view " + std::to_string(view) + ": " + what + ")");
  };
  const auto non_negative = [](float x) { return x >= 0.f; };  // false for NaN
  for (int v = 0; v < model.n_views(); ++v) {
    const ModelView& view = model.view(v);
    if (!view.direction.allFinite() || std::abs(view.direction.norm() - 1.f) > 1e-3f)
      corrupted(v, "its direction is not a unit vector");
    if (!std::isfinite(view.measure) || !non_negative(view.measure)) corrupted(v, "its measure is not a finite number >= 0");
    const int count = model.view_point_count(v);
    if (count < 0 || count > model.n_points()) corrupted(v, "point count " + std::to_string(count) + " out of range");
    for (int i = 0; i < count; ++i) {
      const ModelPoint& point = model.points(v)[i];
      if (!point.position.allFinite() || !point.normal.allFinite() || !std::isfinite(point.foreground_distance) ||
          !non_negative(point.foreground_distance) || !non_negative(point.background_distance))
        corrupted(v, "point " + std::to_string(i) + " has a value that is not finite or negative");
    }
  }
}

/// The model of `request` from its cache file when that file fits (same kind, key and
/// parameters, intact); else nothing, with `why` set to the line that says why it is
/// (re)generated.
std::optional<ViewpointModel> cached_model(const ModelRequest& request, std::uint64_t key, const std::string& path,
                                           std::string* why = nullptr) {
  const std::string what = to_string(request.kind) + " model cache " + path;
  std::string reason;
  std::error_code ec;
  if (!fs::exists(path, ec)) {
    reason = what + ": not found; generating";
  } else {
    try {
      ViewpointModel cached = load_viewpoint_model(path);
      if (cached.kind() == request.kind && cached.key() == key && cached.params() == request.params) return cached;
      reason = what + ": stale (made for another mesh, parameters or kind); regenerating";
    } catch (const ModelFileError& e) {
      reason = to_string(request.kind) + " " + e.what() + "; regenerating";
    }
  }
  if (why) *why = reason;
  return std::nullopt;
}

/// An exclusive lock (flock) on <model file>.lock, held while this process generates and
/// saves the model, so that others needing it at the same time wait and load its file
/// instead of generating it too. When no lock can be had (a read-only cache folder, a file
/// system without flock), the model is generated as without one: the rename of
/// save_viewpoint_model still never lets a reader see half a file. The lock file is removed
/// before the lock is released, so none stays in the cache. A process that took the lock
/// looks for the model file again before generating it, so a lock file removed under a waiter
/// costs at most a second generation, and only when the first one was not saved.
class GenerationLock {
 public:
  GenerationLock(const std::string& model_path, const std::string& what) : path_(model_path + ".lock") {
    std::error_code ec;
    fs::create_directories(fs::path(path_).parent_path(), ec);
    fd_ = ::open(path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0666);
    if (fd_ < 0) return;
    if (::flock(fd_, LOCK_EX | LOCK_NB) == 0) return;
    if (errno == EWOULDBLOCK) {
      report(what + ": another process is generating it; waiting for it");
      int locked;
      while ((locked = ::flock(fd_, LOCK_EX)) != 0 && errno == EINTR) {
      }
      if (locked == 0) return;
    }
    ::close(fd_);
    fd_ = -1;
  }
  ~GenerationLock() {
    if (fd_ < 0) return;
    // Only the file this process locked: another may have made a new one at the same path.
    struct stat locked {}, at_path {};
    if (::fstat(fd_, &locked) == 0 && ::stat(path_.c_str(), &at_path) == 0 && locked.st_ino == at_path.st_ino &&
        locked.st_dev == at_path.st_dev)
      ::unlink(path_.c_str());
    ::close(fd_);  // releases the lock
  }
  GenerationLock(const GenerationLock&) = delete;
  GenerationLock& operator=(const GenerationLock&) = delete;

 private:
  std::string path_;
  int fd_ = -1;
};

/// The models this process is making in the background, by cache file, until they are
/// saved: another tracker or detector of the same object in this process shares the views
/// made so far, and has any view it needs made next, instead of waiting for the file behind
/// the lock this process holds (flock locks belong to an open file, so a process would wait
/// for itself until the whole model is made).
class ModelsInProgress {
 public:
  static ModelsInProgress& instance() {
    static ModelsInProgress models;
    return models;
  }
  /// The model being made for `path`, while someone still reads it.
  std::optional<ViewpointModel> find(const std::string& path) {
    const std::lock_guard<std::mutex> hold(mutex_);
    const auto it = models_.find(path);
    if (it == models_.end()) return std::nullopt;
    std::shared_ptr<ViewSupply> supply = it->second.supply.lock();
    if (!supply) return std::nullopt;  // its last reader is finishing it: wait for the file
    ViewpointModel model = it->second.views;
    model.set_supply(std::move(supply));
    return model;
  }
  void add(const std::string& path, const ViewpointModel& model) {
    if (model.complete()) return;
    Entry entry{model, model.supply()};
    entry.views.set_supply(nullptr);
    const std::lock_guard<std::mutex> hold(mutex_);
    models_.insert_or_assign(path, std::move(entry));
  }
  void remove(const std::string& path) {
    const std::lock_guard<std::mutex> hold(mutex_);
    models_.erase(path);
  }

 private:
  /// The supply is not owned here: the last reader's copy finishes the model when it goes
  /// (ViewSupply's destructor waits for the views), never a generation thread dropping this
  /// entry from its own completion callback.
  struct Entry {
    ViewpointModel views;  ///< the model's arrays, without its supply
    std::weak_ptr<ViewSupply> supply;
  };
  std::mutex mutex_;
  std::map<std::string, Entry> models_;
};

/// Saves a generated model to its cache file; an unwritable cache is a warning, not an error.
bool save_to_cache(const ViewpointModel& model, const std::string& path) {
  try {
    save_viewpoint_model(model, path);
    return true;
  } catch (const ModelFileError& e) {
    report("warning: " + std::string(e.what()) + "; continuing without the cache");
    return false;
  }
}

}  // namespace

std::string default_model_cache_dir() {
  if (const char* dir = std::getenv("ICGP_CACHE_DIR"); dir && *dir) return dir;
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return (fs::path(xdg) / "icgp").string();
  if (const char* home = std::getenv("HOME"); home && *home) return (fs::path(home) / ".cache" / "icgp").string();
  return (fs::temp_directory_path() / "icgp-cache").string();
}

std::string model_cache_path(const std::string& cache_dir, const std::string& name, ViewpointModel::Kind kind,
                             std::uint64_t key) {
  std::ostringstream file;
  file << sanitised(name) << "-" << to_string(kind) << "-" << std::hex << std::setw(16) << std::setfill('0') << key
       << ".icgpmodel";
  return (fs::path(cache_dir) / file.str()).string();
}

void save_viewpoint_model(const ViewpointModel& model, const std::string& path) {
  if (model.n_views() == 0) throw file_error(path, "cannot hold a model without views");
  const fs::path target(path);
  std::error_code ec;
  if (fs::is_directory(target, ec)) throw file_error(path, "cannot be written: it is a directory (expected a file path)");
  if (target.has_parent_path()) fs::create_directories(target.parent_path(), ec);
  if (ec) throw file_error(path, "cannot be written: " + ec.message());
  // Unique per process and call, so concurrent writers of the same model never collide;
  // the last rename wins with a complete file either way.
  static std::atomic<unsigned> counter{0};
  const std::string temporary = path + ".tmp." + std::to_string(::getpid()) + "." + std::to_string(counter++);
  {
    errno = 0;
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (out) {
      const std::string payload = stored_payload(model);
      const std::string head = header(model, payload);
      out.write(head.data(), static_cast<std::streamsize>(head.size()));
      out.write(payload.data(), static_cast<std::streamsize>(payload.size()));
    }
    if (!out) {
      const std::string why = errno != 0 ? std::strerror(errno) : "the stream failed";
      out.close();
      fs::remove(temporary, ec);
      throw file_error(path, "cannot be written: " + why);
    }
  }
  fs::rename(temporary, target, ec);
  if (ec) {
    fs::remove(temporary, ec);
    throw file_error(path, "cannot be written: " + ec.message());
  }
}

ViewpointModel load_viewpoint_model(const std::string& path) {
  const MappedFile file(path);
  const unsigned char* p = file.data();
  if (file.size() >= sizeof kMagic && std::memcmp(p, kMagic, sizeof kMagic) != 0)
    throw file_error(path, "is not an icgp model file (foreign magic)");
  if (file.size() < kHeaderSize)
    throw file_error(path, "is truncated (" + std::to_string(file.size()) + " bytes, the header alone has " +
                               std::to_string(kHeaderSize) + ")");
  HeaderReader r(p + sizeof kMagic);
  std::uint32_t version = 0, kind = 0, n_views = 0, n_points = 0, n_offsets = 0, reserved = 0;
  std::uint64_t key = 0, payload = 0, stored_sum = 0;
  ViewpointModelParams params;
  r >> version >> kind >> key;
  r >> params.n_divides >> params.image_size >> params.image_margin >> params.n_points >> params.min_contour_length >>
      params.normal_chord_offset;
  r >> params.sphere_radius >> params.stride_depth_offset >> params.max_radius_depth_offset >> params.seed;
  r >> n_views >> n_points >> n_offsets >> reserved >> payload >> stored_sum;
  if (version != kViewpointModelVersion)
    throw file_error(path, "has model version " + std::to_string(version) + ", this program writes version " +
                               std::to_string(kViewpointModelVersion));
  try {
    params.validate();  // before payload_size() is trusted with its numbers
  } catch (const std::invalid_argument& e) {
    throw file_error(path, std::string("is corrupted (") + e.what() + ")");
  }
  const bool consistent =
      (kind == static_cast<std::uint32_t>(ViewpointModel::Kind::kRegion) ||
       kind == static_cast<std::uint32_t>(ViewpointModel::Kind::kDepth)) &&
      params.n_divides >= 0 && params.n_divides <= 6 && static_cast<int>(n_views) == params.n_views() &&
      static_cast<int>(n_points) == params.n_points && static_cast<int>(n_offsets) == params.n_depth_offsets() &&
      payload == stored_payload_size(params);
  if (!consistent) throw file_error(path, "is corrupted (inconsistent header)");
  if (file.size() < kHeaderSize + payload)
    throw file_error(path, "is truncated (" + std::to_string(file.size()) + " of " +
                               std::to_string(kHeaderSize + payload) + " bytes)");
  if (file.size() > kHeaderSize + payload)
    throw file_error(path, "is corrupted (" + std::to_string(file.size() - kHeaderSize - payload) + " trailing bytes)");
  if (checksum(p + kHeaderSize, payload, checksum(p, kChecksumOffset, 0)) != stored_sum)
    throw file_error(path, "is corrupted (checksum mismatch)");

  ViewpointModel model = model_from_stored(static_cast<ViewpointModel::Kind>(kind), params, key, p + kHeaderSize);
  check_contents(model, path);
  return model;
}

std::vector<ViewpointModel> load_or_generate(const Mesh& mesh, const std::vector<ModelRequest>& requests,
                                             const std::string& cache_dir, const ModelGenerationOptions& options,
                                             std::vector<CachedModelInfo>* info) {
  const std::string dir = cache_dir.empty() ? default_model_cache_dir() : cache_dir;
  const std::string name = model_name(mesh, options);
  std::vector<ViewpointModel> models(requests.size());
  std::vector<CachedModelInfo> outcome(requests.size());
  std::vector<std::uint64_t> keys(requests.size());
  std::vector<std::size_t> missing_index;
  for (std::size_t i = 0; i < requests.size(); ++i) {
    const ModelRequest& r = requests[i];
    r.params.validate();
    keys[i] = viewpoint_model_key(r.kind, mesh, r.params, options.associated_bodies);
    outcome[i].path = model_cache_path(dir, name, r.kind, keys[i]);
    if (std::optional<ViewpointModel> in_progress = ModelsInProgress::instance().find(outcome[i].path)) {
      if (!options.in_background) in_progress->require_all_views();
      models[i] = std::move(*in_progress);
      outcome[i].generated = true;
      continue;
    }
    if (std::optional<ViewpointModel> cached = cached_model(r, keys[i], outcome[i].path)) {
      models[i] = std::move(*cached);
      continue;
    }
    missing_index.push_back(i);
  }
  if (missing_index.empty()) {
    if (info) *info = std::move(outcome);
    return models;
  }

  // One process generates a model, the others wait for its file (one making it in the
  // background saves it when complete). Locks are taken in path order, so two processes
  // that need the same models never wait for each other.
  std::vector<std::size_t> lock_order = missing_index;
  std::sort(lock_order.begin(), lock_order.end(),
            [&](std::size_t a, std::size_t b) { return outcome[a].path < outcome[b].path; });
  std::vector<std::unique_ptr<GenerationLock>> locks(requests.size());
  for (const std::size_t i : lock_order)
    locks[i] = std::make_unique<GenerationLock>(outcome[i].path,
                                                to_string(requests[i].kind) + " model cache " + outcome[i].path);
  std::vector<ModelRequest> missing;
  std::vector<std::size_t> still_missing;
  for (const std::size_t i : missing_index) {
    std::string why;
    // Another process may have written it while this one waited for the lock.
    if (std::optional<ViewpointModel> cached = cached_model(requests[i], keys[i], outcome[i].path, &why)) {
      models[i] = std::move(*cached);
      continue;
    }
    report(why);
    missing.push_back(requests[i]);
    still_missing.push_back(i);
  }
  ModelGenerationOptions generation = options;
  if (options.in_background) {
    // Each model is saved, and its lock released, once its last view is made.
    struct PendingSave {
      std::string path;
      std::unique_ptr<GenerationLock> lock;
    };
    auto pending = std::make_shared<std::vector<PendingSave>>();
    for (const std::size_t i : still_missing) pending->push_back({outcome[i].path, std::move(locks[i])});
    generation.on_complete = [pending](std::size_t m, const ViewpointModel& model) {
      PendingSave& save = (*pending)[m];
      save_to_cache(model, save.path);
      ModelsInProgress::instance().remove(save.path);
      save.lock.reset();
    };
  }
  std::vector<ViewpointModel> generated = generate_viewpoint_models(mesh, missing, generation);
  for (std::size_t m = 0; m < missing.size(); ++m) {
    const std::size_t i = still_missing[m];
    models[i] = std::move(generated[m]);
    outcome[i].generated = true;
    if (options.in_background)
      ModelsInProgress::instance().add(outcome[i].path, models[i]);
    else
      outcome[i].saved = save_to_cache(models[i], outcome[i].path);
  }
  if (info) *info = std::move(outcome);
  return models;
}

ViewpointModel load_or_generate(ViewpointModel::Kind kind, const Mesh& mesh, const ViewpointModelParams& params,
                                const std::string& cache_dir, const ModelGenerationOptions& options) {
  return std::move(load_or_generate(mesh, {{kind, params}}, cache_dir, options).front());
}

}  // namespace icgp
