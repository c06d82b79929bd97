#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "mass_aggregate_sim/engine/world/world.h"
#include "mass_aggregate_sim/node/body_requests.h"
#include "mass_aggregate_sim/node/body_springs.h"
#include "mass_aggregate_sim/node/force_fields.h"
#include "mass_aggregate_sim/node/joint_requests.h"
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

// A force at a point and a torque on a body, in the world: the force keeps its direction and acts
// on the material point that was at `point` when the request was applied.
struct WrenchRequest {
  BodyRef body;
  engine::Vec3 force = engine::Vec3::Zero();   // N
  engine::Vec3 torque = engine::Vec3::Zero();  // N m
  engine::Vec3 point = engine::Vec3::Zero();   // m
  ForceMode mode = ForceMode::kOneStep;
  engine::Real duration = 0.0;  // s, for kDuration
};

struct RemovedBodies {
  std::vector<engine::BodyId> ids;
  std::size_t joints = 0;  // joints that went with them
};

struct SimulationLimits {
  std::size_t max_particles = 20000;
  std::uint32_t max_steps_per_request = 100000;
  // Force generators and links together (springs, bungees, cables, rods, drag, buoyancy).
  std::size_t max_links = 100000;
  // Forces on particles and wrenches on bodies kept across steps (DURATION and UNTIL_CLEARED).
  std::size_t max_sustained_forces = 10000;
  std::size_t max_bodies = 10000;
  std::size_t max_joints = 10000;
  // The node's world frame: no particle or body may take its name or a collider frame's (tf would
  // clash).
  std::string world_frame = "world";
};

// The world as the node drives it, without ROS: the loaded scene (kept for reset), requests that
// may touch it (each validated in full before anything changes), and the forces that last longer
// than one step. Every call is made from the one thread that owns the world.
class Simulation {
 public:
  // `joint_names` names the scene's joints (the others are joint_<id>).
  Simulation(const engine::World& scene, const SimulationLimits& limits,
             JointNames joint_names = {});

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
  // Links and springs on bodies count together against ~max_links; removeLink removes either.
  engine::Result<engine::GeneratorId> addLink(const LinkRequest& request);
  engine::Result<engine::GeneratorId> addBodySpring(const BodySpringRequest& request);
  // Drag or buoyancy on each particle and body named, all or none, within ~max_links.
  engine::Result<std::vector<engine::GeneratorId>> addForceFields(const ForceFieldRequest& request);
  engine::Status removeForceField(engine::GeneratorId id);
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

  // --- bodies and joints (simulation_bodies.cpp); poses, points and twists in the world, twists
  // of the body frame's origin (Twist) ---
  // All or nothing: every spec is checked (checkBodySpec, names unique among bodies and
  // particles, ~max_bodies) first.
  engine::Result<std::vector<engine::BodyId>> spawnBodies(
      const std::vector<engine::BodySpec>& specs);
  // All or nothing; their joints and wrenches go with them.
  engine::Result<RemovedBodies> removeBodies(const std::vector<BodyRef>& refs);
  // The pose first, then the twist at the new pose; either may be left out (the other is kept).
  engine::Status setBodyState(const BodyRef& ref, const std::optional<engine::Transform>& pose,
                              const std::optional<Twist>& twist);
  // Returns the number of steps the wrench will act (0 for until-cleared and clear).
  engine::Result<std::uint64_t> applyBodyWrench(const WrenchRequest& request);
  // A linear impulse at a world point and an angular impulse; returns the twist right after.
  engine::Result<Twist> applyBodyImpulse(const BodyRef& ref, const engine::Vec3& impulse,
                                         const engine::Vec3& point,
                                         const engine::Vec3& angular_impulse);
  engine::Result<engine::JointId> addJoint(const JointRequest& request);
  engine::Status removeJoint(engine::JointId id);
  engine::Status setHingeMotor(engine::JointId id, bool enabled, engine::Real speed,
                               engine::Real max_torque);
  engine::Result<engine::BodyId> resolveBody(const BodyRef& ref) const;
  const JointNames& jointNames() const { return joint_names_; }

  engine::Result<engine::ParticleId> resolve(const ParticleRef& ref) const;
  // Particle forces and body wrenches kept across steps.
  std::size_t sustainedForceCount() const { return sustained_.size() + wrenches_.size(); }

 private:
  // Room under ~max_links for `more` links and force generators.
  engine::Status checkLinkRoom(std::size_t more = 1) const;
  // For a force or wrench kept across steps (kDuration, kUntilCleared): room under
  // max_sustained_forces, and the steps it lasts (-1: until cleared; a duration rounds to at
  // least one step).
  engine::Result<std::int64_t> sustainedSteps(ForceMode mode, engine::Real duration) const;

  struct SustainedForce {
    engine::ParticleId particle;
    engine::Vec3 force;
    std::int64_t steps_left;  // < 0: until cleared
  };

  struct SustainedWrench {
    engine::BodyId body;
    engine::Vec3 force;
    engine::Vec3 point;  // in the body's frame
    engine::Vec3 torque;
    std::int64_t steps_left;  // < 0: until cleared
  };
  void applyWrenches();

  engine::World scene_;
  engine::World world_;
  SimulationLimits limits_;
  JointNames scene_joint_names_;
  JointNames joint_names_;
  std::vector<SustainedForce> sustained_;
  std::vector<SustainedWrench> wrenches_;
  std::optional<PhysicsSettings> configured_;
};

}  // namespace node
}  // namespace mass_aggregate_sim
