#pragma once
// A shared rigid scene (rigid_scenes.h) as an engine world: how the benchmark and the probes in
// docs/benchmarks build it.

#include <vector>

#include "mass_aggregate_sim/engine/world/world.h"
#include "rigid_scenes.h"

namespace mass_aggregate_sim {
namespace bench {
namespace rigid {

inline engine::BodyShapeSpec engineShapeOf(const BodySpec& spec) {
  engine::BodyShapeSpec shape;
  if (spec.shape == ShapeType::kSphere) {
    shape.geometry = engine::SphereShape{spec.radius};
  } else {
    shape.geometry = engine::BoxShape{spec.half_extents};
  }
  shape.material = engine::Material{spec.restitution, spec.friction};
  return shape;
}

// The scene at 60 Hz: its gravity, its ground as a plane collider, `settings`, and its bodies in
// order, their ids appended to `ids` when given.
inline engine::World engineWorld(const RigidScene& scene, const engine::BodySettings& settings,
                                 std::vector<engine::BodyId>* ids = nullptr) {
  engine::WorldConfig config;
  config.dt = kFrameSeconds;
  config.gravity = scene.gravity;
  engine::World world = *engine::World::create(config);
  world.setBodySettings(settings);
  engine::PlaneCollider ground;
  ground.normal = engine::Vec3::UnitZ();
  ground.offset = scene.ground.height;
  ground.material = engine::Material{scene.ground.restitution, scene.ground.friction};
  world.addCollider(ground);
  for (const BodySpec& spec : scene.bodies) {
    engine::BodySpec body;
    body.type = spec.isFixed() ? engine::BodyType::kFixed : engine::BodyType::kDynamic;
    body.pose.position = spec.position;
    body.pose.rotation = spec.orientation;
    body.shapes = {engineShapeOf(spec)};
    if (!spec.isFixed()) {
      body.mass = spec.mass;
      body.linear_velocity = spec.linear_velocity;
      body.angular_velocity = spec.angular_velocity;
    }
    const engine::BodyId id = *world.addBody(body);
    if (ids) ids->push_back(id);
  }
  return world;
}

}  // namespace rigid
}  // namespace bench
}  // namespace mass_aggregate_sim
