#include "mass_aggregate_sim/node/body_snapshot.h"

#include <algorithm>

namespace mass_aggregate_sim {
namespace node {
namespace {

using engine::Vec3;

Vec3 endPoint(const engine::World& world, const engine::JointEnd& end) {
  if (end.isBody()) {
    return world.bodies().pose(*world.bodies().find(end.body)).apply(end.point);
  }
  if (end.isParticle()) {
    const engine::ParticleStore& p = world.particles();
    return p.positions().col(*p.find(end.particle));
  }
  return end.point;
}

engine::Quat endOrientation(const engine::World& world, const engine::JointEnd& end) {
  if (!end.isBody()) return engine::Quat::Identity();
  return world.bodies().orientation(*world.bodies().find(end.body));
}

Vec3 endAngularVelocity(const engine::World& world, const engine::JointEnd& end) {
  if (!end.isBody()) return Vec3::Zero();
  return world.bodies().angularVelocity(*world.bodies().find(end.body));
}

void takeJoints(const engine::World& world, const JointNames& names, BodySnapshot& out) {
  out.joints.clear();
  out.hinges.clear();
  out.joint_count = world.joints().size();
  const engine::BodyStore& bodies = world.bodies();
  world.joints().forEach([&](const auto& kind) {
    for (const auto& joint : kind) {
      JointView view;
      view.anchor_a = endPoint(world, joint.a);
      view.anchor_b = endPoint(world, joint.b);
      view.body_a = joint.a.isBody();
      view.body_b = joint.b.isBody();
      if (view.body_a) view.centre_a = bodies.position(*bodies.find(joint.a.body));
      if (view.body_b) view.centre_b = bodies.position(*bodies.find(joint.b.body));
      out.joints.push_back(view);
    }
  });
  const auto& hinges = world.joints().of<engine::HingeJoint>();
  if (hinges.empty()) return;
  // World::jointReactions is sorted by id.
  const std::vector<engine::JointReaction> reactions = world.jointReactions();
  for (const engine::HingeJoint& hinge : hinges) {
    const engine::Quat q_a = endOrientation(world, hinge.a);
    const engine::Quat q_b = endOrientation(world, hinge.b);
    const Vec3 axis = q_a * hinge.axis_a;
    HingeState state;
    state.name = jointName(names, hinge.id);
    state.position = engine::JointKind<engine::HingeJoint>::angle(hinge, q_a, q_b);
    state.velocity =
        (endAngularVelocity(world, hinge.b) - endAngularVelocity(world, hinge.a)).dot(axis);
    const auto it = std::lower_bound(
        reactions.begin(), reactions.end(), hinge.id,
        [](const engine::JointReaction& r, const engine::JointId id) { return r.id < id; });
    if (it != reactions.end() && it->id == hinge.id) state.effort = it->torque.dot(axis);
    out.hinges.push_back(state);
  }
}

}  // namespace

void takeBodySnapshot(const engine::World& world, const JointNames& names, const bool contacts,
                      BodySnapshot& out) {
  const engine::BodyStore& bodies = world.bodies();
  const std::size_t n = bodies.size();
  out.ids.resize(n);
  out.names.resize(n);
  out.types.resize(n);
  out.poses.resize(n);
  out.twists.resize(n);
  out.sleeping.resize(n);
  out.masses.resize(n);
  out.shapes.clear();
  out.named = 0;
  out.sleeping_count = 0;
  for (std::size_t i = 0; i < n; ++i) {
    out.ids[i] = bodies.idAt(i).packed();
    if (out.names[i] != bodies.name(i)) out.names[i] = bodies.name(i);
    if (!out.names[i].empty()) ++out.named;
    out.types[i] = bodies.type(i);
    out.poses[i] = bodies.pose(i);
    out.twists[i] = bodyTwist(bodies, i);
    // Fixed bodies never move and are never awake: only a movable body sleeps.
    const bool sleeping = bodies.type(i) != engine::BodyType::kFixed && !bodies.awake(i);
    out.sleeping[i] = sleeping ? 1 : 0;
    if (sleeping) ++out.sleeping_count;
    out.masses[i] = bodies.mass(i);
    const std::vector<engine::ShapeIndex>& own = bodies.shapesOf(i);
    for (std::size_t k = 0; k < own.size(); ++k) {
      out.shapes.push_back(ShapeView{i, static_cast<std::uint32_t>(k),
                                     bodies.shapes()[own[k]].geometry, bodies.shapePose(own[k])});
    }
  }
  takeJoints(world, names, out);
  out.substep = world.config().dt / static_cast<double>(std::max(1, world.substepsUsed()));
  out.contacts.clear();
  if (n == 0) {
    out.islands = 0;
    out.contact_count = 0;
    return;
  }
  std::vector<engine::BodyContactReport> reports = world.bodyContacts();
  out.islands = world.bodyIslandCount();
  out.contact_count = reports.size();
  if (contacts) out.contacts = std::move(reports);
}

}  // namespace node
}  // namespace mass_aggregate_sim
