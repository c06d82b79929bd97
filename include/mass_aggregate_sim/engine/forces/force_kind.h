#pragma once

#include <cstdint>
#include <vector>

#include "mass_aggregate_sim/engine/core/kind_list.h"
#include "mass_aggregate_sim/engine/core/particle_id.h"
#include "mass_aggregate_sim/engine/core/status.h"
#include "mass_aggregate_sim/engine/core/types.h"

namespace mass_aggregate_sim {
namespace engine {

// Names one force generator or link; never reused within a world (they share one id space).
using GeneratorId = std::uint32_t;

class ParticleStore;
struct ForceEvaluation;
class ImplicitSystem;
struct StiffnessTerm;

// What the engine knows of a force generator kind K: ForceKind<K>, specialised in K's own header
// and defined in its own source file (forces/<kind>.cpp). Every stage that handles force
// generators visits ForceKinds (force_generators.h) through these functions, so a kind that lacks
// one does not compile:
//   kName                     the kind's name in messages
//   validate(K&, particles)   refuses bad values (Status says why); may normalise the kind
//   refersTo(k, id)           whether the generator acts on particle id (removed with it)
//   accumulate(ks, e, force, elastic)
//                             adds each generator's force at e.x, e.v to `force`; with `elastic`
//                             also adds their elastic energy at e.x to it
//   energy(ks, e)             their elastic energy at e.x
//   linearise(ks, system)     their K = df/dx and D = df/dv for implicit Euler
//   stiffness(ks, particles, terms)
//                             their springs for the stability analysis
//   decay(ks, particles, terms)
//                             their drags for the stability analysis (DecayTerm)
//   kUncountedWork            does work the energy guard cannot count (its energy is not a
//                             potential): a world with one is not guarded
//   kDrawn                    whether the kind acts between two points (a spring) and is drawn
//                             as a line: then drawn(k, particles) gives the segment and its
//                             tension; one-particle kinds (drag, buoyancy) are not drawn
template <typename Kind>
struct ForceKind;

// A drag for the stability analysis (stability.h): the rate of the first-order decay it puts on
// a velocity, v' = -rate v (k1 / m; about a body's axes angular / I_min), which the integrators
// take explicitly.
struct DecayTerm {
  GeneratorId id = 0;
  Real rate = 0.0;  // 1/s
  bool angular = false;
};

// A force generator as the node draws it: the line between its two ends and its tension (N, > 0
// pulling the ends together, 0 for a slack bungee).
struct DrawnSegment {
  Vec3 a;
  Vec3 b;
  Real tension;
};

}  // namespace engine
}  // namespace mass_aggregate_sim
