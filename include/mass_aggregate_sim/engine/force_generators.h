#pragma once

#include <cstdint>
#include <vector>

#include "mass_aggregate_sim/engine/particle_id.h"
#include "mass_aggregate_sim/engine/types.h"

namespace mass_aggregate_sim {
namespace engine {

// Names one force generator of any kind; never reused within a world.
using GeneratorId = std::uint32_t;

// Each kind is plain data kept in its own array and applied by one loop (force_evaluation.cpp).

// F = -(k1 |v| + k2 |v|^2) v/|v|
struct Drag {
  ParticleId particle;
  Real k1 = 0.0;
  Real k2 = 0.0;
  GeneratorId id = 0;
};

// Hooke's law between two particles, signed: pulls when stretched, pushes when compressed.
// Optional dashpot along the spring: F_a = -(k (l - L) + c (v_a - v_b).n) n, n = (x_a - x_b)/l.
struct Spring {
  ParticleId a;
  ParticleId b;
  Real stiffness = 0.0;
  Real rest_length = 0.0;
  Real damping = 0.0;
  GeneratorId id = 0;
};

// A spring from a particle to a fixed point.
struct AnchoredSpring {
  ParticleId particle;
  Vec3 anchor = Vec3::Zero();
  Real stiffness = 0.0;
  Real rest_length = 0.0;
  Real damping = 0.0;
  GeneratorId id = 0;
};

// A spring that only pulls: no force while its length is at or below the rest length.
struct Bungee {
  ParticleId a;
  ParticleId b;
  Real stiffness = 0.0;
  Real rest_length = 0.0;
  Real damping = 0.0;
  GeneratorId id = 0;
};

struct AnchoredBungee {
  ParticleId particle;
  Vec3 anchor = Vec3::Zero();
  Real stiffness = 0.0;
  Real rest_length = 0.0;
  Real damping = 0.0;
  GeneratorId id = 0;
};

// Buoyancy of a particle against a liquid whose surface is the plane up.x = surface_height.
// With s = up.x - surface_height the particle's height above the surface:
//   s >= max_depth: out of the liquid, no force;  s <= -max_depth: fully submerged, rho V |g| up;
//   in between, linear: rho V |g| (max_depth - s) / (2 max_depth) up.
struct Buoyancy {
  ParticleId particle;
  Real max_depth = 0.1;
  Real volume = 0.0;
  Real liquid_density = 1000.0;
  Real surface_height = 0.0;
  Vec3 up = Vec3::UnitZ();
  GeneratorId id = 0;
};

// A spring too stiff to integrate, solved in closed form: the damped harmonic motion of the
// particle about the anchor over the step gives the acceleration that lands it where the exact
// solution does.
struct StiffSpring {
  ParticleId particle;
  Vec3 anchor = Vec3::Zero();
  Real stiffness = 0.0;
  Real damping = 0.0;
  GeneratorId id = 0;
};

// Every force generator of a world, one array per kind; an empty kind costs nothing.
struct ForceGenerators {
  std::vector<Drag> drags;
  std::vector<Spring> springs;
  std::vector<AnchoredSpring> anchored_springs;
  std::vector<Bungee> bungees;
  std::vector<AnchoredBungee> anchored_bungees;
  std::vector<Buoyancy> buoyancies;
  std::vector<StiffSpring> stiff_springs;

  bool empty() const {
    return drags.empty() && springs.empty() && anchored_springs.empty() && bungees.empty() &&
           anchored_bungees.empty() && buoyancies.empty() && stiff_springs.empty();
  }
  std::size_t size() const {
    return drags.size() + springs.size() + anchored_springs.size() + bungees.size() +
           anchored_bungees.size() + buoyancies.size() + stiff_springs.size();
  }
  void clear() { *this = ForceGenerators{}; }
};

}  // namespace engine
}  // namespace mass_aggregate_sim
