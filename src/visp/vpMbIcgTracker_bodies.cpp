// SPDX-License-Identifier: GPL-2.0-or-later
// vpMbIcgTracker: icgp's extension for several bodies. The object (cMo) stays ViSP's one
// reference pose; further bodies, links and occluders are entries of the configuration's
// `bodies:` list, tracked in the same frames by the same cues.
#include "icgp/io/yaml_reader.h"
#include "icgp/visp/conversions.h"
#include "vpMbIcgTracker_impl.h"

using icgp::visp_detail::guarded;

namespace {

const icgp::BodyConfig* find_body(const icgp::TrackerConfig& config, const std::string& name) {
  for (const icgp::BodyConfig& body : config.bodies)
    if (body.name == name) return &body;
  return nullptr;
}

}  // namespace

const std::string& vpMbIcgTracker::getReferenceBodyName() {
  static const std::string name = Impl::kBody;
  return name;
}

void vpMbIcgTracker::addBody(const std::string& name, const std::string& modelFile) {
  guarded("addBody", [&] { add_body_config({name, modelFile, 1.0, false, std::nullopt}); });
}

void vpMbIcgTracker::addBody(const std::string& name, const std::string& modelFile, const icgp::Joint& joint) {
  guarded("addBody", [&] {
    icgp::Joint checked = joint;
    icgp::validate(checked, name);
    add_body_config({name, modelFile, 1.0, false, checked});
  });
}

void vpMbIcgTracker::addOccluder(const std::string& name, const std::string& modelFile) {
  guarded("addOccluder", [&] { add_body_config({name, modelFile, 1.0, true, std::nullopt}); });
}

void vpMbIcgTracker::add_body_config(icgp::BodyConfig body) {
  Impl& d = *impl_;
  std::vector<icgp::BodyConfig> bodies = d.config.bodies;
  bodies.push_back(std::move(body));
  icgp::in_tree_order(bodies, Impl::kBody);  // names, parents and cycles, before anything changes
  d.config.bodies = std::move(bodies);
  d.tracker_changed();
}

std::vector<std::string> vpMbIcgTracker::getBodyNames() const {
  std::vector<std::string> names;
  for (const icgp::BodyConfig& body : impl_->config.bodies) names.push_back(body.name);
  return names;
}

const icgp::BodyConfig& vpMbIcgTracker::body_config(const std::string& name, const std::string& call) const {
  if (const icgp::BodyConfig* body = find_body(impl_->config, name)) return *body;
  std::vector<std::string> names = {Impl::kBody};
  for (const icgp::BodyConfig& body : impl_->config.bodies) names.push_back(body.name);
  throw vpException(vpException::badValue, "vpMbIcgTracker::" + call + ": no body is named '" + name +
                                               "' (the bodies are " + icgp::yaml::join(names) + ")");
}

void vpMbIcgTracker::setBodyPose(const std::string& name, const vpHomogeneousMatrix& cMb) {
  if (name == Impl::kBody) {
    m_cMo = cMb;
    return;
  }
  const icgp::BodyConfig& body = body_config(name, "setBodyPose");
  if (body.joint)
    throw vpException(vpException::badValue, "vpMbIcgTracker::setBodyPose: body '" + name +
                                                 "' is a link: its pose follows its joint (setJointValues)");
  Impl& d = *impl_;
  d.body_poses[name] = icgp::to_pose(cMb);
  if (!d.tracker) return;
  d.tracker->body(name).reference_T_body = d.body_poses[name];
  // A tracked body moved by the program restarts the cues, as ViSP's setPose() does.
  if (!body.occluder) d.start_pending = true;
}

vpHomogeneousMatrix vpMbIcgTracker::getBodyPose(const std::string& name) const {
  if (name == Impl::kBody) return m_cMo;
  body_config(name, "getBodyPose");
  const Impl& d = *impl_;
  if (d.tracker) return icgp::to_homogeneous_matrix(d.tracker->body(name).reference_T_body);
  const auto it = d.body_poses.find(name);
  return it == d.body_poses.end() ? vpHomogeneousMatrix() : icgp::to_homogeneous_matrix(it->second);
}

bool vpMbIcgTracker::isBodyTracked(const std::string& name) const {
  if (name == Impl::kBody) return impl_->tracker && impl_->quality >= impl_->config.tracker.quality_threshold;
  body_config(name, "isBodyTracked");
  const auto it = impl_->body_results.find(name);
  return it != impl_->body_results.end() && it->second.tracked;
}

double vpMbIcgTracker::getBodyTrackingQuality(const std::string& name) const {
  if (name == Impl::kBody) return impl_->quality;
  body_config(name, "getBodyTrackingQuality");
  const auto it = impl_->body_results.find(name);
  return it == impl_->body_results.end() ? 0.0 : it->second.quality;
}

std::vector<double> vpMbIcgTracker::getJointValues(const std::string& name) const {
  const icgp::BodyConfig& body = body_config(name, "getJointValues");
  const Impl& d = *impl_;
  if (d.tracker && body.joint) return d.tracker->joint_values(name);
  const auto it = d.joint_values.find(name);
  return it == d.joint_values.end() ? std::vector<double>() : it->second;
}

void vpMbIcgTracker::setJointValues(const std::string& name, const std::vector<double>& values) {
  const icgp::BodyConfig& body = body_config(name, "setJointValues");
  if (!body.joint)
    throw vpException(vpException::badValue, "vpMbIcgTracker::setJointValues: body '" + name + "' has no joint");
  if (static_cast<int>(values.size()) != body.joint->size())
    throw vpException(vpException::badValue, "vpMbIcgTracker::setJointValues: body '" + name + "': its joint has " +
                                                 std::to_string(body.joint->size()) + " values, got " +
                                                 std::to_string(values.size()));
  Impl& d = *impl_;
  d.joint_values[name] = body.joint->clamped(values);
  if (d.tracker) {
    d.tracker->set_joint_values(name, values);
    d.start_pending = true;
  }
}
