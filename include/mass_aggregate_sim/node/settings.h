#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "mass_aggregate_sim/engine/collision/collision_settings.h"
#include "mass_aggregate_sim/engine/world/stability.h"
#include "mass_aggregate_sim/engine/world/world.h"
#include "mass_aggregate_sim/engine/world/world_config.h"

namespace mass_aggregate_sim {
namespace node {

// What a user may change while the node runs (dynamic_reconfigure, cfg/Sim.cfg), in the units and
// names of the parameters.
struct LiveSettings {
  double rate = 60.0;  // Hz: dt = 1 / rate
  int substeps = 1;
  std::string integrator = "semi_implicit_euler";
  engine::Vec3 gravity = engine::Vec3(0.0, 0.0, -9.81);  // m/s^2
  bool auto_substep = false;
  std::string divergence_policy = "continue";
  bool particle_collisions = false;
  bool continuous = false;
  double particle_restitution = 0.5;
  double particle_friction = 0.0;
  int max_iterations = 20;
  double penetration_slop = 0.001;  // m
  // The body solver's (BodySettings): substeps, iterations, relax_iterations, sleep.
  int body_substeps = 4;
  int body_iterations = 2;
  int body_relax_iterations = 0;
  bool body_sleep = true;
  double publish_rate = 30.0;  // Hz, wall
  bool paused = false;
};

// The world's physics settings in engine form. Of the body solver's settings (the scene's
// `body_solver`) four are live (LiveSettings::body_*); configure() keeps the others.
struct PhysicsSettings {
  engine::WorldConfig config;
  engine::CollisionSettings collisions;
  engine::BodySettings bodies;
};

LiveSettings liveSettingsOf(const PhysicsSettings& physics, double publish_rate, bool paused);

// `wanted` laid over `base`: checked as a request is (every value finite and in range, names
// known); the error names the parameter and the reason, e.g. "rate: must be in (0, 100000] Hz,
// got 0". The settings the live ones do not cover (broadphase, tolerances...) stay as in base.
engine::Result<PhysicsSettings> applyLiveSettings(const LiveSettings& wanted,
                                                  const PhysicsSettings& base);

std::optional<engine::DivergencePolicy> parseDivergencePolicy(const std::string& name);

// Every setting that changes how the world steps, one "key: value" line each (YAML), numbers
// with 17 significant digits so equal text means equal bits.
std::string describeConfiguration(const PhysicsSettings& physics);

// The identity of a loaded scene: its state hash (positions, velocities, time), what the state
// hash leaves out (masses, radii, damping, colliders, generators and links by kind; bodies' types,
// masses, inertia and shapes and joints by kind, when it has bodies) and its configuration
// (describeConfiguration). Two nodes with equal scene hashes step alike.
std::uint64_t sceneHash(const engine::World& scene);

}  // namespace node
}  // namespace mass_aggregate_sim
