// World: the requests on rigid bodies and joints, each validated before anything changes; every
// one wakes what it touches.
#include <algorithm>
#include <cmath>
#include <optional>
#include <type_traits>
#include <vector>

#include "engine/bodies/body_collision.h"
#include "engine/bodies/body_workspace.h"
#include "engine/bodies/contact_solver.h"
#include "engine/bodies/islands.h"
#include "engine/collision/narrowphase/any_shape.h"
#include "engine/joints/joint_ends.h"
#include "engine/solver/contact_workspace.h"
#include "mass_aggregate_sim/engine/bodies/mass_properties.h"
#include "mass_aggregate_sim/engine/world/world.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

Status checkSpec(const BodySpec& spec) {
  if (!spec.pose.position.allFinite()) return Status::error("pose position is not finite");
  if (!spec.pose.rotation.coeffs().allFinite() ||
      std::abs(spec.pose.rotation.norm() - 1.0) > 1e-6) {
    return Status::error("pose orientation must be a unit quaternion (|q| within 1e-6 of 1)");
  }
  if (!spec.linear_velocity.allFinite()) return Status::error("linear velocity is not finite");
  if (!spec.angular_velocity.allFinite()) return Status::error("angular velocity is not finite");
  for (const auto& [value, name] :
       {std::pair<Real, const char*>{spec.linear_damping, "linear damping"},
        {spec.angular_damping, "angular damping"}}) {
    if (!std::isfinite(value) || value < 0.0) {
      return Status::error(std::string(name) + " must be finite and >= 0");
    }
  }
  return Status::ok();
}

bool isAmong(const ShapeIndex s, const std::vector<ShapeIndex>& shapes) {
  return std::find(shapes.begin(), shapes.end(), s) != shapes.end();
}

// The dense bodies that touch (have a contact with) dense body `body`.
std::vector<std::size_t> whatTouches(const BodyStore& bodies, const BodyWorkspace& ws,
                                     const std::size_t body) {
  const std::vector<ShapeIndex>& shapes = bodies.shapesOf(body);
  std::vector<std::size_t> touching;
  for (const BodyContact& c : ws.contacts) {
    if (c.key.other != ContactOther::kShape) continue;
    const bool a = isAmong(c.key.shape, shapes);
    const bool b = isAmong(static_cast<ShapeIndex>(c.key.b), shapes);
    if (a == b) continue;
    const ShapeIndex other = a ? static_cast<ShapeIndex>(c.key.b) : c.key.shape;
    touching.push_back(bodies.denseIndexUnchecked(bodies.shapes()[other].body));
  }
  return touching;
}

}  // namespace

Result<BodyId> World::addBody(const BodySpec& spec) {
  const Status valid = checkSpec(spec);
  if (!valid) return valid;
  const Result<MassProperties> mass = computeMassProperties(spec.shapes, spec.mass);
  if (!mass) return mass.status();
  BodySpec normalised = spec;
  normalised.pose.rotation.normalize();
  return bodies_.add(normalised, *mass);
}

Status World::removeBody(const BodyId id) {
  const auto dense = bodies_.find(id);
  if (!dense) return Status::error("body: " + bodies_.describeInvalid(id));
  BodyWorkspace& ws = *body_ws_;
  removeBodyGeneratorsOf(id);
  // It, what rested on it and what its joints held (a fixed hub's spokes are islands apart)
  // wake, in one pass over the links that remain: its island without its joints is split only
  // between itself and the bodies they held.
  std::vector<std::size_t> woken = whatTouches(bodies_, ws, *dense);
  woken.push_back(*dense);
  joints_.forEach([&](auto& kind) {
    for (const auto& joint : kind) {
      if (joint.a.body != id && joint.b.body != id) continue;
      for (const JointEnd* end : {&joint.a, &joint.b}) {
        const auto held = end->isBody() ? bodies_.find(end->body) : std::nullopt;
        if (held) woken.push_back(*held);
      }
    }
    kind.erase(
        std::remove_if(kind.begin(), kind.end(),
                       [&](const auto& joint) { return joint.a.body == id || joint.b.body == id; }),
        kind.end());
  });
  wakeIslands(bodies_, ws, joints_, woken);
  // Its contacts go.
  const std::vector<ShapeIndex>& shapes = bodies_.shapesOf(*dense);
  const auto gone = [&](const BodyContact& c) {
    return isAmong(c.key.shape, shapes) || (c.key.other == ContactOther::kShape &&
                                            isAmong(static_cast<ShapeIndex>(c.key.b), shapes));
  };
  for (const BodyContact& c : ws.contacts) {
    if (gone(c)) ws.kept_masses.giveBack(c);
  }
  ws.contacts.erase(std::remove_if(ws.contacts.begin(), ws.contacts.end(), gone),
                    ws.contacts.end());
  removeBodyProxies(bodies_, *dense, ws);
  return bodies_.remove(id);
}

