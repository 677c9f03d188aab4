// SPDX-License-Identifier: GPL-2.0-or-later
#include "icgp/render/scene_renderer.h"

#include <limits>
#include <stdexcept>

namespace icgp {

bool RenderRequest::operator==(const RenderRequest& other) const {
  const Intrinsics& k = intrinsics;
  const Intrinsics& o = other.intrinsics;
  return k.fu == o.fu && k.fv == o.fv && k.pu == o.pu && k.pv == o.pv &&
         k.width == o.width && k.height == o.height &&
         camera_T_reference.matrix() == other.camera_T_reference.matrix() && square.u_min == other.square.u_min &&
         square.v_min == other.square.v_min && square.size == other.square.size && size == other.size &&
         targets == other.targets;
}

std::optional<RenderRequest> focused_render_request(const std::string& camera, const Intrinsics& intrinsics,
                                                    const Pose& camera_T_reference, const Pose& reference_T_body,
                                                    const Sphere& sphere, int size) {
  const Eigen::Vector3d centre = camera_T_reference * reference_T_body * sphere.centre;
  if (!(centre.z() > sphere.radius)) return std::nullopt;
  return RenderRequest{camera, intrinsics, camera_T_reference, square_around_sphere(intrinsics, centre, sphere.radius),
                       size};
}

void Renders::clear() {
  renders_.clear();
  ids_.clear();
}

void Renders::add(RenderRequest request, FocusedRender render) {
  renders_.emplace_back(std::move(request), std::move(render));
}

void Renders::set_id(const std::string& body, std::uint8_t id) { ids_.emplace_back(body, id); }

std::uint8_t Renders::id(const std::string& body) const {
  for (const auto& [name, id] : ids_)
    if (name == body) return id;
  throw std::logic_error("body '" + body + "' was not rendered in this stage");
}

const FocusedRender* Renders::find(const RenderRequest& request) const {
  for (const auto& [asked, render] : renders_)
    if (asked == request) return &render;
  return nullptr;
}

const FocusedRender& Renders::at(const RenderRequest& request) const {
  if (const FocusedRender* render = find(request)) return *render;
  throw std::logic_error("no render of camera '" + request.camera + "' was requested for this stage");
}

SceneRenderer::SceneRenderer() = default;
SceneRenderer::~SceneRenderer() = default;

Renderer& SceneRenderer::renderer() {
  if (!renderer_) renderer_ = std::make_unique<Renderer>();
  return *renderer_;
}

void SceneRenderer::hide_all() {
  for (const Uploaded& u : uploaded_) renderer_->set_body_visible(u.handle, false);
}

Renderer::BodyHandle SceneRenderer::show(const std::string& name, const Mesh& mesh) {
  for (const Uploaded& u : uploaded_)
    if (u.name == name) {
      renderer().set_body_visible(u.handle, true);
      return u.handle;
    }
  if (uploaded_.size() >= std::numeric_limits<std::uint8_t>::max())
    throw std::invalid_argument("the tracker's renderer takes at most 255 bodies (id images are 8 bit)");
  const auto id = static_cast<std::uint8_t>(uploaded_.size() + 1);
  uploaded_.push_back({name, renderer().add_body(mesh, id)});
  return uploaded_.back().handle;
}

std::uint8_t SceneRenderer::id(const std::string& body) const {
  for (std::size_t i = 0; i < uploaded_.size(); ++i)
    if (uploaded_[i].name == body) return static_cast<std::uint8_t>(i + 1);
  return 0;
}

void SceneRenderer::render(const std::vector<const Body*>& bodies, const std::vector<RenderRequest>& requests,
                           Renders& out) {
  out.clear();
  if (requests.empty()) return;
  renderer();
  hide_all();
  std::vector<Renderer::BodyHandle> handles;
  for (const Body* body : bodies) {
    handles.push_back(show(body->name, body->mesh));
    out.set_id(body->name, id(body->name));
  }
  for (const RenderRequest& request : requests) {
    // Each body in the requesting camera's frame, the camera at the origin: the same
    // product camera_T_reference · reference_T_body a cue computes for its own pose.
    for (std::size_t b = 0; b < bodies.size(); ++b)
      renderer_->set_body_pose(handles[b], request.camera_T_reference * bodies[b]->reference_T_body);
    FocusedRender render;
    RenderOutput images =
        renderer_->render_focused(request.intrinsics, Pose(), request.square.u_min, request.square.v_min,
                                  request.square.size, request.size, request.targets, &render.intrinsics);
    render.depth = std::move(images.depth);
    render.ids = std::move(images.ids);
    render.normals = std::move(images.normals);
    render.color = std::move(images.color);
    out.add(request, std::move(render));
  }
}

cv::Mat SceneRenderer::depth_of(const std::string& name, const Mesh& mesh, const Intrinsics& intrinsics,
                                const Pose& camera_T_body) {
  renderer();
  hide_all();
  renderer_->set_body_pose(show(name, mesh), camera_T_body);
  return renderer_->render(intrinsics, Pose(), kRenderDepth).depth;
}

}  // namespace icgp
