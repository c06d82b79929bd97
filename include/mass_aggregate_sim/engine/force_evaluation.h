#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "mass_aggregate_sim/engine/force_generators.h"
#include "mass_aggregate_sim/engine/particle_store.h"
#include "mass_aggregate_sim/engine/types.h"

namespace mass_aggregate_sim {
namespace engine {

// A spring or bungee between two particles with both ends resolved to dense indices, a < b (the
// ends swapped when needed: the force on each end is then the same to the bit).
struct DenseSpring {
  std::uint32_t a = 0;
  std::uint32_t b = 0;
  Real stiffness = 0.0;
  Real rest_length = 0.0;
  Real damping = 0.0;
};

// The springs and bungees of a ForceGenerators in the same order, ends as dense indices: the hot
// loops then read one packed array instead of looking every id up. Valid while neither the
// generators nor the store's layout (ParticleStore::layoutVersion) change.
//
// The lists are cut, in order, into segments. A run is a segment whose ends advance together
// (spring first + j joins a + j and b + j): chains, ropes and the rows and columns of a cloth
// come out that way, and a run reads its positions and adds its forces as contiguous blocks.
struct SpringSegment {
  std::uint32_t first = 0;
  std::uint32_t count = 0;
  bool run = false;
  bool damped = false;  // a spring of the segment has damping != 0
};
struct DenseSprings {
  std::vector<DenseSpring> springs;
  std::vector<DenseSpring> bungees;
  std::vector<SpringSegment> spring_segments;
  std::vector<SpringSegment> bungee_segments;
};
DenseSprings resolveDenseSprings(const ForceGenerators& generators, const ParticleStore& particles);

// Adds the force of every generator, evaluated at positions x and velocities v (dense order, same
// size as the store), to `force`. A pure function of its arguments, so RK4 can call it per stage.
// dt is the step the stiff springs solve over; gravity_magnitude feeds buoyancy. `dense`, when
// given, must be resolveDenseSprings() of the same generators and store: the springs and bungees
// then come from it (same forces, same order). `elastic_energy`, when given (with `dense`),
// receives the generators' elastic energy at x, the springs' from the lengths the force pass
// computes.
void accumulateGeneratorForces(const ForceGenerators& generators, const ParticleStore& particles,
                               const Eigen::Ref<const Vec3Array>& x,
                               const Eigen::Ref<const Vec3Array>& v, Real gravity_magnitude,
                               Real dt, Eigen::Ref<Vec3Array> force,
                               const DenseSprings* dense = nullptr, Real* elastic_energy = nullptr);

// Elastic energy stored in springs, anchored springs, stretched bungees and stiff springs; `dense`
// as for accumulateGeneratorForces.
Real generatorPotentialEnergy(const ForceGenerators& generators, const ParticleStore& particles,
                              const DenseSprings* dense = nullptr);

}  // namespace engine
}  // namespace mass_aggregate_sim