Result<std::size_t> World::bodyForRequest(const BodyId id) {
  const auto dense = bodies_.find(id);
  if (!dense) return Status::error("body: " + bodies_.describeInvalid(id));
  wakeIsland(bodies_, *body_ws_, joints_, *dense);
  return *dense;
}

Status World::setBodyPose(const BodyId id, const Transform& pose) {
  if (!pose.position.allFinite()) return Status::error("pose position is not finite");
  if (!pose.rotation.coeffs().allFinite() || std::abs(pose.rotation.norm() - 1.0) > 1e-6) {
    return Status::error("pose orientation must be a unit quaternion (|q| within 1e-6 of 1)");
  }
  const auto dense = bodyForRequest(id);
  if (!dense) return dense.status();
  const Transform mass_pose =
      Transform{pose.position, pose.rotation.normalized()} * bodies_.massFrame(*dense);
  bodies_.position(*dense) = mass_pose.position;
  bodies_.orientation(*dense) = mass_pose.rotation.normalized();
  bodies_.refreshWorldInertia(*dense);
  if (!bodies_.awake(*dense)) {
    // A fixed body, which no step moves: what rested on it and what it now overlaps wake here,
    // and its proxies follow at the next pair stage.
    BodyWorkspace& ws = *body_ws_;
    std::vector<std::size_t> woken = whatTouches(bodies_, ws, *dense);
    for (const ShapeIndex s : bodies_.shapesOf(*dense)) {
      const Aabb box = shapeBounds(bodies_.shapes()[s].geometry, Frame(bodies_.shapePose(s)))
                           .grown(body_settings_.speculative_distance);
      const std::vector<std::size_t> near = bodiesNear(bodies_, ws, box);
      woken.insert(woken.end(), near.begin(), near.end());
    }
    wakeIslands(bodies_, ws, joints_, woken);
    ws.posed.push_back(id);
  }
  return Status::ok();
}

Status World::setBodyVelocity(const BodyId id, const Vec3& linear, const Vec3& angular) {
  if (!linear.allFinite() || !angular.allFinite()) {
    return Status::error("velocity is not finite");
  }
  const auto dense = bodyForRequest(id);
  if (!dense) return dense.status();
  if (bodies_.type(*dense) == BodyType::kFixed && !(linear.isZero(0.0) && angular.isZero(0.0))) {
    return Status::error("body " + id.str() + " is fixed: its velocity stays zero");
  }
  bodies_.linearVelocity(*dense) = linear;
  bodies_.angularVelocity(*dense) = angular;
  return Status::ok();
}

Status World::addBodyForce(const BodyId id, const Vec3& force, const Vec3& point) {
  if (!force.allFinite()) return Status::error("force is not finite");
  if (!point.allFinite()) return Status::error("point is not finite");
  const auto dense = bodyForRequest(id);
  if (!dense) return dense.status();
  bodies_.force(*dense) += force;
  bodies_.torque(*dense) += (point - bodies_.position(*dense)).cross(force);
  return Status::ok();
}

Status World::addBodyTorque(const BodyId id, const Vec3& torque) {
  if (!torque.allFinite()) return Status::error("torque is not finite");
  const auto dense = bodyForRequest(id);
  if (!dense) return dense.status();
  bodies_.torque(*dense) += torque;
  return Status::ok();
}

Status World::applyBodyImpulse(const BodyId id, const Vec3& impulse, const Vec3& point,
                               const Vec3& angular_impulse) {
  if (!impulse.allFinite()) return Status::error("impulse is not finite");
  if (!point.allFinite()) return Status::error("point is not finite");
  if (!angular_impulse.allFinite()) return Status::error("angular impulse is not finite");
  const auto found = bodies_.find(id);
  if (found && !bodies_.dynamic(*found)) {
    return Status::error("body " + id.str() + " is not dynamic: an impulse cannot move it");
  }
  const auto dense = bodyForRequest(id);
  if (!dense) return dense.status();
  // dv = J / m, dw = I^-1 ((p - c) x J + L)
  bodies_.linearVelocity(*dense) += bodies_.inverseMass(*dense) * impulse;
  bodies_.refreshWorldInertia(*dense);
  bodies_.angularVelocity(*dense) +=
      bodies_.worldInverseInertia(*dense) *
      ((point - bodies_.position(*dense)).cross(impulse) + angular_impulse);
  return Status::ok();
}

Status World::wakeBody(const BodyId id) { return bodyForRequest(id).status(); }

