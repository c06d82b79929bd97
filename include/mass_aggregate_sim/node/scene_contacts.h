#pragma once

#include <xmlrpcpp/XmlRpcValue.h>

#include <string>

#include "mass_aggregate_sim/engine/world/world.h"

namespace mass_aggregate_sim {
namespace node {

// The contact parts of a scene (see scene_loader.h); each throws ParamError with the key.
// `collisions`: a map of CollisionSettings fields, applied over the world's current settings.
void readCollisionSettings(XmlRpc::XmlRpcValue& collisions, const std::string& key,
                           engine::World& world);
// `colliders`: a list of {type: plane | sphere | box | capsule, shape fields, restitution,
// friction}.
void readColliders(XmlRpc::XmlRpcValue& colliders, const std::string& key, engine::World& world);

}  // namespace node
}  // namespace mass_aggregate_sim
