// ~add_force_field's message and the node's request (force_field_conversions.h).
#include "mass_aggregate_sim/node/force_field_conversions.h"

#include <cmath>

#include "mass_aggregate_sim/node/conversions.h"

namespace mass_aggregate_sim {
namespace node {

using engine::Real;
using engine::Result;
using engine::Vec3;

Result<ForceFieldRequest> toForceFieldRequest(const AddForceField::Request& msg) {
  ForceFieldRequest request;
  const auto type = parseForceFieldType(msg.type);
  if (!type) return type.status();
  request.type = *type;
  const auto model = parseBuoyancyModel(msg.model);
  if (!model) return engine::Status::error("model: " + model.message());
  request.model = *model;
  for (const auto id : msg.particle_ids) request.particles.push_back(ParticleRef{id, ""});
  for (const auto& name : msg.particle_names) request.particles.push_back(ParticleRef{0, name});
  for (const auto id : msg.body_ids) request.bodies.push_back(BodyRef{id, ""});
  for (const auto& name : msg.body_names) request.bodies.push_back(BodyRef{0, name});
  request.k1 = msg.k1;
  request.k2 = msg.k2;
  request.angular = msg.angular;
  request.volume = msg.volume;
  request.max_depth = msg.max_depth;
  request.liquid_density = msg.liquid_density;
  request.surface_height = msg.surface_height;
  const Vec3 up = fromMsg(msg.up);
  request.up = up.isZero(0.0) ? Vec3::UnitZ() : up;
  return request;
}

// The surface {x : n.x = height}, n = up / |up|, holds the point height n of the frame: in the
// world it is {x : n_w.x = n_w.p_w} with n_w = R n and p_w = T(height n).
void placeForceFieldRequest(const ReferenceFrame& frame, ForceFieldRequest& request,
                            AddForceField::Request& msg) {
  const Real length = request.up.norm();
  if (std::isfinite(length) && length > 0.0) {
    const Vec3 n = request.up / length;
    const Vec3 n_world = frame.pose.rotation * n;
    request.surface_height = n_world.dot(frame.pose.apply(request.surface_height * n));
    request.up = n_world;
  }
  msg.frame_id.clear();
  msg.up = toVector3Msg(request.up);
  msg.surface_height = request.surface_height;
}

}  // namespace node
}  // namespace mass_aggregate_sim
