#pragma once

#include <xmlrpcpp/XmlRpcValue.h>

#include <cstddef>
#include <string>

#include "mass_aggregate_sim/engine/world/world.h"
#include "mass_aggregate_sim/node/joint_requests.h"

namespace mass_aggregate_sim {
namespace node {

// The rigid-body parts of a scene (see scene_loader.h); each throws ParamError with the key.

// `body_solver`: a map of BodySettings fields, applied over the world's current settings.
void readBodySolver(XmlRpc::XmlRpcValue& solver, const std::string& key, engine::World& world);

struct BodyLimits {
  std::size_t max_bodies = 10000;
  std::size_t max_joints = 10000;
  std::string world_frame = "world";
};

// `bodies`: a list of {name, type, position, orientation, velocity, angular_velocity, mass,
// linear_damping, angular_damping, can_sleep, shapes: [{type, the kind's fields, position,
// orientation, density, friction, restitution}], count, offset}. With count, count bodies named
// <name>_0 ... at position + i offset.
void readBodies(XmlRpc::XmlRpcValue& bodies, const std::string& key, engine::World& world,
                const BodyLimits& limits);
// `joints`: a list of {type, name, a, b, anchor, anchor_b, collide_connected, the kind's fields};
// a and b name a body or a particle, b left out is the world. Names go into `names`.
void readJoints(XmlRpc::XmlRpcValue& joints, const std::string& key, engine::World& world,
                const BodyLimits& limits, JointNames& names);

}  // namespace node
}  // namespace mass_aggregate_sim
