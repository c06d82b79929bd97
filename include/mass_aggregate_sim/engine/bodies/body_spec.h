#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "mass_aggregate_sim/engine/bodies/body_shapes.h"
#include "mass_aggregate_sim/engine/collision/shape_parts.h"
#include "mass_aggregate_sim/engine/core/stable_id.h"
#include "mass_aggregate_sim/engine/core/transform.h"

namespace mass_aggregate_sim {
namespace engine {

struct BodyTag;
// Names one rigid body (slot + generation).
using BodyId = StableId<BodyTag>;

// Dynamic bodies move under forces and contacts; kinematic bodies move with the velocity they are
// given and push dynamic ones without being pushed back; fixed bodies never move.
enum class BodyType : std::uint8_t { kDynamic, kKinematic, kFixed };

// One shape of a body: its geometry at a pose in the body's frame, its surface and its density
// (used when the body's mass is not given).
struct BodyShapeSpec {
  AnyBodyShape geometry = SphereShape{};
  Transform local;
  Material material{0.0, 0.5};
  Real density = 1000.0;  // kg/m^3
};

// What a new body starts with. Its frame is `pose`; its centre of mass and principal axes follow
// from its shapes (several shapes make a compound). Velocities are those of the centre of mass, in
// the world frame.
struct BodySpec {
  std::string name;
  BodyType type = BodyType::kDynamic;
  Transform pose;
  Vec3 linear_velocity = Vec3::Zero();   // m/s
  Vec3 angular_velocity = Vec3::Zero();  // rad/s
  std::vector<BodyShapeSpec> shapes;
  // kg; > 0 replaces the mass the densities give (the inertia scales with it), 0 keeps it.
  Real mass = 0.0;
  // 1/s: each substep v' = v / (1 + h c) (and w likewise), a drag that keeps a body stable.
  Real linear_damping = 0.0;
  Real angular_damping = 0.0;
  // Rests with its island once all of it has been slow for a while (BodySettings).
  bool can_sleep = true;
};

}  // namespace engine
}  // namespace mass_aggregate_sim
