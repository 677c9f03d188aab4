// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/io/mesh_loader.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <stdexcept>

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "mesh_file_check.h"

namespace icgp {
namespace {

namespace fs = std::filesystem;

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw std::runtime_error("load_mesh: '" + path + "': " + what);
}

void check_scale(const std::string& path, double scale) {
  if (!std::isfinite(scale) || scale <= 0.0)
    throw std::invalid_argument("load_mesh: '" + path + "': scale " + std::to_string(scale) +
                                " is invalid; expected a finite number > 0");
}

void check_is_file(const std::string& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) fail(path, "no such file; expected a mesh file assimp can read");
  const auto bytes = fs::file_size(path, ec);
  if (ec) fail(path, "its size cannot be read");
  if (bytes > kMaxMeshFileBytes)
    fail(path, std::to_string(bytes) + " bytes (expected at most " + std::to_string(kMaxMeshFileBytes) + " bytes)");
}

unsigned int import_flags() {
  // No normal generation: icgp::Mesh stores none, and smooth normals would only split
  // vertices. SortByPType gives points and lines meshes of their own, which load_mesh
  // skips. RemoveComponent strips normals and vertex colours before
  // JoinIdenticalVertices so that vertices differing only by those (e.g. STL facet
  // normals) are shared.
  return aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_PreTransformVertices |
         aiProcess_SortByPType | aiProcess_RemoveComponent | aiProcess_ValidateDataStructure;
}

/// Checked on the file's own vertices: joining identical vertices would merge a NaN vertex
/// into another one and hide it.
void check_finite_vertices(const aiScene& scene, const std::string& path) {
  for (unsigned int m = 0; m < scene.mNumMeshes; ++m) {
    const aiMesh& mesh = *scene.mMeshes[m];
    for (unsigned int i = 0; i < mesh.mNumVertices; ++i) {
      const aiVector3D& v = mesh.mVertices[i];
      if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
        throw std::invalid_argument("load_mesh: '" + path + "': mesh " + std::to_string(m) + " vertex " + std::to_string(i) +
                                    " is (" + std::to_string(v.x) + ", " + std::to_string(v.y) + ", " +
                                    std::to_string(v.z) + ") (expected finite coordinates)");
    }
  }
}

const aiScene* read_scene(Assimp::Importer& importer, const std::string& path) {
  importer.SetPropertyInteger(AI_CONFIG_PP_RVC_FLAGS, aiComponent_NORMALS | aiComponent_TANGENTS_AND_BITANGENTS |
                                                          aiComponent_COLORS | aiComponent_BONEWEIGHTS |
                                                          aiComponent_ANIMATIONS | aiComponent_LIGHTS |
                                                          aiComponent_CAMERAS);
  const aiScene* scene = importer.ReadFile(path, aiProcess_ValidateDataStructure);
  if (scene == nullptr)
    fail(path, std::string("cannot be read as a triangle mesh: ") + importer.GetErrorString());
  check_finite_vertices(*scene, path);
  scene = importer.ApplyPostProcessing(import_flags());
  if (scene == nullptr)
    fail(path, std::string("cannot be read as a triangle mesh: ") + importer.GetErrorString());
  return scene;
}

std::vector<Eigen::Vector3f> scaled_vertices(const aiMesh& mesh, double scale) {
  std::vector<Eigen::Vector3f> vertices(mesh.mNumVertices);
  const float s = static_cast<float>(scale);
  for (unsigned int i = 0; i < mesh.mNumVertices; ++i) {
    const aiVector3D& v = mesh.mVertices[i];
    vertices[i] = s * Eigen::Vector3f(v.x, v.y, v.z);
  }
  return vertices;
}

std::vector<Eigen::Vector2f> texcoords_of(const aiMesh& mesh) {
  if (!mesh.HasTextureCoords(0)) return {};
  std::vector<Eigen::Vector2f> texcoords(mesh.mNumVertices);
  for (unsigned int i = 0; i < mesh.mNumVertices; ++i)
    texcoords[i] = Eigen::Vector2f(mesh.mTextureCoords[0][i].x, mesh.mTextureCoords[0][i].y);
  return texcoords;
}

