#include "body_scene.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace mass_aggregate_sim {
namespace study {

using engine::BodySettings;
using engine::BodyShapeSpec;
using engine::BodySpec;
using engine::BoxShape;
using engine::PlaneCollider;
using engine::WorldConfig;

Real contactHertz(const BodyKnobs& knobs) {
  return std::min(BodySettings{}.contact_hertz * knobs.stiffness, 0.25 * knobs.substeps / kBodyDt);
}

Real jointHertz(const BodyKnobs& knobs) {
  return std::min(BodySettings{}.joint_hertz * knobs.stiffness, 0.25 * knobs.substeps / kBodyDt);
}

World bodyWorld(const BodyKnobs& knobs, const Real g) {
  WorldConfig config;
  config.dt = kBodyDt;
  config.gravity = Vec3(0.0, 0.0, -g);
  World world(config);
  BodySettings settings;
  settings.substeps = knobs.substeps;
  settings.iterations = knobs.iterations;
  settings.contact_hertz *= knobs.stiffness;
  settings.joint_hertz *= knobs.stiffness;
  settings.sleep = false;
  if (!world.setBodySettings(settings)) std::abort();
  return world;
}

BodyId addBox(World& world, const Vec3& half_extents, const Real mass, const Vec3& position,
              const Material& material, const Quat& orientation) {
  BodyShapeSpec shape;
  shape.geometry = BoxShape{half_extents};
  shape.material = material;
  BodySpec spec;
  spec.shapes = {shape};
  spec.mass = mass;
  spec.pose.position = position;
  spec.pose.rotation = orientation;
  const auto id = world.addBody(spec);
  if (!id) std::abort();
  return *id;
}

void addGround(World& world, const Material& material) {
  PlaneCollider ground;
  ground.normal = Vec3::UnitZ();
  ground.offset = 0.0;
  ground.material = material;
  if (!world.addCollider(ground)) std::abort();
}

int stepsIn(const Real seconds) { return static_cast<int>(std::lround(seconds / kBodyDt)); }

BodyRun finishRun(const World& world, std::vector<Real> values) {
  BodyRun run;
  run.diverged =
      world.divergenceCount() > 0 ||
      !std::all_of(values.begin(), values.end(), [](const Real v) { return std::isfinite(v); });
  run.values = std::move(values);
  return run;
}

}  // namespace study
}  // namespace mass_aggregate_sim
