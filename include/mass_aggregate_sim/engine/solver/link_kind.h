#pragma once

#include "mass_aggregate_sim/engine/core/kind_list.h"
#include "mass_aggregate_sim/engine/core/particle_id.h"
#include "mass_aggregate_sim/engine/core/status.h"
#include "mass_aggregate_sim/engine/core/types.h"
#include "mass_aggregate_sim/engine/forces/force_kind.h"

namespace mass_aggregate_sim {
namespace engine {

class ParticleStore;

// Links are hard constraints between two particles or a particle and a fixed anchor, solved with
// the contacts; their ids come from the force generators' id space (World::removeGenerator
// removes either). Each row acts along the line between the ends.
struct LinkLimits {
  Real length = 0.0;       // the length held (a rod) or not exceeded (a cable)
  bool pulls_only = true;  // a cable only pulls; a rod holds its length either way
  Real restitution = 0.0;  // a cable snapping taut reflects the separating speed by this
};

// What the engine knows of a link kind K: LinkKind<K>, specialised in K's own header and defined
// in its own source file (solver/<kind>.cpp). Every stage that handles links visits LinkKinds
// (links.h) through these, so a kind that lacks one does not compile:
//   kName                    the kind's name in messages
//   validate(K&, particles)  refuses bad values (Status says why)
//   refersTo(k, id)          whether the link holds particle id (removed with it)
//   limits(k)                what its constraint row holds
template <typename Kind>
struct LinkKind;

}  // namespace engine
}  // namespace mass_aggregate_sim
