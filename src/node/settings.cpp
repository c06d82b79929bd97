#include "mass_aggregate_sim/node/settings.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <tuple>

#include "mass_aggregate_sim/engine/integrators/integrator.h"
#include "mass_aggregate_sim/node/input_limits.h"

namespace mass_aggregate_sim {
namespace node {
namespace {

using engine::Real;
using engine::Result;
using engine::Status;

constexpr double kMaxRate = 100000.0;  // Hz, as a scene's rate
constexpr double kMaxPublishRate = 1000.0;

std::string exact(const double value) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}

std::string readable(const double value) {
  char text[40];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

const char* boolText(const bool value) { return value ? "true" : "false"; }

// A count in [low, high], refused as "name: must be in [low, high], got value".
Status checkCount(const int value, const int low, const int high, const char* name) {
  if (value >= low && value <= high) return Status::ok();
  return Status::error(std::string(name) + ": must be in [" + std::to_string(low) + ", " +
                       std::to_string(high) + "], got " + std::to_string(value));
}

class Fnv {
 public:
  void add(const void* data, const std::size_t size) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < size; ++i) {
      hash_ ^= bytes[i];
      hash_ *= 1099511628211ull;
    }
  }
  template <typename T>
  void add(const T& value) {
    add(&value, sizeof value);
  }
  std::uint64_t value() const { return hash_; }

 private:
  std::uint64_t hash_ = 14695981039346656037ull;
};

}  // namespace

std::optional<engine::DivergencePolicy> parseDivergencePolicy(const std::string& name) {
  for (const auto policy : {engine::DivergencePolicy::kContinue, engine::DivergencePolicy::kPause,
                            engine::DivergencePolicy::kReset}) {
    if (name == engine::divergencePolicyName(policy)) return policy;
  }
  return std::nullopt;
}

LiveSettings liveSettingsOf(const PhysicsSettings& physics, const double publish_rate,
                            const bool paused) {
  LiveSettings s;
  s.rate = 1.0 / physics.config.dt;
  s.substeps = physics.config.substeps;
  s.integrator = engine::integratorName(physics.config.integrator);
  s.gravity = physics.config.gravity;
  s.auto_substep = physics.config.auto_substep;
  s.divergence_policy = engine::divergencePolicyName(physics.config.divergence_policy);
  s.particle_collisions = physics.collisions.particle_collisions;
  s.continuous = physics.collisions.continuous;
  s.particle_restitution = physics.collisions.particle_restitution;
  s.particle_friction = physics.collisions.particle_friction;
  s.max_iterations = physics.collisions.max_iterations;
  s.penetration_slop = physics.collisions.penetration_slop;
  s.body_substeps = physics.bodies.substeps;
  s.body_iterations = physics.bodies.iterations;
  s.body_relax_iterations = physics.bodies.relax_iterations;
  s.body_sleep = physics.bodies.sleep;
  s.publish_rate = publish_rate;
  s.paused = paused;
  return s;
}