/// mesh: triangles only (Triangulate and SortByPType make that so for a triangle mesh).
std::vector<Eigen::Vector3i> triangles_of(const aiMesh& mesh) {
  std::vector<Eigen::Vector3i> triangles;
  triangles.reserve(mesh.mNumFaces);
  for (unsigned int f = 0; f < mesh.mNumFaces; ++f) {
    const aiFace& face = mesh.mFaces[f];
    triangles.emplace_back(face.mIndices[0], face.mIndices[1], face.mIndices[2]);
  }
  return triangles;
}

Eigen::Vector3f diffuse_colour_of(const aiMaterial& material, const Eigen::Vector3f& fallback) {
  aiColor3D colour;
  if (material.Get(AI_MATKEY_COLOR_DIFFUSE, colour) != AI_SUCCESS) return fallback;
  return Eigen::Vector3f(colour.r, colour.g, colour.b);
}

/// Embedded textures are either a compressed file image (mHeight == 0, mWidth bytes) or
/// raw BGRA texels.
cv::Mat decode_embedded_texture(const aiTexture& texture) {
  if (texture.mHeight == 0) {
    if (texture.mWidth == 0) return {};  // cv::imdecode asserts on an empty buffer
    const cv::Mat bytes(1, static_cast<int>(texture.mWidth), CV_8UC1, texture.pcData);
    return cv::imdecode(bytes, cv::IMREAD_COLOR);
  }
  const cv::Mat bgra(static_cast<int>(texture.mHeight), static_cast<int>(texture.mWidth), CV_8UC4,
                     texture.pcData);
  cv::Mat bgr;
  cv::cvtColor(bgra, bgr, cv::COLOR_BGRA2BGR);
  return bgr;
}

cv::Mat embedded_texture(const aiScene& scene, const std::string& reference, const std::string& path) {
  const aiTexture* texture = scene.GetEmbeddedTexture(reference.c_str());
  if (texture == nullptr) fail(path, "embedded texture '" + reference + "' does not exist in the file");
  cv::Mat bgr = decode_embedded_texture(*texture);
  if (bgr.empty()) fail(path, "embedded texture '" + reference + "' cannot be decoded; expected PNG/JPEG data");
  return bgr;
}

cv::Mat texture_file(const std::string& reference, const std::string& path) {
  // Models exported on Windows often write backslashes in texture paths.
  std::string relative = reference;
  std::replace(relative.begin(), relative.end(), '\\', '/');
  const fs::path file = fs::path(path).parent_path() / relative;
  std::error_code ec;
  if (!fs::is_regular_file(file, ec))
    fail(path, "texture '" + file.string() + "' does not exist; expected it relative to the model's folder");
  cv::Mat bgr = cv::imread(file.string(), cv::IMREAD_COLOR);
  if (bgr.empty()) fail(path, "texture '" + file.string() + "' cannot be read; expected an image file (PNG, JPEG...)");
  return bgr;
}

cv::Mat diffuse_texture_of(const aiMaterial& material, const aiScene& scene, const std::string& path) {
  aiString reference;
  if (material.GetTexture(aiTextureType_DIFFUSE, 0, &reference) != AI_SUCCESS) return {};
  const std::string name = reference.C_Str();
  // "*N" names the N-th embedded texture; other names may also match an embedded one
  // (e.g. FBX), and only otherwise refer to a file.
  if (name.rfind('*', 0) == 0 || scene.GetEmbeddedTexture(name.c_str()) != nullptr)
    return embedded_texture(scene, name, path);
  return texture_file(name, path);
}

