#pragma once

#include <cstdint>
#include <vector>

#include "mass_aggregate_sim/engine/collision/shape_kind.h"
#include "mass_aggregate_sim/engine/core/particle_id.h"

namespace mass_aggregate_sim {
namespace engine {

// The particles given their own material for particle-particle contacts, by slot
// (ParticleId::index), so they survive the store's dense moves. A pair combines the two: mean
// restitution, geometric mean friction.
class ParticleMaterials {
 public:
  void set(const ParticleId id, const Material& material) {
    if (has_.size() <= id.index) {
      has_.resize(id.index + 1, 0);
      material_.resize(id.index + 1);
    }
    if (!has_[id.index]) ++count_;
    has_[id.index] = 1;
    material_[id.index] = material;
  }
  void forget(const ParticleId id) {
    if (id.index < has_.size() && has_[id.index]) {
      has_[id.index] = 0;
      --count_;
    }
  }
  void clear() {
    has_.assign(has_.size(), 0);
    count_ = 0;
  }
  bool any() const { return count_ > 0; }
  // The material of the particle in `slot`, or `otherwise` when it has none of its own.
  Material of(const std::uint32_t slot, const Material& otherwise) const {
    return slot < has_.size() && has_[slot] ? material_[slot] : otherwise;
  }

 private:
  std::vector<Material> material_;
  std::vector<std::uint8_t> has_;
  std::size_t count_ = 0;
};

}  // namespace engine
}  // namespace mass_aggregate_sim
