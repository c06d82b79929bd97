#pragma once

#include "mass_aggregate_sim/engine/core/types.h"

namespace mass_aggregate_sim {
namespace engine {

// A liquid filling the half-space below a plane: the points x with up.x < height (up a unit
// vector).
struct LiquidSurface {
  Vec3 up = Vec3::UnitZ();
  Real height = 0.0;

  // How far x is above the surface (negative below it).
  Real above(const Vec3& x) const { return up.dot(x) - height; }
};

// The part of a shape below a liquid surface: its volume and its first moment (the integral of
// x over it). They add over the shapes of a body; the centre of buoyancy is moment / volume.
struct SubmergedVolume {
  Real volume = 0.0;
  Vec3 moment = Vec3::Zero();

  SubmergedVolume& operator+=(const SubmergedVolume& other) {
    volume += other.volume;
    moment += other.moment;
    return *this;
  }
  // The whole of a shape of volume v centred at c.
  static SubmergedVolume whole(const Real v, const Vec3& c) { return SubmergedVolume{v, v * c}; }
};

}  // namespace engine
}  // namespace mass_aggregate_sim
