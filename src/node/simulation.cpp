#include "mass_aggregate_sim/node/simulation.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <utility>

#include "mass_aggregate_sim/node/input_limits.h"

namespace mass_aggregate_sim {
namespace node {
namespace {

using engine::GeneratorId;
using engine::ParticleId;
using engine::Real;
using engine::Result;
using engine::Status;
using engine::Vec3;

}  // namespace

Simulation::Simulation(const engine::World& scene, const SimulationLimits& limits,
                       JointNames joint_names)
    : scene_(scene),
      world_(scene),
      limits_(limits),
      scene_joint_names_(std::move(joint_names)),
      joint_names_(scene_joint_names_) {}

Result<ParticleId> Simulation::resolve(const ParticleRef& ref) const {
  return resolveParticle(world_, ref);
}

Result<std::vector<ParticleId>> Simulation::spawn(const std::vector<engine::ParticleSpec>& specs) {
  if (specs.empty()) return Status::error("no particles to spawn");
  const std::size_t now = world_.particles().size();
  if (specs.size() > limits_.max_particles || now + specs.size() > limits_.max_particles) {
    return Status::error("spawning " + std::to_string(specs.size()) + " particles would make " +
                         std::to_string(now + specs.size()) + ", over ~max_particles (" +
                         std::to_string(limits_.max_particles) + ")");
  }
  std::set<std::string> names;
  for (std::size_t i = 0; i < specs.size(); ++i) {
    const std::string where = "particles[" + std::to_string(i) + "]: ";
    Status valid = engine::validateSpec(specs[i]);
    if (valid) valid = checkParticleSpec(specs[i], limits_.world_frame);
    if (!valid) return Status::error(where + valid.message());
    const std::string& name = specs[i].name;
    if (name.empty()) continue;
    if (world_.particles().findByName(name) || world_.bodies().findByName(name) ||
        !names.insert(name).second) {
      return Status::error(where + "the name " + quoteInput(name) + " is already taken");
    }
  }
  std::vector<ParticleId> ids;
  ids.reserve(specs.size());
  for (const auto& spec : specs) ids.push_back(*world_.addParticle(spec));
  return ids;
}

Result<std::vector<ParticleId>> Simulation::remove(const std::vector<ParticleRef>& refs) {
  if (refs.empty()) return Status::error("no particles to remove");
  if (refs.size() > limits_.max_particles) {
    return Status::error("ids and names: " + std::to_string(refs.size()) +
                         " particles named, more than ~max_particles (" +
                         std::to_string(limits_.max_particles) + ")");
  }
  std::vector<ParticleId> ids;
  std::set<ParticleId> seen;
  for (const auto& ref : refs) {
    const auto id = resolve(ref);
    if (!id) return id.status();
    if (!seen.insert(*id).second) {
      return Status::error("particle " + std::to_string(id.value().packed()) + " is named twice");
    }
    ids.push_back(*id);
  }
  for (const ParticleId id : ids) {
    world_.removeParticle(id);
    sustained_.erase(std::remove_if(sustained_.begin(), sustained_.end(),
                                    [id](const SustainedForce& f) { return f.particle == id; }),
                     sustained_.end());
  }
  // Joints to a removed particle went with it.
  pruneJointNames(world_, joint_names_);
  return ids;
}

Status Simulation::setState(const ParticleRef& ref, const std::optional<Vec3>& position,
                            const std::optional<Vec3>& velocity) {
  if (!position && !velocity) return Status::error("neither position nor velocity to set");
  const auto id = resolve(ref);
  if (!id) return id.status();
  if (position) {
    const Status valid = checkPosition(*position, "position");
    if (!valid) return valid;
  }
  if (velocity) {
    const Status valid = checkVelocity(*velocity, "velocity");
    if (!valid) return valid;
  }
  const auto dense = *world_.particles().find(*id);
  if (velocity && world_.particles().inverseMasses()[dense] <= 0.0 && !velocity->isZero(0.0)) {
    return Status::error("particle " + std::to_string(id.value().packed()) +
                         " is immovable: its velocity stays zero");
  }
  if (position) world_.setPosition(*id, *position);
  if (velocity) world_.setVelocity(*id, *velocity);
  return Status::ok();
}

Result<std::uint64_t> Simulation::applyForce(const ForceRequest& request) {
  const auto id = resolve(request.particle);
  if (!id) return id.status();
  if (request.mode == ForceMode::kClear) {
    const std::size_t before = sustained_.size();
    sustained_.erase(std::remove_if(sustained_.begin(), sustained_.end(),
                                    [&](const SustainedForce& f) { return f.particle == *id; }),
                     sustained_.end());
    if (sustained_.size() == before) {
      return Status::error("particle " + std::to_string(id.value().packed()) +
                           " has no sustained force to clear");
    }
    return std::uint64_t{0};
  }
  const Status valid_force = checkVector(request.force, kMaxForce, "force", "N");
  if (!valid_force) return valid_force;
  if (request.mode == ForceMode::kOneStep) {
    world_.addForce(*id, request.force);
    return std::uint64_t{1};
  }
  const auto steps = sustainedSteps(request.mode, request.duration);
  if (!steps) return steps.status();
  sustained_.push_back(SustainedForce{*id, request.force, *steps});
  return static_cast<std::uint64_t>(std::max<std::int64_t>(*steps, 0));
}

Result<std::int64_t> Simulation::sustainedSteps(const ForceMode mode, const Real duration) const {
  if (sustainedForceCount() >= limits_.max_sustained_forces) {
    return Status::error("mode: already " + std::to_string(sustainedForceCount()) +
                         " sustained forces and wrenches, the limit (clear some first)");
  }
  if (mode != ForceMode::kDuration) return std::int64_t{-1};
  if (!std::isfinite(duration) || duration <= 0.0) {
    return Status::error("duration must be finite and > 0");
  }
  const Real count = std::round(duration / world_.config().dt);
  if (count > static_cast<Real>(limits_.max_steps_per_request) * 100.0) {
    return Status::error("duration is too long");
  }
  return std::max<std::int64_t>(1, static_cast<std::int64_t>(count));
}

Result<Vec3> Simulation::applyImpulse(const ParticleRef& ref, const Vec3& impulse) {
  const auto id = resolve(ref);
  if (!id) return id.status();
  if (!impulse.allFinite()) return Status::error("impulse: must be finite");
  const std::size_t dense = *world_.particles().find(*id);
  const Real inverse_mass = world_.particles().inverseMasses()[dense];
  if (inverse_mass > 0.0) {
    // The velocity it would give, checked before anything changes: v + J / m.
    const Vec3 after = world_.particles().velocities().col(dense) + impulse * inverse_mass;
    const Status valid = checkVelocity(after, "impulse: the resulting velocity");
    if (!valid) return valid;
  }
  const Status applied = world_.applyImpulse(*id, impulse);
  if (!applied) return applied;
  return Vec3(world_.particles().velocities().col(*world_.particles().find(*id)));
}

Status Simulation::checkLinkRoom(const std::size_t more) const {
  const std::size_t links =
      world_.generators().size() + world_.bodyGenerators().size() + world_.links().size();
  if (links + more > limits_.max_links) {
    return Status::error("already " + std::to_string(links) + " links and force generators, " +
                         (more > 1 ? std::to_string(more) + " more exceed " : std::string()) +
                         "~max_links (" + std::to_string(limits_.max_links) + ")");
  }
  return Status::ok();
}

Result<GeneratorId> Simulation::addLink(const LinkRequest& request) {
  const Status room = checkLinkRoom();
  if (!room) return room;
  return node::addLink(world_, request);
}

Result<GeneratorId> Simulation::addBodySpring(const BodySpringRequest& request) {
  const Status room = checkLinkRoom();
  if (!room) return room;
  return node::addBodySpring(world_, request);
}

Result<std::vector<GeneratorId>> Simulation::addForceFields(const ForceFieldRequest& request) {
  const Status room = checkLinkRoom(request.particles.size() + request.bodies.size());
  if (!room) return room;
  return node::addForceFields(world_, request);
}

Status Simulation::removeForceField(const GeneratorId id) {
  if (!isForceField(world_, id)) {
    return Status::error("no drag or buoyancy with id " + std::to_string(id));
  }
  return world_.removeGenerator(id);
}

Status Simulation::removeLink(const GeneratorId id) {
  if (!isLink(world_, id)) return Status::error("no link with id " + std::to_string(id));
  return world_.removeGenerator(id);
}

void Simulation::step() {
  for (auto& sustained : sustained_) {
    world_.addForce(sustained.particle, sustained.force);
    if (sustained.steps_left > 0) --sustained.steps_left;
  }
  sustained_.erase(std::remove_if(sustained_.begin(), sustained_.end(),
                                  [](const SustainedForce& f) { return f.steps_left == 0; }),
                   sustained_.end());
  applyWrenches();
  world_.step();
}

Status Simulation::stepMany(const std::uint32_t n) {
  if (n == 0) return Status::error("steps must be at least 1");
  if (n > limits_.max_steps_per_request) {
    return Status::error("steps must be at most " + std::to_string(limits_.max_steps_per_request));
  }
  for (std::uint32_t i = 0; i < n; ++i) step();
  return Status::ok();
}

void Simulation::reset() {
  world_ = scene_;
  sustained_.clear();
  wrenches_.clear();
  joint_names_ = scene_joint_names_;
  if (configured_) configure(*configured_);
}

PhysicsSettings Simulation::settings() const {
  return PhysicsSettings{world_.config(), world_.collisionSettings(), world_.bodySettings()};
}

Status Simulation::configure(const PhysicsSettings& settings) {
  const Status valid = engine::validateConfig(settings.config);
  if (!valid) return valid;
  const Status collisions = engine::validateCollisionSettings(settings.collisions);
  if (!collisions) return collisions;
  const Status bodies = engine::validateBodySettings(settings.bodies);
  if (!bodies) return bodies;
  world_.setConfig(settings.config);
  world_.setCollisionSettings(settings.collisions);
  world_.setBodySettings(settings.bodies);  // wakes every body only when they change
  if (settings.config.divergence_policy == engine::DivergencePolicy::kReset) {
    world_.setResetSnapshot();
  } else {
    world_.clearResetSnapshot();
  }
  configured_ = settings;
  return Status::ok();
}

}  // namespace node
}  // namespace mass_aggregate_sim