/// A material's value for `key`, when it has one; refused outside [min, max], naming the
/// file, the material and the key as the file spells it.
std::optional<float> material_number(const aiMaterial& material, const char* key, unsigned type, unsigned index,
                                     const std::string& name, double min, double max, const std::string& path) {
  float value = 0.f;
  if (material.Get(key, type, index, value) != AI_SUCCESS) return std::nullopt;
  if (!(value >= min && value <= max)) {
    char text[128];
    std::snprintf(text, sizeof text, " is %g; expected a number in [%g, %g]", value, min, max);
    fail(path, "material '" + std::string(material.GetName().C_Str()) + "': " + name + text);
  }
  return value;
}

/// How the surface reflects, read as Blender reads a file (so that both renderers see one
/// material): roughness from the PBR roughness (.mtl Pr, glTF roughnessFactor), else from
/// the Phong exponent (Ns in [0, 1000]: 1 - sqrt(Ns / 1000)); metallic from .mtl Pm or glTF
/// metallicFactor; specular from the specular colour's mean (.mtl Ks).
void read_reflectance(const aiMaterial& source, Material& material, const std::string& path) {
  if (auto ns = material_number(source, AI_MATKEY_SHININESS, "Ns (shininess)", 0.0, 1000.0, path))
    material.roughness = 1.0f - std::sqrt(*ns / 1000.0f);
  if (auto r = material_number(source, AI_MATKEY_ROUGHNESS_FACTOR, "Pr (roughness)", 0.0, 1.0, path))
    material.roughness = *r;
  if (auto m = material_number(source, AI_MATKEY_METALLIC_FACTOR, "Pm (metallic)", 0.0, 1.0, path))
    material.metallic = *m;
  aiColor3D ks;
  if (source.Get(AI_MATKEY_COLOR_SPECULAR, ks) == AI_SUCCESS) {
    for (float c : {ks.r, ks.g, ks.b})
      if (!(c >= 0.f && c <= 1.f)) {
        char text[96];
        std::snprintf(text, sizeof text, "': Ks (specular colour) has %g; expected three numbers in [0, 1]", c);
        fail(path, "material '" + std::string(source.GetName().C_Str()) + text);
      }
    material.specular = (ks.r + ks.g + ks.b) / 3.0f;
  }
}

Material material_of(const aiMesh& mesh, const aiScene& scene, const std::string& path) {
  Material material;
  if (mesh.mMaterialIndex >= scene.mNumMaterials) return material;
  const aiMaterial& source = *scene.mMaterials[mesh.mMaterialIndex];
  material.diffuse_rgb = diffuse_colour_of(source, material.diffuse_rgb);
  material.texture_bgr = diffuse_texture_of(source, scene, path);
  // A mesh without materials gets assimp's default one, whose zero Ns and Ks say nothing:
  // it keeps Material's defaults, as a mesh Blender imports without materials does.
  if (std::string(source.GetName().C_Str()) != AI_DEFAULT_MATERIAL_NAME) read_reflectance(source, material, path);
  return material;
}

MeshPart part_of(const aiMesh& mesh, const aiScene& scene, const std::string& path, double scale) {
  MeshPart part;
  part.vertices = scaled_vertices(mesh, scale);
  part.texcoords = texcoords_of(mesh);
  part.triangles = triangles_of(mesh);
  part.material = material_of(mesh, scene, path);
  return part;
}

}  // namespace

Mesh load_mesh(const std::string& path, const MeshLoadOptions& options) {
  check_scale(path, options.scale);
  check_is_file(path);
  check_mesh_file_structure(path);
  Assimp::Importer importer;  // owns the scene: keep it alive while copying
  const aiScene& scene = *read_scene(importer, path);
  Mesh mesh;
  mesh.source = path;
  for (unsigned int m = 0; m < scene.mNumMeshes; ++m) {
    const aiMesh& source = *scene.mMeshes[m];
    if ((source.mPrimitiveTypes & aiPrimitiveType_TRIANGLE) == 0) continue;  // points or lines
    mesh.parts.push_back(part_of(source, scene, path, options.scale));
  }
  if (mesh.empty()) fail(path, "contains no triangles; expected a surface mesh (points and lines are ignored)");
  check_mesh(mesh);
  return mesh;
}

}  // namespace icgp
