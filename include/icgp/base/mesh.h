// SPDX-License-Identifier: GPL-2.0-or-later
#pragma once

#include <Eigen/Core>
#include <opencv2/core/mat.hpp>
#include <string>
#include <vector>

#include "icgp/base/pose.h"

namespace icgp {

/// Appearance of one part of a mesh: a diffuse texture when present, else a flat colour,
/// and how its surface reflects light (the metallic-roughness parameters of physically
/// based shading, each in [0, 1]; the defaults: a dielectric of medium gloss).
struct Material {
  Eigen::Vector3f diffuse_rgb{0.8f, 0.8f, 0.8f};  ///< linear 0..1
  cv::Mat texture_bgr;                             ///< CV_8UC3, empty when untextured
  float roughness = 0.5f;  ///< 0: a mirror-sharp highlight, 1: none
  float metallic = 0.0f;   ///< 1: a metal, whose reflection takes the diffuse colour
  /// Reflectance of a dielectric at normal incidence, 0.5 = 4 % (Blender's "Specular"); 0: no highlight.
  float specular = 0.5f;
};

/// Triangles sharing one material. Texture coordinates are empty or one per vertex, with
/// (0,0) at the bottom-left of the texture image (OBJ/glTF-as-loaded-by-assimp convention).
struct MeshPart {
  std::vector<Eigen::Vector3f> vertices;  ///< metres, in the mesh (body) frame
  std::vector<Eigen::Vector2f> texcoords;
  std::vector<Eigen::Vector3i> triangles;  ///< indices into vertices
  Material material;
};

/// Bounds every loaded mesh is held to (check_mesh): beyond them model generation and
/// rendering would take unbounded time or lose float precision.
struct MeshLimits {
  static constexpr std::size_t kMaxTriangles = 10000000;
  static constexpr float kMaxCoordinate = 1e4f;  ///< |x|, |y|, |z| in metres
};

/// A triangle mesh in metres, the one geometry type every loader produces and every
/// consumer (renderer, model generation, metrics) reads.
struct Mesh {
  std::string source;  ///< file it was loaded from, for messages
  std::vector<MeshPart> parts;

  std::size_t vertex_count() const;
  std::size_t triangle_count() const;
  bool empty() const { return triangle_count() == 0; }
  /// All vertices of all parts, in order.
  std::vector<Eigen::Vector3f> all_vertices() const;
  /// Axis-aligned bounds; throws std::runtime_error for an empty mesh.
  void bounds(Eigen::Vector3f& min_corner, Eigen::Vector3f& max_corner) const;
  /// Radius of the smallest origin-centred sphere containing the mesh: views are rendered
  /// looking at the body origin, so this (not the tight bounding sphere) sizes them.
  float radius_about_origin() const;
  /// Transforms every vertex in place: X <- T X.
  void transform(const Posef& T);
  /// Appends the parts of another mesh.
  void append(const Mesh& other);
};

/// A sphere around a mesh, in the mesh's frame.
struct Sphere {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double radius = 0.0;
};

/// The sphere about the centre of the mesh's bounds through its farthest vertex: what a
/// focused render or keypoint crop must enclose. Throws std::runtime_error for an empty mesh.
Sphere bounding_sphere(const Mesh& mesh);

/// Whether any part of the mesh has a texture image.
bool has_texture(const Mesh& mesh);

/// A closed box of `size` (metres) centred on its origin, in one flat colour: an occluder
/// or a prop in a rendered scene.
Mesh box_mesh(const Eigen::Vector3d& size, const Eigen::Vector3f& diffuse_rgb);

/// Throws std::invalid_argument naming `mesh.source` when the mesh is not one icgp can
/// track: no triangle, more than MeshLimits::kMaxTriangles, a vertex that is not finite or
/// beyond MeshLimits::kMaxCoordinate, a triangle index outside its part's vertices, texture
/// coordinates not one per vertex, or all vertices at one point (no extent to view).
void check_mesh(const Mesh& mesh);

}  // namespace icgp
