// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "icgp/base/mesh.h"
#include "icgp/model/viewpoint_model.h"
#include "icgp/model/viewpoint_model_generator.h"

namespace icgp {

/// Why a model file cannot be used: missing, unreadable, foreign, of another version,
/// truncated or corrupted. The message names the file and the reason.
class ModelFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// $ICGP_CACHE_DIR, else $XDG_CACHE_HOME/icgp, else $HOME/.cache/icgp, else icgp-cache in
/// the temporary directory.
std::string default_model_cache_dir();

/// <cache_dir>/<name>-<kind>-<key as 16 hex digits>.icgpmodel, the name reduced to
/// letters, digits, '.', '_' and '-'.
std::string model_cache_path(const std::string& cache_dir, const std::string& name, ViewpointModel::Kind kind,
                             std::uint64_t key);

/// Writes a model file: magic, version, kind, key, parameters, counts, payload (views,
/// point counts, points and depth offsets in 45 bytes a point, src/model/stored_model.h) and
/// a checksum over all of it. Atomic: written to a temporary file next to `path`, then renamed, so readers never
/// see half a file. Creates missing directories. Throws ModelFileError on failure.
void save_viewpoint_model(const ViewpointModel& model, const std::string& path);

/// Reads a model file and verifies it (magic, version, sizes, checksum, values); throws
/// ModelFileError saying why it is unusable. Does not check what model it is: compare its
/// kind(), key() and params() with what you expect. The model equals the one that was saved,
/// byte for byte (the default region model of an object loads in about 30 ms).
ViewpointModel load_viewpoint_model(const std::string& path);

/// What load_or_generate did for one model.
struct CachedModelInfo {
  std::string path;        ///< its cache file
  bool generated = false;  ///< not in the cache (or unusable there), so generated
  bool saved = false;      ///< written to the cache (false when the cache is not writable, or in_background)
};

/// The models of the requests, from the cache when a file there fits (same kind, key and
/// parameters, intact), else generated (together, sharing renders) and saved. Every file
/// that is not used is reported in one line on stderr saying why (missing, stale, foreign,
/// truncated, corrupted); an unwritable cache gives a warning, never an error. Processes that
/// need the same missing model at once do not all generate it: one does, holding a lock on
/// <model file>.lock, and the others say on stderr that they wait, then load its file.
/// options.in_background: missing models are returned at once, generated in the background
/// (generate_viewpoint_models), and each is saved when complete; this process holds the
/// model's lock until then, so others wait for its file as for any generation. Within this
/// process a model still being made is shared: a later call gets the same model, at once
/// with options.in_background (its views are made as they are required), else once it is
/// complete.
/// options.on_complete is replaced by the saving.
/// `cache_dir` empty: default_model_cache_dir(). Files are named after options.name, else
/// the mesh file's stem.
std::vector<ViewpointModel> load_or_generate(const Mesh& mesh, const std::vector<ModelRequest>& requests,
                                             const std::string& cache_dir = {},
                                             const ModelGenerationOptions& options = {},
                                             std::vector<CachedModelInfo>* info = nullptr);

/// One model: load_or_generate with a single request.
ViewpointModel load_or_generate(ViewpointModel::Kind kind, const Mesh& mesh, const ViewpointModelParams& params,
                                const std::string& cache_dir = {}, const ModelGenerationOptions& options = {});

}  // namespace icgp
