// The query services of SimNode: a ray cast and an overlap test over particles, bodies and
// colliders, answered at a step boundary; they change nothing and are not recorded.
#include <cmath>

#include "mass_aggregate_sim/node/body_conversions.h"
#include "mass_aggregate_sim/node/conversions.h"
#include "mass_aggregate_sim/node/input_limits.h"
#include "mass_aggregate_sim/node/sim_node.h"
#include "service_helpers.h"

namespace mass_aggregate_sim {
namespace node {
namespace {

using engine::Real;
using engine::Status;
using engine::Vec3;

Status checkQuerySize(const Real value, const std::string& field) {
  if (!std::isfinite(value) || !(value > 0.0) || value > kMaxLength) {
    return Status::error(field + ": must be finite and in (0, 4e+06] m");
  }
  return Status::ok();
}

// The particles whose sphere overlaps a box (centre, half extents, orientation): the engine's
// overlapBox is axis-aligned only, so each particle near it is tested in the box's frame.
std::vector<engine::ParticleId> particlesInBox(const engine::World& world, const Vec3& center,
                                               const Vec3& half_extents, const engine::Quat& q) {
  std::vector<engine::ParticleId> found;
  const engine::ParticleStore& p = world.particles();
  const engine::Quat inverse = q.conjugate();
  for (const engine::ParticleId id : world.overlapSphere(center, half_extents.norm())) {
    const std::size_t i = *p.find(id);
    const Vec3 local = inverse * (Vec3(p.positions().col(i)) - center);
    const Vec3 nearest = local.cwiseMax(-half_extents).cwiseMin(half_extents);
    if ((local - nearest).norm() <= p.radii()[i]) found.push_back(id);
  }
  return found;
}

}  // namespace

bool SimNode::onRaycast(Raycast::Request& req, Raycast::Response& res) {
  const Vec3 origin = fromMsg(req.origin);
  const Vec3 direction = fromMsg(req.direction);
  engine::Status valid = checkPosition(origin, "origin");
  if (valid) valid = checkVector(direction, kMaxLength, "direction", "");
  if (valid && !(direction.norm() > 0.0)) valid = Status::error("direction: must not be zero");
  if (valid) valid = checkQuerySize(req.max_distance, "max_distance");
  if (!valid) return answer(res, false, valid.message());
  return runOnWorldThread(res, [&] {
    const auto frame = referenceFrame(req.frame_id);
    if (!frame) {
      answer(res, false, "frame_id: " + frame.message());
      return;
    }
    const engine::Transform& pose = frame.value().pose;
    const engine::World& world = sim_.world();
    const auto hit = world.raycast(pose.apply(origin), pose.rotation * direction, req.max_distance);
    res.hit = hit.has_value();
    if (hit) {
      if (hit->hit_particle) {
        res.kind = Raycast::Response::PARTICLE;
        res.id = hit->particle.packed();
        res.name = world.particles().name(*world.particles().find(hit->particle));
      } else if (hit->hit_body) {
        res.kind = Raycast::Response::BODY;
        res.id = hit->body.packed();
        res.name = world.bodies().name(*world.bodies().find(hit->body));
      } else {
        res.kind = Raycast::Response::COLLIDER;
        res.id = hit->collider;
      }
      res.point = toPointMsg(pose.applyInverse(hit->point));
      res.normal = toVector3Msg(pose.rotation.conjugate() * hit->normal);
      res.distance = hit->distance;
    }
    answer(res, true,
           hit ? "hit " +
                     std::string(hit->hit_particle ? "particle"
                                 : hit->hit_body   ? "body"
                                                   : "collider") +
                     " " + std::to_string(res.id) + " at " + std::to_string(hit->distance) + " m"
               : std::string("nothing within max_distance"));
  });
}

bool SimNode::onOverlap(Overlap::Request& req, Overlap::Response& res) {
  const engine::Transform local = fromMsg(req.pose);
  engine::Status valid = checkPosition(local.position, "pose.position");
  if (valid && req.shape == Overlap::Request::SPHERE) {
    valid = checkQuerySize(req.radius, "radius");
  } else if (valid && req.shape == Overlap::Request::BOX) {
    valid = checkUnitQuaternion(local.rotation, "pose.orientation");
    const Vec3 half = fromMsg(req.half_extents);
    for (int axis = 0; valid && axis < 3; ++axis) {
      valid = checkQuerySize(half[axis], "half_extents[" + std::to_string(axis) + "]");
    }
  } else if (valid) {
    valid = Status::error("shape: must be SPHERE (0) or BOX (1), got " + std::to_string(req.shape));
  }
  if (!valid) return answer(res, false, valid.message());
  return runOnWorldThread(res, [&] {
    const auto frame = referenceFrame(req.frame_id);
    if (!frame) {
      answer(res, false, "frame_id: " + frame.message());
      return;
    }
    const engine::Transform pose = poseToWorld(*frame, local);
    const engine::World& world = sim_.world();
    std::vector<engine::BodyId> bodies;
    std::vector<engine::ParticleId> particles;
    if (req.shape == Overlap::Request::SPHERE) {
      bodies = world.bodiesOverlappingSphere(pose.position, req.radius);
      particles = world.overlapSphere(pose.position, req.radius);
    } else {
      const Vec3 half = fromMsg(req.half_extents);
      const engine::Quat q = pose.rotation.normalized();
      bodies = world.bodiesOverlappingBox(pose.position, half, q);
      particles = particlesInBox(world, pose.position, half, q);
    }
    for (const engine::BodyId id : bodies) {
      res.body_ids.push_back(id.packed());
      res.body_names.push_back(world.bodies().name(*world.bodies().find(id)));
    }
    for (const engine::ParticleId id : particles) {
      res.particle_ids.push_back(id.packed());
      res.particle_names.push_back(world.particles().name(*world.particles().find(id)));
    }
    answer(res, true,
           std::to_string(bodies.size()) + " body(ies) and " + std::to_string(particles.size()) +
               " particle(s) overlap");
  });
}

}  // namespace node
}  // namespace mass_aggregate_sim
