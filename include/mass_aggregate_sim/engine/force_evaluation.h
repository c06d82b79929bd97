#pragma once

#include <Eigen/Core>

#include "mass_aggregate_sim/engine/force_generators.h"
#include "mass_aggregate_sim/engine/particle_store.h"
#include "mass_aggregate_sim/engine/types.h"

namespace mass_aggregate_sim {
namespace engine {

// Adds the force of every generator, evaluated at positions x and velocities v (dense order, same
// size as the store), to `force`. A pure function of its arguments, so RK4 can call it per stage.
// dt is the step the stiff springs solve over; gravity_magnitude feeds buoyancy.
void accumulateGeneratorForces(const ForceGenerators& generators, const ParticleStore& particles,
                               const Eigen::Ref<const Vec3Array>& x,
                               const Eigen::Ref<const Vec3Array>& v, Real gravity_magnitude,
                               Real dt, Eigen::Ref<Vec3Array> force);

// Elastic energy stored in springs, anchored springs, stretched bungees and stiff springs.
Real generatorPotentialEnergy(const ForceGenerators& generators, const ParticleStore& particles);

}  // namespace engine
}  // namespace mass_aggregate_sim
