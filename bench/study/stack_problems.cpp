// Columns of ten 1 kg (or alternately 1 and 100 kg) unit cubes on the ground, friction 0.5 and no
// bounce, left for 10 s with sleeping off: at rest, the top must stay where it rests.
#include <cmath>
#include <string>
#include <vector>

#include "body_scene.h"

namespace mass_aggregate_sim {
namespace study {
namespace {

constexpr int kCubes = 10;
constexpr Real kDuration = 10.0;
// Creep is measured from here, once a dropped column has settled.
constexpr Real kSettled = 2.0;

struct Column {
  Real gap = 0.0;         // m between cubes at the start
  Real offset = 0.0;      // m along x, alternately + and -
  Real yaw = 0.0;         // rad about z, alternately + and -
  Real heavy_mass = 1.0;  // kg of every second cube (from the second)
};

BodyRun stand(const BodyKnobs& knobs, const Column& column) {
  World world = bodyWorld(knobs, kG);
  const Material material{0.0, 0.5};
  addGround(world, material);
  BodyId top;
  for (int k = 0; k < kCubes; ++k) {
    const Real sign = k % 2 == 0 ? -1.0 : 1.0;
    const Quat turn(Eigen::AngleAxisd(sign * column.yaw, Vec3::UnitZ()));
    top = addBox(world, Vec3::Constant(0.5), k % 2 == 0 ? 1.0 : column.heavy_mass,
                 Vec3(sign * column.offset, 0.0, 0.5 + k * (1.0 + column.gap)), material, turn);
  }
  const std::size_t i = *world.bodies().find(top);
  // Where the top rests once every gap has closed.
  Vec3 rest = world.bodies().position(i);
  rest.z() = kCubes - 0.5;
  Vec3 settled = Vec3::Zero();
  const int steps = stepsIn(kDuration);
  for (int step = 1; step <= steps; ++step) {
    world.step();
    if (step == stepsIn(kSettled)) settled = world.bodies().position(i);
  }
  const Vec3& end = world.bodies().position(i);
  return finishRun(world, {(end - rest).norm(), (end - settled).norm(), world.kineticEnergy()});
}

std::vector<BodyMetric> stackMetrics() {
  return {{"top_drift",
           "distance of the top cube after 10 s from where it should rest (m)",
           {1e-1, 1e-2, 1e-3, 1e-4}},
          {"top_creep", "distance the top cube moved from 2 s to 10 s (m)", {1e-2, 1e-3, 1e-4}},
          {"kinetic_energy", "kinetic energy after 10 s (J)", {}}};
}

BodyProblem stack(const std::string& name, const std::string& description, const Column& column) {
  BodyProblem p;
  p.name = name;
  p.description = description;
  p.duration = kDuration;
  p.metrics = stackMetrics();
  p.run = [column](const BodyKnobs& knobs) { return stand(knobs, column); };
  return p;
}

// Alternately 5 cm off-centre and turned 5 degrees, `gap` apart.
Column turnedColumn(const Real gap) {
  Column column;
  column.gap = gap;
  column.offset = 0.05;
  column.yaw = 5.0 * M_PI / 180.0;
  return column;
}

}  // namespace

BodyProblem cubeStack() {
  return stack("cube_stack", "10 unit cubes placed touching, 10 s", Column{});
}

BodyProblem droppedStack() {
  return stack("dropped_stack",
               "10 unit cubes placed 1 cm apart, alternately 5 cm off-centre and turned 5 "
               "degrees, falling into place, 10 s",
               turnedColumn(0.01));
}

BodyProblem turnedStack() {
  return stack("turned_stack",
               "10 unit cubes placed touching, alternately 5 cm off-centre and turned 5 degrees, "
               "10 s",
               turnedColumn(0.0));
}

BodyProblem heavyLightStack() {
  Column column;
  column.heavy_mass = 100.0;
  return stack("heavy_light_stack",
               "10 unit cubes placed touching, alternately 1 kg and 100 kg (1 kg at the bottom)",
               column);
}

}  // namespace study
}  // namespace mass_aggregate_sim
