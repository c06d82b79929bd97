#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "mass_aggregate_sim/engine/world/world.h"
#include "mass_aggregate_sim/node/links.h"
#include "mass_aggregate_sim/node/settings.h"

namespace mass_aggregate_sim {
namespace node {

enum class ForceMode { kOneStep, kDuration, kUntilCleared, kClear };

struct ForceRequest {
  ParticleRef particle;
  engine::Vec3 force = engine::Vec3::Zero();
  ForceMode mode = ForceMode::kOneStep;
  engine::Real duration = 0.0;  // s, for kDuration
};

struct SimulationLimits {
  std::size_t max_particles = 20000;
  std::uint32_t max_steps_per_request = 100000;
  // Force generators and links together (springs, bungees, cables, rods, drag, buoyancy).
  std::size_t max_links = 100000;
  // Forces kept across steps (DURATION and UNTIL_CLEARED).
  std::size_t max_sustained_forces = 10000;
  // The node's world frame: no particle may take its name or a collider frame's (tf would clash).
  std::string world_frame = "world";
};

// The world as the node drives it, without ROS: the loaded scene (kept for reset), requests that
// may touch it (each validated in full before anything changes), and the forces that last longer
// than one step. Every call is made from the one thread that owns the world.
class Simulation {
 public:
  Simulation(const engine::World& scene, const SimulationLimits& limits);

  const engine::World& world() const { return world_; }
  const SimulationLimits& limits() const { return limits_; }

  // All or nothing: every spec is checked (values, unique names, the particle limit) first.
  engine::Result<std::vector<engine::ParticleId>> spawn(
      const std::vector<engine::ParticleSpec>& specs);
  // All or nothing; returns the ids removed.
  engine::Result<std::vector<engine::ParticleId>> remove(const std::vector<ParticleRef>& refs);
  engine::Status setState(const ParticleRef& ref, const std::optional<engine::Vec3>& position,
                          const std::optional<engine::Vec3>& velocity);
  // Returns the number of steps the force will act (0 for until-cleared and clear).
  engine::Result<std::uint64_t> applyForce(const ForceRequest& request);
  // dv = J / m; returns the velocity right after.
  engine::Result<engine::Vec3> applyImpulse(const ParticleRef& ref, const engine::Vec3& impulse);
  engine::Result<engine::GeneratorId> addLink(const LinkRequest& request);
  engine::Status removeLink(engine::GeneratorId id);

  // One fixed step: sustained forces are added, then the world steps.
  void step();
  // n steps at once (the node allows it only while paused).
  engine::Status stepMany(std::uint32_t n);
  // Back to the loaded scene; sustained forces are dropped. Settings changed by configure() stay.
  void reset();

  PhysicsSettings settings() const;
  // New physics settings, from now on and across reset(). A divergence policy of reset keeps a
  // snapshot of the world as it is now (and at each reset()) to go back to.
  engine::Status configure(const PhysicsSettings& settings);

  engine::Result<engine::ParticleId> resolve(const ParticleRef& ref) const;
  std::size_t sustainedForceCount() const { return sustained_.size(); }

 private:
  struct SustainedForce {
    engine::ParticleId particle;
    engine::Vec3 force;
    std::int64_t steps_left;  // < 0: until cleared
  };

  engine::World scene_;
  engine::World world_;
  SimulationLimits limits_;
  std::vector<SustainedForce> sustained_;
  std::optional<PhysicsSettings> configured_;
};

}  // namespace node
}  // namespace mass_aggregate_sim
