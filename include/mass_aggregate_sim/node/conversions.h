#pragma once

#include <geometry_msgs/Point.h>
#include <geometry_msgs/Vector3.h>

#include "mass_aggregate_sim/ParticleArray.h"
#include "mass_aggregate_sim/ParticleSpec.h"
#include "mass_aggregate_sim/engine/core/types.h"
#include "mass_aggregate_sim/engine/world/world.h"
#include "mass_aggregate_sim/node/snapshot.h"

namespace mass_aggregate_sim {
namespace node {

geometry_msgs::Point toPointMsg(const engine::Vec3& v);
geometry_msgs::Vector3 toVector3Msg(const engine::Vec3& v);
engine::Vec3 fromMsg(const geometry_msgs::Point& p);
engine::Vec3 fromMsg(const geometry_msgs::Vector3& v);

// Every particle of the world; the header's stamp and frame are left for the caller.
void fillParticleArray(const WorldSnapshot& world, ParticleArray& msg);

// A spawn request's particle as an engine spec (position and velocity as given, no frame change).
// Refuses a mass that is not finite and > 0 (unless fixed); radius 0 means default_radius and
// damping 0 means no damping (1). The engine validates the rest.
engine::Result<engine::ParticleSpec> toParticleSpec(const ParticleSpec& msg, double default_radius);

}  // namespace node
}  // namespace mass_aggregate_sim
