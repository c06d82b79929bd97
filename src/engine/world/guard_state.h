#pragma once

#include <cstdint>
#include <optional>

#include "mass_aggregate_sim/engine/world/world.h"

namespace mass_aggregate_sim {
namespace engine {

// The guards' record: the last divergence and how many, and the energy guard's reference (the
// state the first step after the last change ended in).
struct GuardState {
  std::optional<DivergenceEvent> last_divergence;
  std::uint64_t divergence_count = 0;
  bool energy_known = false;
  Real energy = 0.0;
  Real free_energy = 0.0;  // kinetic + elastic
  Real gravitational_energy = 0.0;
  std::uint64_t steps_since_reference = 0;
};

}  // namespace engine
}  // namespace mass_aggregate_sim
