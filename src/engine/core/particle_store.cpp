#include "mass_aggregate_sim/engine/core/particle_store.h"

#include <cmath>
#include <limits>

namespace mass_aggregate_sim {
namespace engine {
namespace {

bool finite(const Vec3& v) { return v.allFinite(); }

void pushVec3(ParticleBuffer& buffer, const Vec3& v) {
  buffer.push_back(v.x());
  buffer.push_back(v.y());
  buffer.push_back(v.z());
}

// Not all bits zero: a component -0 counts, since g + (-0) and g + (+0) differ when g is -0.
bool anyBitSet(const Real* xyz) {
  for (std::size_t k = 0; k < 3; ++k) {
    if (xyz[k] != 0.0 || std::signbit(xyz[k])) return true;
  }
  return false;
}

void copyVec3(ParticleBuffer& buffer, std::size_t from, std::size_t to) {
  for (std::size_t k = 0; k < 3; ++k) buffer[3 * to + k] = buffer[3 * from + k];
}

}  // namespace

Status validateSpec(const ParticleSpec& spec) {
  if (!finite(spec.position)) return Status::error("position is not finite");
  if (!finite(spec.velocity)) return Status::error("velocity is not finite");
  if (!finite(spec.acceleration)) return Status::error("acceleration is not finite");
  if (!std::isfinite(spec.inverse_mass) || spec.inverse_mass < 0.0) {
    return Status::error("inverse mass must be finite and >= 0 (0 = immovable)");
  }
  if (!std::isfinite(spec.damping) || spec.damping < 0.0 || spec.damping > 1.0) {
    return Status::error("damping must be in [0, 1]");
  }
  if (!std::isfinite(spec.radius) || spec.radius < 0.0) {
    return Status::error("radius must be finite and >= 0");
  }
  return Status::ok();
}

ParticleId ParticleStore::add(const ParticleSpec& spec) {
  const ParticleId id = slots_.add();
  const bool movable = spec.inverse_mass > 0.0;
  pushVec3(position_, spec.position);
  pushVec3(velocity_, movable ? spec.velocity : Vec3::Zero());
  pushVec3(force_, Vec3::Zero());
  pushVec3(acceleration_, spec.acceleration);
  if (anyBitSet(spec.acceleration.data())) ++own_acceleration_count_;
  pushVec3(previous_position_, spec.position);
  pushVec3(previous_external_, Vec3::Zero());
  history_seeded_.push_back(0.0);
  inverse_mass_.push_back(spec.inverse_mass);
  mobility_.push_back(movable ? 1.0 : 0.0);
  damping_.push_back(spec.damping);
  radius_.push_back(spec.radius);
  name_.push_back(spec.name);
  ++damping_version_;
  ++layout_version_;
  return id;
}

Status ParticleStore::remove(const ParticleId id) {
  const auto dense = find(id);
  if (!dense) return Status::error(describeInvalid(id));
  if (hasOwnAcceleration(*dense)) --own_acceleration_count_;
  const auto move = slots_.remove(id);
  if (move.from != move.to) moveDense(move.from, move.to);
  popDense();
  ++damping_version_;
  ++layout_version_;
  return Status::ok();
}

void ParticleStore::clear() {
  slots_.clear();
  for (auto* buffer :
       {&position_, &velocity_, &force_, &acceleration_, &previous_position_, &previous_external_,
        &history_seeded_, &inverse_mass_, &mobility_, &damping_, &radius_}) {
    buffer->clear();
  }
  name_.clear();
  own_acceleration_count_ = 0;
  ++damping_version_;
  ++layout_version_;
}

bool ParticleStore::contains(const ParticleId id) const { return find(id).has_value(); }

std::optional<std::size_t> ParticleStore::find(const ParticleId id) const {
  return slots_.find(id);
}

ParticleId ParticleStore::idAt(const std::size_t dense) const { return slots_.idAt(dense); }

std::string ParticleStore::describeInvalid(const ParticleId id) const {
  return slots_.describeInvalid(id, "particle");
}

Status ParticleStore::checkReference(const ParticleId id, const char* field) const {
  if (contains(id)) return Status::ok();
  return Status::error(std::string(field) + ": " + describeInvalid(id));
}

std::optional<ParticleId> ParticleStore::findByName(const std::string& name) const {
  if (name.empty()) return std::nullopt;
  for (std::size_t i = 0; i < name_.size(); ++i) {
    if (name_[i] == name) return idAt(i);
  }
  return std::nullopt;
}

void ParticleStore::setInverseMass(const std::size_t dense, const Real inverse_mass) {
  inverse_mass_[dense] = inverse_mass;
  mobility_[dense] = inverse_mass > 0.0 ? 1.0 : 0.0;
  if (inverse_mass <= 0.0) velocities().col(dense).setZero();
}

Real ParticleStore::mass(const std::size_t dense) const {
  return inverse_mass_[dense] > 0.0 ? 1.0 / inverse_mass_[dense]
                                    : std::numeric_limits<Real>::infinity();
}

void ParticleStore::setDamping(const std::size_t dense, const Real damping) {
  damping_[dense] = damping;
  ++damping_version_;
}

bool ParticleStore::hasOwnAcceleration(const std::size_t dense) const {
  return anyBitSet(acceleration_.data() + 3 * dense);
}

void ParticleStore::moveDense(const std::size_t from, const std::size_t to) {
  for (auto* buffer : {&position_, &velocity_, &force_, &acceleration_, &previous_position_,
                       &previous_external_}) {
    copyVec3(*buffer, from, to);
  }
  for (auto* buffer : {&history_seeded_, &inverse_mass_, &mobility_, &damping_, &radius_}) {
    (*buffer)[to] = (*buffer)[from];
  }
  name_[to] = std::move(name_[from]);
}

void ParticleStore::popDense() {
  for (auto* buffer : {&position_, &velocity_, &force_, &acceleration_, &previous_position_,
                       &previous_external_}) {
    buffer->resize(buffer->size() - 3);
  }
  for (auto* buffer : {&history_seeded_, &inverse_mass_, &mobility_, &damping_, &radius_}) {
    buffer->pop_back();
  }
  name_.pop_back();
}

}  // namespace engine
}  // namespace mass_aggregate_sim
