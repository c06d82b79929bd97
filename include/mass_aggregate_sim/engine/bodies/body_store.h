#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "mass_aggregate_sim/engine/bodies/body_spec.h"
#include "mass_aggregate_sim/engine/bodies/mass_properties.h"
#include "mass_aggregate_sim/engine/core/dense_slots.h"
#include "mass_aggregate_sim/engine/core/status.h"

namespace mass_aggregate_sim {
namespace engine {

// Names one shape of a body while the body lives (an index into BodyStore::shapes()).
using ShapeIndex = std::uint32_t;

// A shape as the store keeps it: its geometry at a pose in its body's mass frame (centre of mass,
// principal axes), its surface, and where the broadphase holds it.
struct BodyShape {
  AnyBodyShape geometry;
  Transform local;  // in the body's mass frame
  Material material;
  BodyId body;
  std::int32_t proxy = -1;  // the broadphase's handle, -1 while not in it
  bool live = false;
};

// Rigid bodies as a structure of arrays, densely packed: index i of every array is the same body.
// Removal moves the last body into the hole; BodyId (slot + generation) is the stable handle.
// A body's state is its mass frame's pose (position = centre of mass, orientation = principal
// axes) and its velocities (of the centre of mass, world frame); its frame (the pose the user
// gives and sees) is that pose times the inverse of its mass frame.
class BodyStore {
 public:
  std::size_t size() const { return slots_.size(); }
  bool empty() const { return size() == 0; }

  // The spec and its mass properties, checked by the caller (World::addBody).
  BodyId add(const BodySpec& spec, const MassProperties& mass);
  Status remove(BodyId id);
  void clear();

  bool contains(BodyId id) const { return slots_.find(id).has_value(); }
  std::optional<std::size_t> find(BodyId id) const { return slots_.find(id); }
  std::size_t denseIndexUnchecked(BodyId id) const { return slots_.denseIndexUnchecked(id); }
  BodyId idAt(std::size_t i) const { return slots_.idAt(i); }
  std::string describeInvalid(BodyId id) const { return slots_.describeInvalid(id, "body"); }
  // Ok for a live id, else "<field>: " and why not.
  Status checkReference(BodyId id, const char* field) const;
  std::optional<BodyId> findByName(const std::string& name) const;

  BodyType type(std::size_t i) const { return type_[i]; }
  bool dynamic(std::size_t i) const { return type_[i] == BodyType::kDynamic; }
  const std::string& name(std::size_t i) const { return name_[i]; }
  // The mass frame in the world.
  Vec3& position(std::size_t i) { return position_[i]; }
  const Vec3& position(std::size_t i) const { return position_[i]; }
  Quat& orientation(std::size_t i) { return orientation_[i]; }
  const Quat& orientation(std::size_t i) const { return orientation_[i]; }
  // The body's own frame in the world.
  Transform pose(std::size_t i) const;
  // The mass frame in the body's frame.
  const Transform& massFrame(std::size_t i) const { return mass_frame_[i]; }
  Vec3& linearVelocity(std::size_t i) { return linear_velocity_[i]; }
  const Vec3& linearVelocity(std::size_t i) const { return linear_velocity_[i]; }
  Vec3& angularVelocity(std::size_t i) { return angular_velocity_[i]; }
  const Vec3& angularVelocity(std::size_t i) const { return angular_velocity_[i]; }
  // Velocity of the material point at world position p.
  Vec3 velocityAt(std::size_t i, const Vec3& p) const {
    return linear_velocity_[i] + angular_velocity_[i].cross(p - position_[i]);
  }
  // Accumulated for the next step (forces at points add their torque about the centre of mass).
  Vec3& force(std::size_t i) { return force_[i]; }
  const Vec3& force(std::size_t i) const { return force_[i]; }
  Vec3& torque(std::size_t i) { return torque_[i]; }
  const Vec3& torque(std::size_t i) const { return torque_[i]; }
  Real mass(std::size_t i) const { return mass_[i]; }
  Real inverseMass(std::size_t i) const { return inverse_mass_[i]; }
  // Principal moments (kg m^2) and their inverses (0 for kinematic and fixed bodies).
  const Vec3& principalInertia(std::size_t i) const { return principal_inertia_[i]; }
  const Vec3& inversePrincipalInertia(std::size_t i) const { return inverse_inertia_[i]; }
  // R diag(1/I) R^T for the current orientation, refreshed once per step (and on every set).
  const Mat3& worldInverseInertia(std::size_t i) const { return world_inverse_inertia_[i]; }
  void refreshWorldInertia(std::size_t i);
  Real linearDamping(std::size_t i) const { return linear_damping_[i]; }
  Real angularDamping(std::size_t i) const { return angular_damping_[i]; }
  // Sleeping (islands.h): a sleeping body is not stepped until something wakes its island.
  bool awake(std::size_t i) const { return awake_[i] != 0; }
  void setAwake(std::size_t i, bool awake);
  bool canSleep(std::size_t i) const { return can_sleep_[i] != 0; }
  Real& sleepTime(std::size_t i) { return sleep_time_[i]; }
  Real sleepTime(std::size_t i) const { return sleep_time_[i]; }
  const std::vector<ShapeIndex>& shapesOf(std::size_t i) const { return shapes_of_[i]; }
  // The farthest any of its shapes reaches from its centre of mass (m): a point of the body
  // moves at most |v| + |w| reach.
  Real reach(std::size_t i) const { return reach_[i]; }

  // Every shape slot (live or free); a body's are shapesOf(i).
  const std::vector<BodyShape>& shapes() const { return shapes_; }
  std::vector<BodyShape>& shapes() { return shapes_; }
  // The shape's pose in the world.
  Transform shapePose(ShapeIndex s) const;

  // Changes whenever bodies are added or removed (the dense order may have changed).
  std::uint64_t layoutVersion() const { return layout_version_; }

 private:
  void moveDense(std::size_t from, std::size_t to);
  void popDense();

  DenseSlots<BodyId> slots_;
  std::vector<BodyType> type_;
  std::vector<std::string> name_;
  std::vector<Vec3> position_;
  std::vector<Quat> orientation_;
  std::vector<Transform> mass_frame_;
  std::vector<Vec3> linear_velocity_;
  std::vector<Vec3> angular_velocity_;
  std::vector<Vec3> force_;
  std::vector<Vec3> torque_;
  std::vector<Real> mass_;
  std::vector<Real> inverse_mass_;
  std::vector<Vec3> principal_inertia_;
  std::vector<Vec3> inverse_inertia_;
  std::vector<Mat3> world_inverse_inertia_;
  std::vector<Real> linear_damping_;
  std::vector<Real> angular_damping_;
  std::vector<std::uint8_t> awake_;
  std::vector<std::uint8_t> can_sleep_;
  std::vector<Real> sleep_time_;
  std::vector<std::vector<ShapeIndex>> shapes_of_;
  std::vector<Real> reach_;
  std::vector<BodyShape> shapes_;
  std::vector<ShapeIndex> free_shapes_;
  std::uint64_t layout_version_ = 0;
};

}  // namespace engine
}  // namespace mass_aggregate_sim
