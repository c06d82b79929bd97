#pragma once
// A contact between two particles the body solver moves (both resting on a body, or on particles
// that do), in the body solver's passes: its normal row, and Coulomb friction while the pile rests
// on moving bodies alone. Such a pile's contacts are this solver's alone: the particle solver
// passes over their velocities and still takes out their overlap in its positions stage.
// Particles do not turn: no angular terms.

#include <cstdint>
#include <vector>

#include "engine/bodies/solver_body.h"

namespace mass_aggregate_sim {
namespace engine {

struct ParticlePair {
  std::int32_t a = kNoBody;  // solver bodies, both moving
  std::int32_t b = kNoBody;
  // Where each centre moves from this step (its solver body's dp is measured from there).
  Vec3 start_a = Vec3::Zero();
  Vec3 start_b = Vec3::Zero();
  Real touching = 0.0;  // the distance between the centres at which they touch: r_a + r_b
  Real friction = 0.0;  // applied only while the body solver has the contact alone (`alone`)
  // Accumulated over the substep and warm started from the last: pushing b away from a along n,
  // and the friction impulse on a (on b its opposite), in the contact plane.
  Real normal_impulse = 0.0;
  Vec3 friction_impulse = Vec3::Zero();
  std::uint64_t key = 0;  // the particle contact's key (Contact::key)
  // This substep: whether the body solver has the contact alone (its pile rests on moving bodies
  // only), and then its index among the substep's particle contacts. Else the particle solver
  // solves it too, friction included, and this row only keeps the two from closing.
  bool alone = false;
  std::uint32_t contact = 0;
};

// The substep's last impulses again, along the pair's normal now (the friction in the plane
// across it, within mu times the normal impulse).
void warmStartParticlePairs(std::vector<ParticlePair>& pairs, std::vector<SolverBody>& bodies);
// One Gauss-Seidel pass: each pair kept from closing (a gap may close no faster than within h),
// then, when alone, its slip removed within Coulomb's cone. Rigid: the overlap is the particle
// solver's positions stage's (a bias would push a resting column apart with real velocity).
void solveParticlePairs(std::vector<ParticlePair>& pairs, std::vector<SolverBody>& bodies, Real h);

}  // namespace engine
}  // namespace mass_aggregate_sim
