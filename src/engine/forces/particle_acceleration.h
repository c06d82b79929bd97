#pragma once
// A particle's acceleration from the forces on it, written once for the force stage and the
// integrators' fused passes, for T a scalar or a vector of lanes (simd::Real4).

namespace mass_aggregate_sim {
namespace engine {

// What acts on every particle alike, per unit mass: gravity and its own constant acceleration;
// mobility is 1 for a movable particle and 0 for an immovable one.
template <typename T>
inline T uniformAcceleration(const T mobility, const T gravity, const T own) {
  return mobility * (gravity + own);
}

// a = F / m + g + a_own (inverse mass 0 and uniform 0 for an immovable particle).
template <typename T>
inline T particleAcceleration(const T force, const T inverse_mass, const T uniform) {
  return force * inverse_mass + uniform;
}

}  // namespace engine
}  // namespace mass_aggregate_sim