Result<PhysicsSettings> applyLiveSettings(const LiveSettings& wanted, const PhysicsSettings& base) {
  if (!(wanted.rate > 0.0 && wanted.rate <= kMaxRate)) {
    return Status::error("rate: must be in (0, " + readable(kMaxRate) + "] Hz, got " +
                         readable(wanted.rate));
  }
  const Status substeps = checkCount(wanted.substeps, 1, 1000, "substeps");
  if (!substeps) return substeps;
  const auto integrator = engine::parseIntegrator(wanted.integrator);
  if (!integrator) {
    return Status::error("integrator: unknown integrator " + quoteInput(wanted.integrator) +
                         " (known: " + engine::integratorNames() + ")");
  }
  const Status gravity = checkVector(wanted.gravity, kMaxAcceleration, "gravity", "m/s^2");
  if (!gravity) return gravity;
  const auto policy = parseDivergencePolicy(wanted.divergence_policy);
  if (!policy) {
    return Status::error("divergence_policy: unknown policy " +
                         quoteInput(wanted.divergence_policy) + " (known: continue, pause, reset)");
  }
  if (!(wanted.publish_rate > 0.0 && wanted.publish_rate <= kMaxPublishRate)) {
    return Status::error("publish_rate: must be in (0, " + readable(kMaxPublishRate) +
                         "] Hz, got " + readable(wanted.publish_rate));
  }
  PhysicsSettings out = base;
  engine::WorldConfig& c = out.config;
  // dt exactly as a scene's rate gives it, so a node started with ~rate R and one set to R live
  // step alike.
  c.dt = 1.0 / wanted.rate;
  c.max_frame_time = std::max(base.config.max_frame_time, c.dt);
  c.substeps = wanted.substeps;
  c.integrator = *integrator;
  c.gravity = wanted.gravity;
  c.auto_substep = wanted.auto_substep;
  c.divergence_policy = *policy;
  const Status config = engine::validateConfig(c);
  if (!config) return config;
  engine::CollisionSettings& k = out.collisions;
  k.particle_collisions = wanted.particle_collisions;
  k.continuous = wanted.continuous;
  for (const auto& [name, value, high, unit] :
       {std::tuple<const char*, double, double, const char*>{"particle_restitution",
                                                             wanted.particle_restitution, 1.0, ""},
        {"particle_friction", wanted.particle_friction, 100.0, ""},
        {"penetration_slop", wanted.penetration_slop, 1.0, "m"}}) {
    const Status checked = checkNonNegative(value, high, name, unit);
    if (!checked) return checked;
  }
  const Status iterations = checkCount(wanted.max_iterations, 1, 10000, "max_iterations");
  if (!iterations) return iterations;
  k.particle_restitution = wanted.particle_restitution;
  k.particle_friction = wanted.particle_friction;
  k.max_iterations = wanted.max_iterations;
  k.penetration_slop = wanted.penetration_slop;
  const Status collisions = engine::validateCollisionSettings(k);
  if (!collisions) return collisions;
  for (const auto& [name, value, low] :
       {std::tuple<const char*, int, int>{"body_substeps", wanted.body_substeps, 1},
        {"body_iterations", wanted.body_iterations, 1},
        {"body_relax_iterations", wanted.body_relax_iterations, 0}}) {
    const Status checked = checkCount(value, low, 64, name);
    if (!checked) return checked;
  }
  engine::BodySettings& b = out.bodies;
  b.substeps = wanted.body_substeps;
  b.iterations = wanted.body_iterations;
  b.relax_iterations = wanted.body_relax_iterations;
  b.sleep = wanted.body_sleep;
  const Status bodies = engine::validateBodySettings(b);
  if (!bodies) return bodies;
  return out;
}

