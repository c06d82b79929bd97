#pragma once

#include <xmlrpcpp/XmlRpcValue.h>

#include <cstddef>
#include <string>
#include <vector>

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
// A `forces` entry of type spring or bungee, a body at one end at least: {type, a, b, anchor,
// anchor_b, stiffness, rest_length, damping}; a and b name a body or a particle, b left out is
// the world; anchor is end a's world point (a body's origin or the particle when left out),
// anchor_b end b's (required for the world); rest_length left out is the distance.
void readPointSpring(XmlRpc::XmlRpcValue& spring, const std::string& key, engine::World& world);
// The bodies of a `forces` entry's `bodies: [names]`.
std::vector<engine::BodyId> readBodyTargets(XmlRpc::XmlRpcValue& entry, const std::string& key,
                                            const engine::World& world);

}  // namespace node
}  // namespace mass_aggregate_sim