Status World::setBodySettings(const BodySettings& settings) {
  const Status valid = validateBodySettings(settings);
  if (!valid) return valid;
  if (settings == body_settings_) return Status::ok();
  body_settings_ = settings;
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    if (bodies_.type(i) != BodyType::kFixed) bodies_.setAwake(i, true);
  }
  return Status::ok();
}

// When every body is fixed or asleep and none holds a particle, the bodies only lend the particle
// solver their surfaces (BodySurface) and the step need not take their substeps: a pile resting
// in a sleeping bin then costs what it does in a bin of colliders. Without the particle solver's
// contacts a particle meets a still body through body rows, which are solved at the bodies'
// substeps. The step after the last body stopped still takes them: its pile passes from the body
// rows to the particle solver at the substep it was solved at, and changes substep a step later,
// warm started (a pile changing both at once jolted: the grains of a bin that had just fallen
// asleep left that step at 5 to 11 cm/s and woke it again, each time).
bool World::bodiesMove(const bool reach) const {
  if (body_ws_->prepared) return true;
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    if (bodies_.awake(i) && bodies_.type(i) != BodyType::kFixed) return true;
  }
  if (!particles_.empty() && !contactsActive()) return true;
  if (reach) return true;
  bool holds_particle = false;
  joints_.forEach([&](const auto& kind) {
    for (const auto& joint : kind) {
      holds_particle = holds_particle || joint.a.isParticle() || joint.b.isParticle();
    }
  });
  return holds_particle;
}

std::size_t World::bodyIslandCount() const {
  if (bodies_.empty()) return 0;
  return countIslands(bodies_, *body_ws_, joints_);
}

std::vector<BodyContactReport> World::bodyContacts() const {
  std::vector<BodyContactReport> out;
  if (bodies_.empty()) return out;
  // The kept impulses of the body rows are over the body solver's substep; the report's over
  // the last step's.
  const Real substep = config_.dt / static_cast<Real>(substeps_used_);
  const Real kept_to_substep = body_substep_ > 0.0 ? substep / body_substep_ : 1.0;
  for (const BodyContact& c : body_ws_->contacts) {
    if (c.manifold.count == 0) continue;
    BodyContactReport r;
    r.body = bodies_.shapes()[c.key.shape].body;
    r.normal = c.manifold.normal;
    switch (c.key.other) {
      case ContactOther::kShape:
        r.other = BodyContactReport::Other::kBody;
        r.other_body = bodies_.shapes()[static_cast<ShapeIndex>(c.key.b)].body;
        break;
      case ContactOther::kCollider:
        r.other = BodyContactReport::Other::kCollider;
        r.collider = static_cast<ColliderId>(c.key.b);
        break;
      case ContactOther::kParticle:
        r.other = BodyContactReport::Other::kParticle;
        r.particle = ParticleId::fromPacked(c.key.b);
        break;
    }
    // A particle on a still body was the particle solver's this step (BodySurface): its
    // impulses are there.
    Real normal = 0.0;
    Vec3 friction = Vec3::Zero();
    if (c.key.other == ContactOther::kParticle &&
        contacts_->resolver.lastImpulses(stillSurfaceContactKey(r.particle.index, c.key.shape),
                                         normal, friction)) {
      BodyContactReport::Point p;
      p.position = c.manifold.points[0].point;
      p.separation = c.manifold.points[0].separation;
      p.normal_impulse = normal;
      p.friction_impulse = friction;
      r.points.push_back(p);
      out.push_back(std::move(r));
      continue;
    }
    // The manifold's friction and twist as point impulses, the least-norm split with the same
    // sum and the same torque about the centre: f_k = F / n + tau (n x d_k) / sum |d_i|^2.
    const ContactPatch patch = contactPatch(c.manifold);
    Real spread = 0.0;
    for (int k = 0; k < c.manifold.count; ++k) spread += patch.offsets[k].squaredNorm();
    for (int k = 0; k < c.manifold.count; ++k) {
      BodyContactReport::Point p;
      p.position = c.manifold.points[k].point;
      p.separation = c.manifold.points[k].separation;
      p.normal_impulse = c.normal_impulses[k];
      p.friction_impulse = c.friction_impulse / static_cast<Real>(c.manifold.count);
      if (spread > 0.0) {
        p.friction_impulse += c.twist_impulse / spread * c.manifold.normal.cross(patch.offsets[k]);
      }
      if (kept_to_substep != 1.0) {
        p.normal_impulse *= kept_to_substep;
        p.friction_impulse *= kept_to_substep;
      }
      r.points.push_back(p);
    }
    out.push_back(std::move(r));
  }
  return out;
}