std::string describeConfiguration(const PhysicsSettings& physics) {
  const engine::WorldConfig& c = physics.config;
  const engine::CollisionSettings& k = physics.collisions;
  std::ostringstream out;
  out << "integrator: " << engine::integratorName(c.integrator) << "\n"
      << "rate: " << exact(1.0 / c.dt) << "\n"
      << "dt: " << exact(c.dt) << "\n"
      << "substeps: " << c.substeps << "\n"
      << "gravity: [" << exact(c.gravity.x()) << ", " << exact(c.gravity.y()) << ", "
      << exact(c.gravity.z()) << "]\n"
      << "auto_substep: " << boolText(c.auto_substep) << "\n"
      << "divergence_policy: " << engine::divergencePolicyName(c.divergence_policy) << "\n"
      << "energy_growth_limit: " << exact(c.energy_growth_limit) << "\n"
      << "particle_collisions: " << boolText(k.particle_collisions) << "\n"
      << "broadphase: " << engine::broadphaseName(k.broadphase) << "\n"
      << "continuous: " << boolText(k.continuous) << "\n"
      << "particle_restitution: " << exact(k.particle_restitution) << "\n"
      << "particle_friction: " << exact(k.particle_friction) << "\n"
      << "max_iterations: " << k.max_iterations << "\n"
      << "penetration_slop: " << exact(k.penetration_slop) << "\n"
      << "collide_linked: " << boolText(k.collide_linked) << "\n"
      << "rod_tolerance: " << exact(k.rod_tolerance) << "\n"
      << "velocity_tolerance: " << exact(k.velocity_tolerance) << "\n"
      << "max_contacts: " << k.max_contacts << "\n"
      << "runaway_speed: " << exact(k.runaway_speed) << "\n";
  const engine::BodySettings& b = physics.bodies;
  out << "body_substeps: " << b.substeps << "\n"
      << "body_iterations: " << b.iterations << "\n"
      << "body_relax_iterations: " << b.relax_iterations << "\n"
      << "body_contact_hertz: " << exact(b.contact_hertz) << "\n"
      << "body_contact_damping_ratio: " << exact(b.contact_damping_ratio) << "\n"
      << "body_joint_hertz: " << exact(b.joint_hertz) << "\n"
      << "body_joint_damping_ratio: " << exact(b.joint_damping_ratio) << "\n"
      << "body_max_push_speed: " << exact(b.max_push_speed) << "\n"
      << "body_speculative_distance: " << exact(b.speculative_distance) << "\n"
      << "body_linear_slop: " << exact(b.linear_slop) << "\n"
      << "body_min_twist_lever: " << exact(b.min_twist_lever) << "\n"
      << "body_restitution_threshold: " << exact(b.restitution_threshold) << "\n"
      << "body_sleep: " << boolText(b.sleep) << "\n"
      << "body_sleep_speed: " << exact(b.sleep_speed) << "\n"
      << "body_time_to_sleep: " << exact(b.time_to_sleep) << "\n"
      << "body_continuous: " << boolText(b.continuous) << "\n"
      << "body_gyroscopic: " << boolText(b.gyroscopic) << "\n"
      << "body_runaway_speed: " << exact(b.runaway_speed) << "\n";
  return out.str();
}

std::uint64_t sceneHash(const engine::World& scene) {
  Fnv hash;
  hash.add(scene.stateHash());
  const engine::ParticleStore& particles = scene.particles();
  for (std::size_t i = 0; i < particles.size(); ++i) {
    hash.add(particles.inverseMasses()[i]);
    hash.add(particles.radii()[i]);
    hash.add(particles.dampings()[i]);
  }
  // How many of each kind: every kind's list, in its order.
  const auto add_counts = [&](const auto& kinds) {
    kinds.forEach([&](const auto& kind) { hash.add(static_cast<std::uint64_t>(kind.size())); });
  };
  add_counts(scene.generators());
  add_counts(scene.links());
  add_counts(scene.colliders());
  // Bodies and joints, when there are any.
  const engine::BodyStore& bodies = scene.bodies();
  if (!bodies.empty() || !scene.joints().empty()) {
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      hash.add(static_cast<std::uint8_t>(bodies.type(i)));
      hash.add(bodies.mass(i));
      hash.add(bodies.principalInertia(i).x());
      hash.add(bodies.principalInertia(i).y());
      hash.add(bodies.principalInertia(i).z());
      hash.add(static_cast<std::uint64_t>(bodies.shapesOf(i).size()));
      for (const engine::ShapeIndex s : bodies.shapesOf(i)) {
        const engine::BodyShape& shape = bodies.shapes()[s];
        hash.add(static_cast<std::uint64_t>(shape.geometry.index()));
        hash.add(shape.material.friction);
        hash.add(shape.material.restitution);
      }
    }
    add_counts(scene.joints());
  }
  const std::string configuration = describeConfiguration(
      PhysicsSettings{scene.config(), scene.collisionSettings(), scene.bodySettings()});
  hash.add(configuration.data(), configuration.size());
  return hash.value();
}

}  // namespace node
}  // namespace mass_aggregate_sim
