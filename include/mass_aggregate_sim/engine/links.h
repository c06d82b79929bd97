#pragma once

#include <vector>

#include "mass_aggregate_sim/engine/force_generators.h"
#include "mass_aggregate_sim/engine/particle_id.h"
#include "mass_aggregate_sim/engine/types.h"

namespace mass_aggregate_sim {
namespace engine {

// Links are hard constraints solved by the contact resolver, not forces. Their ids come from the
// same space as force generators' (World::removeGenerator removes either).

// Keeps two particles at most max_length apart; when it snaps taut the separating speed is
// reflected with the given restitution.
struct Cable {
  ParticleId a;
  ParticleId b;
  Real max_length = 1.0;
  Real restitution = 0.0;
  GeneratorId id = 0;
};

// Keeps two particles exactly length apart (within CollisionSettings::rod_tolerance, relative).
struct Rod {
  ParticleId a;
  ParticleId b;
  Real length = 1.0;
  GeneratorId id = 0;
};

struct AnchoredCable {
  ParticleId particle;
  Vec3 anchor = Vec3::Zero();
  Real max_length = 1.0;
  Real restitution = 0.0;
  GeneratorId id = 0;
};

struct AnchoredRod {
  ParticleId particle;
  Vec3 anchor = Vec3::Zero();
  Real length = 1.0;
  GeneratorId id = 0;
};

// Every link of a world, one array per kind.
struct Links {
  std::vector<Cable> cables;
  std::vector<Rod> rods;
  std::vector<AnchoredCable> anchored_cables;
  std::vector<AnchoredRod> anchored_rods;

  bool empty() const {
    return cables.empty() && rods.empty() && anchored_cables.empty() && anchored_rods.empty();
  }
  std::size_t size() const {
    return cables.size() + rods.size() + anchored_cables.size() + anchored_rods.size();
  }
  void clear() { *this = Links{}; }
};

}  // namespace engine
}  // namespace mass_aggregate_sim
