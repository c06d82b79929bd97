#pragma once
// The closed-form half of the stiff spring kind (stiff_spring.h): the stage that moves each
// particle held by stiff springs exactly over a substep.

#include <vector>

#include "mass_aggregate_sim/engine/core/particle_store.h"
#include "mass_aggregate_sim/engine/forces/stiff_spring.h"

namespace mass_aggregate_sim {
namespace engine {

// A particle held by stiff springs, for one substep: its dense index, its state at the start of
// the substep, the acceleration of everything else on it then, and its springs summed
// (stiffness, stiffness-weighted anchors, damping).
struct StiffParticle {
  std::size_t index = 0;
  Vec3 position = Vec3::Zero();
  Vec3 velocity = Vec3::Zero();
  Vec3 other_acceleration = Vec3::Zero();
  Real stiffness = 0.0;
  Vec3 weighted_anchor = Vec3::Zero();
  Real damping = 0.0;
};

// Before the integrator: every movable particle with a stiff spring, once, in dense order, from
// the store's state and `acceleration` (the whole acceleration of every particle now, the
// springs' share included, as the force stage gives it for a substep of h).
void prepareStiffSprings(const std::vector<StiffSpring>& springs, const ParticleStore& particles,
                         const Eigen::Ref<const Vec3Array>& acceleration, Real h,
                         std::vector<StiffParticle>& out);
// After the integrator: each such particle's exact damped harmonic motion over h about its
// equilibrium, everything else held at its start-of-substep value, written to the store; its
// position Verlet history is to be seeded again.
void applyStiffSprings(const std::vector<StiffParticle>& held, ParticleStore& particles, Real h);

}  // namespace engine
}  // namespace mass_aggregate_sim