namespace {

// The bodies with a shape within reach of the probe shape placed at frame.
template <typename Probe>
std::vector<BodyId> bodiesOverlapping(const BodyStore& bodies, const Probe& probe,
                                      const Frame& frame) {
  std::vector<BodyId> found;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    for (const ShapeIndex s : bodies.shapesOf(i)) {
      const Manifold m = collideAnyWith(bodies.shapes()[s].geometry, Frame(bodies.shapePose(s)),
                                        probe, frame, 0.0);
      bool touches = false;
      for (int k = 0; k < m.count; ++k) touches = touches || m.points[k].separation <= 0.0;
      if (touches) {
        found.push_back(bodies.idAt(i));
        break;
      }
    }
  }
  return found;
}

}  // namespace

std::vector<BodyId> World::bodiesOverlappingSphere(const Vec3& center, const Real radius) const {
  if (!center.allFinite() || !std::isfinite(radius) || radius < 0.0) return {};
  return bodiesOverlapping(bodies_, SphereShape{radius}, Frame(center, Mat3::Identity()));
}

std::vector<BodyId> World::bodiesOverlappingBox(const Vec3& center, const Vec3& half_extents,
                                                const Quat& orientation) const {
  if (!center.allFinite() || !half_extents.allFinite() || (half_extents.array() <= 0.0).any() ||
      !orientation.coeffs().allFinite() || orientation.norm() < 1e-9) {
    return {};
  }
  return bodiesOverlapping(bodies_, BoxShape{half_extents},
                           Frame(center, orientation.normalized().toRotationMatrix()));
}

// --- joints ---

Status World::checkJointEnds(const JointEnd& a, const JointEnd& b, const bool turns) const {
  const JointScene scene{bodies_, particles_};
  Status valid = checkJointEnd(a, scene, "a", turns);
  if (valid) valid = checkJointEnd(b, scene, "b", turns);
  if (!valid) return valid;
  if (!a.isBody() && !b.isBody()) {
    return Status::error(
        "a joint needs a body at one end at least (particles alone are joined by links)");
  }
  if (a.isBody() && b.isBody() && a.body == b.body) {
    return Status::error("a joint's ends are on the same body");
  }
  const auto still = [&](const JointEnd& end) {
    if (end.isBody())
      return bodies_.type(bodies_.denseIndexUnchecked(end.body)) == BodyType::kFixed;
    return !end.isParticle();
  };
  if (still(a) && still(b)) return Status::error("neither end of the joint can move");
  return Status::ok();
}

void World::wakeJointEnds(const JointEnd& a, const JointEnd& b) {
  std::vector<BodyId> ends;
  for (const JointEnd* end : {&a, &b}) {
    if (end->isBody()) ends.push_back(end->body);
  }
  wakeBodies(ends);
}

void World::wakeBodies(const std::vector<BodyId>& bodies) {
  std::vector<std::size_t> seeds;
  for (const BodyId body : bodies) {
    const auto dense = bodies_.find(body);
    if (dense) seeds.push_back(*dense);
  }
  wakeIslands(bodies_, *body_ws_, joints_, seeds);
}

Status World::removeJoint(const JointId id) {
  bool removed = false;
  joints_.forEach([&](auto& kind) {
    const auto it =
        std::find_if(kind.begin(), kind.end(), [id](const auto& joint) { return joint.id == id; });
    if (it == kind.end()) return;
    wakeJointEnds(it->a, it->b);
    kind.erase(it);
    removed = true;
  });
  if (!removed) return Status::error("no joint with id " + std::to_string(id));
  return Status::ok();
}

std::vector<JointReaction> World::jointReactions() const {
  std::vector<JointReaction> out;
  const Real h =
      body_substep_ > 0.0 ? body_substep_ : config_.dt / static_cast<Real>(substeps_used_);
  joints_.forEach([&](const auto& kind) {
    using Kind = typename std::decay_t<decltype(kind)>::value_type;
    for (const auto& joint : kind) out.push_back(JointKind<Kind>::reaction(joint, h));
  });
  std::sort(out.begin(), out.end(),
            [](const JointReaction& x, const JointReaction& y) { return x.id < y.id; });
  return out;
}

Status World::setHingeMotor(const JointId id, const bool enabled, const Real speed,
                            const Real max_torque) {
  if (!std::isfinite(speed)) return Status::error("motor speed is not finite");
  if (!std::isfinite(max_torque) || max_torque < 0.0) {
    return Status::error("motor max torque must be finite and >= 0");
  }
  auto& hinges = joints_.of<HingeJoint>();
  const auto it =
      std::find_if(hinges.begin(), hinges.end(), [id](const HingeJoint& j) { return j.id == id; });
  if (it == hinges.end()) return Status::error("no hinge joint with id " + std::to_string(id));
  it->motor = enabled;
  it->motor_speed = speed;
  it->max_motor_torque = max_torque;
  wakeJointEnds(it->a, it->b);
  return Status::ok();
}

}  // namespace engine
}  // namespace mass_aggregate_sim
