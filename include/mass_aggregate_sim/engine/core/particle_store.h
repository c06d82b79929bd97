#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "mass_aggregate_sim/engine/core/cache_line_allocator.h"
#include "mass_aggregate_sim/engine/core/dense_slots.h"
#include "mass_aggregate_sim/engine/core/particle_id.h"
#include "mass_aggregate_sim/engine/core/status.h"
#include "mass_aggregate_sim/engine/core/types.h"

namespace mass_aggregate_sim {
namespace engine {

// What a new particle starts with. inverse_mass 0 makes it immovable.
struct ParticleSpec {
  Vec3 position = Vec3::Zero();
  Vec3 velocity = Vec3::Zero();
  Vec3 acceleration = Vec3::Zero();  // constant acceleration of this particle, on top of gravity
  Real inverse_mass = 1.0;
  Real damping = 1.0;  // fraction of velocity kept per second: the ODE term v' = ln(damping) v
  Real radius = 0.1;
  std::string name;
};

// Checks a spec without adding it: finite numbers, inverse mass >= 0, damping in [0, 1], radius >=
// 0.
Status validateSpec(const ParticleSpec& spec);

// One attribute of every particle, on a cache line (see CacheLineAllocator).
using ParticleBuffer = std::vector<Real, CacheLineAllocator<Real>>;

// Particles as a structure of arrays, densely packed so each attribute is one contiguous Eigen
// array: column i of every array is the same particle. Removal moves the last particle into the
// hole, so dense indices change; ParticleId (slot + generation) is the stable handle.
class ParticleStore {
 public:
  std::size_t size() const { return slots_.size(); }
  bool empty() const { return size() == 0; }

  ParticleId add(const ParticleSpec& spec);
  // Refuses (and changes nothing) when the id is stale or unknown.
  Status remove(ParticleId id);
  void clear();

  bool contains(ParticleId id) const;
  // The dense index of a live particle, or nothing for a stale or unknown id.
  std::optional<std::size_t> find(ParticleId id) const;
  // Dense index of an id known to be live (no check: for hot loops over validated references).
  std::size_t denseIndexUnchecked(ParticleId id) const { return slots_.denseIndexUnchecked(id); }
  ParticleId idAt(std::size_t dense) const;
  // Says why an id is not live: unknown slot, or the generation it had versus the slot's now.
  std::string describeInvalid(ParticleId id) const;
  // Ok for a live id, else "<field>: " and why not.
  Status checkReference(ParticleId id, const char* field) const;
  std::optional<ParticleId> findByName(const std::string& name) const;

  Vec3Map positions() { return vec3(position_); }
  ConstVec3Map positions() const { return vec3(position_); }
  Vec3Map velocities() { return vec3(velocity_); }
  ConstVec3Map velocities() const { return vec3(velocity_); }
  // External force accumulated for the next step (services, user code); cleared after each step.
  Vec3Map forces() { return vec3(force_); }
  ConstVec3Map forces() const { return vec3(force_); }
  // Constant acceleration of each particle, on top of the world's gravity (set when it is added).
  ConstVec3Map accelerations() const { return vec3(acceleration_); }
  // Whether some particle's own acceleration is anything but (+0, +0, +0). When none is, a pass
  // may add a constant +0 instead of reading them: the same operation on the same bits.
  bool anyOwnAcceleration() const { return own_acceleration_count_ > 0; }
  // Position Verlet's history: the position one substep ago, the external acceleration (F / m) of
  // that substep, and whether the two are seeded (1) or must be seeded from the particle's
  // position and velocity before the next substep (0: a new particle, or one whose velocity was
  // set).
  Vec3Map previousPositions() { return vec3(previous_position_); }
  ConstVec3Map previousPositions() const { return vec3(previous_position_); }
  Vec3Map previousExternalAccelerations() { return vec3(previous_external_); }
  ConstVec3Map previousExternalAccelerations() const { return vec3(previous_external_); }
  ScalarMap historySeeded() { return scalar(history_seeded_); }
  ConstScalarMap historySeeded() const { return scalar(history_seeded_); }
  ConstScalarMap inverseMasses() const { return scalar(inverse_mass_); }
  // 1 for a movable particle, 0 for an immovable one: multiplies uniform accelerations.
  ConstScalarMap mobility() const { return scalar(mobility_); }
  ConstScalarMap dampings() const { return scalar(damping_); }
  void setDamping(std::size_t dense, Real damping);
  // Changes whenever any damping may have changed (set, add, remove), so d^dt can be cached.
  std::uint64_t dampingVersion() const { return damping_version_; }
  // Changes whenever the dense order may have changed (add, remove, clear), so data that holds
  // dense indices can be cached.
  std::uint64_t layoutVersion() const { return layout_version_; }
  ScalarMap radii() { return scalar(radius_); }
  ConstScalarMap radii() const { return scalar(radius_); }
  const std::string& name(std::size_t dense) const { return name_[dense]; }

  // Keeps mobility in step with inverse mass; an immovable particle also loses its velocity.
  void setInverseMass(std::size_t dense, Real inverse_mass);
  Real mass(std::size_t dense) const;

 private:
  Vec3Map vec3(ParticleBuffer& buffer) { return Vec3Map(buffer.data(), 3, size()); }
  ConstVec3Map vec3(const ParticleBuffer& buffer) const {
    return ConstVec3Map(buffer.data(), 3, size());
  }
  ScalarMap scalar(ParticleBuffer& buffer) { return ScalarMap(buffer.data(), size()); }
  ConstScalarMap scalar(const ParticleBuffer& buffer) const {
    return ConstScalarMap(buffer.data(), size());
  }
  bool hasOwnAcceleration(std::size_t dense) const;
  void moveDense(std::size_t from, std::size_t to);
  void popDense();

  DenseSlots<ParticleId> slots_;
  // Growable buffers (amortised O(1) add); Eigen maps give the arrays their shape.
  ParticleBuffer position_;
  ParticleBuffer velocity_;
  ParticleBuffer force_;
  ParticleBuffer acceleration_;
  ParticleBuffer previous_position_;
  ParticleBuffer previous_external_;
  ParticleBuffer history_seeded_;
  ParticleBuffer inverse_mass_;
  ParticleBuffer mobility_;
  ParticleBuffer damping_;
  ParticleBuffer radius_;
  std::vector<std::string> name_;

  std::uint64_t damping_version_ = 0;
  std::uint64_t layout_version_ = 0;
  std::size_t own_acceleration_count_ = 0;  // particles for which hasOwnAcceleration holds
};

}  // namespace engine
}  // namespace mass_aggregate_sim
