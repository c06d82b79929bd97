#include "mass_aggregate_sim/engine/core/particle_store.h"

#include <cmath>
#include <limits>

namespace mass_aggregate_sim {
namespace engine {
namespace {

bool finite(const Vec3& v) { return v.allFinite(); }

void pushVec3(std::vector<Real>& buffer, const Vec3& v) {
  buffer.push_back(v.x());
  buffer.push_back(v.y());
  buffer.push_back(v.z());
}

void copyVec3(std::vector<Real>& buffer, std::size_t from, std::size_t to) {
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
  std::uint32_t slot;
  if (!free_slots_.empty()) {
    slot = free_slots_.back();
    free_slots_.pop_back();
  } else {
    slot = static_cast<std::uint32_t>(dense_of_slot_.size());
    dense_of_slot_.push_back(0);
    generation_of_slot_.push_back(0);
    slot_live_.push_back(false);
  }
  const auto dense = static_cast<std::uint32_t>(size());
  dense_of_slot_[slot] = dense;
  slot_live_[slot] = true;
  slot_of_dense_.push_back(slot);

  const bool movable = spec.inverse_mass > 0.0;
  pushVec3(position_, spec.position);
  pushVec3(velocity_, movable ? spec.velocity : Vec3::Zero());
  pushVec3(force_, Vec3::Zero());
  pushVec3(acceleration_, spec.acceleration);
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
  return ParticleId{slot, generation_of_slot_[slot]};
}

Status ParticleStore::remove(const ParticleId id) {
  const auto dense = find(id);
  if (!dense) return Status::error(describeInvalid(id));
  const std::size_t last = size() - 1;
  if (*dense != last) moveDense(last, *dense);
  popDense();
  slot_live_[id.index] = false;
  ++generation_of_slot_[id.index];
  free_slots_.push_back(id.index);
  ++damping_version_;
  ++layout_version_;
  return Status::ok();
}

void ParticleStore::clear() {
  for (const std::uint32_t slot : slot_of_dense_) {
    slot_live_[slot] = false;
    ++generation_of_slot_[slot];
    free_slots_.push_back(slot);
  }
  slot_of_dense_.clear();
  for (auto* buffer :
       {&position_, &velocity_, &force_, &acceleration_, &previous_position_, &previous_external_,
        &history_seeded_, &inverse_mass_, &mobility_, &damping_, &radius_}) {
    buffer->clear();
  }
  name_.clear();
  ++damping_version_;
  ++layout_version_;
}

bool ParticleStore::contains(const ParticleId id) const { return find(id).has_value(); }

std::optional<std::size_t> ParticleStore::find(const ParticleId id) const {
  if (id.index >= slot_live_.size() || !slot_live_[id.index] ||
      generation_of_slot_[id.index] != id.generation) {
    return std::nullopt;
  }
  return dense_of_slot_[id.index];
}

ParticleId ParticleStore::idAt(const std::size_t dense) const {
  const std::uint32_t slot = slot_of_dense_[dense];
  return ParticleId{slot, generation_of_slot_[slot]};
}

std::string ParticleStore::describeInvalid(const ParticleId id) const {
  if (!id.valid() || id.index >= slot_live_.size()) {
    return "unknown particle id " + id.str() + " (no such slot)";
  }
  if (!slot_live_[id.index]) return "stale particle id " + id.str() + " (particle was removed)";
  if (generation_of_slot_[id.index] != id.generation) {
    return "stale particle id " + id.str() + " (slot " + std::to_string(id.index) +
           " now holds generation " + std::to_string(generation_of_slot_[id.index]) + ")";
  }
  return "particle id " + id.str() + " is live";
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

void ParticleStore::moveDense(const std::size_t from, const std::size_t to) {
  for (auto* buffer : {&position_, &velocity_, &force_, &acceleration_, &previous_position_,
                       &previous_external_}) {
    copyVec3(*buffer, from, to);
  }
  for (auto* buffer : {&history_seeded_, &inverse_mass_, &mobility_, &damping_, &radius_}) {
    (*buffer)[to] = (*buffer)[from];
  }
  name_[to] = std::move(name_[from]);
  slot_of_dense_[to] = slot_of_dense_[from];
  dense_of_slot_[slot_of_dense_[to]] = static_cast<std::uint32_t>(to);
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
  slot_of_dense_.pop_back();
}

}  // namespace engine
}  // namespace mass_aggregate_sim
