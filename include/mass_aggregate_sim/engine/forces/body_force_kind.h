#pragma once

#include <vector>

#include "mass_aggregate_sim/engine/core/status.h"
#include "mass_aggregate_sim/engine/forces/force_kind.h"
#include "mass_aggregate_sim/engine/joints/joint_kind.h"

namespace mass_aggregate_sim {
namespace engine {

class BodyForceScene;
struct BodyStiffnessTerm;
class BodyForceSums;

// What the engine knows of a kind K of force generator that acts on bodies (a point of a body,
// its centre of mass), and on a particle at the other end: BodyForceKind<K>, specialised in K's
// own header and defined in its own source file (forces/<kind>.cpp). Every place that handles
// them (adding, removing them with their bodies and particles, the force stage, the energy,
// sleeping) visits BodyForceKinds (body_force_generators.h), so a kind that lacks one does not
// compile:
//   kName                        the kind's name in messages
//   validate(K&, scene)          refuses bad values (Status says why); may normalise the kind
//   bodiesOf(k)                  the bodies it acts on (woken when it is added or removed)
//   refersTo(k, BodyId), refersTo(k, ParticleId)
//                                whether it acts on that body or particle (removed with it)
//   joins(k)                     whether it joins two things that move (a body to another body
//                                or to a particle): they stay awake together
//   reachesParticle(k)           whether an end is a particle
//   accumulate(ks, scene, sums)  adds each generator's force at the state of the scene
//   energy(ks, scene)            their elastic energy at the state of the scene
//   stiffness(ks, scene, terms)  a BodyStiffnessTerm per spring, for the stability analysis
//                                (stability.h); nothing for a kind without stiffness
//   decay(ks, scene, terms)      a DecayTerm per drag (linear and angular), likewise
// They act as the particle kinds do, with the law written once (force_laws.h); they are evaluated
// once per substep at its start (bodies are integrated by semi-implicit Euler, which reads the
// forces there), and a particle at one end feels that force, constant over the substep, as an
// external force under its own integrator: the two ends' impulses are equal and opposite, so
// momentum is conserved to rounding.
template <typename Kind>
struct BodyForceKind;

}  // namespace engine
}  // namespace mass_aggregate_sim
