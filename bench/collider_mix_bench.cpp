// Scenario C on a realistic mix of colliders (issue 13): C's grid of spheres (r = 0.1 m, 0.5 m
// apart, particle collisions off), each resting where it stands on a ground plane with friction
// 0.5 and on or between boxes and a sphere. C alone is a frictionless plane, the one case the
// plane groups' lanes serve; here every collider kind and contact arrangement of a scene takes
// its part. The grid's four quadrants:
//   x < L/2, z < L/2   ground, and two rails (long axis-aligned boxes) with one row of spheres
//                      in the channel between them, touching the ground and both rails;
//   x >= L/2, z < L/2  a table (an axis-aligned box, top 1 m up): spheres on its top, and along
//                      its four sides a row touching the side and the ground;
//   x < L/2, z >= L/2  a dome (a sphere collider sunk into the ground, slope at most 20 degrees
//                      where it meets it, within what friction 0.5 holds): spheres on it;
//   x >= L/2, z >= L/2 a ramp (a box turned 15 degrees about z, its underside 0.25 m up):
//                      spheres on it, and on the ground around and under it.
// Every collider has restitution 0.2 and friction 0.5. Each particle meets each of the six
// colliders' tests, so the count of colliders is fixed and their sizes grow with the grid.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include "mass_aggregate_sim/engine/world/world.h"
#include "scenario_common.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

using bench::kRadius;

constexpr Real kGridSpacing = 0.5;
constexpr int kMixSettleSteps = 60;
const Material kMixMaterial{0.2, 0.5};

World colliderMixWorld(const std::int64_t n) {
  World world(bench::scenarioConfig());
  const auto side = static_cast<std::int64_t>(std::ceil(std::sqrt(static_cast<double>(n))));
  const std::int64_t half = side / 2;
  const Real length = kGridSpacing * static_cast<Real>(side);
  const auto at = [](const std::int64_t index) { return kGridSpacing * static_cast<Real>(index); };
  world.addCollider(PlaneCollider{Vec3::UnitY(), 0.0, kMixMaterial});

  // Rails: faces one radius either side of grid row rail_row, from grid column 1 to half - 2.
  const std::int64_t rail_row = half / 2;
  const Real rail_lo = at(1);
  const Real rail_hi = at(half - 2);
  for (const Real sign : {-1.0, 1.0}) {
    BoxCollider rail;
    rail.half_extents = Vec3(0.5 * (rail_hi - rail_lo), 0.075, 0.1);
    rail.center = Vec3(0.5 * (rail_lo + rail_hi), 0.075, at(rail_row) + sign * (kRadius + 0.1));
    rail.material = kMixMaterial;
    world.addCollider(rail);
  }

  // Table: its sides one radius beyond grid columns / rows, so those spheres touch them.
  const std::int64_t table_x0 = half + 1;
  const std::int64_t table_x1 = side - 2;
  const std::int64_t table_z0 = 1;
  const std::int64_t table_z1 = half - 2;
  BoxCollider table;
  table.center =
      Vec3(0.5 * (at(table_x0) + at(table_x1)), 0.5, 0.5 * (at(table_z0) + at(table_z1)));
  table.half_extents = Vec3(0.5 * (at(table_x1) - at(table_x0)) - kRadius, 0.5,
                            0.5 * (at(table_z1) - at(table_z0)) - kRadius);
  table.material = kMixMaterial;
  world.addCollider(table);

  // Dome: radius R, centre depth R cos(20 deg), so its rim on the ground has radius R sin(20 deg).
  const Real rim_angle = 20.0 * M_PI / 180.0;
  const Real rim = 0.25 * length - 1.0;
  SphereCollider dome;
  dome.radius = rim / std::sin(rim_angle);
  dome.center = Vec3(0.25 * length, -dome.radius * std::cos(rim_angle), 0.75 * length);
  dome.material = kMixMaterial;
  world.addCollider(dome);

  // Ramp: turned about z, so its top rises along x; its lowest corner is 0.25 m up.
  const Real ramp_angle = 15.0 * M_PI / 180.0;
  BoxCollider ramp;
  ramp.half_extents = Vec3(rim / std::cos(ramp_angle), 0.25, rim);
  ramp.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(ramp_angle, Vec3::UnitZ()));
  ramp.center = Vec3(0.75 * length,
                     0.25 + ramp.half_extents.x() * std::sin(ramp_angle) +
                         ramp.half_extents.y() * std::cos(ramp_angle),
                     0.75 * length);
  ramp.material = kMixMaterial;
  world.addCollider(ramp);

  for (std::int64_t i = 0; i < n; ++i) {
    const std::int64_t column = i % side;
    const std::int64_t row = i / side;
    const Real x = at(column);
    const Real z = at(row);
    Real y = kRadius;  // on the ground
    const bool on_table =
        column > table_x0 && column < table_x1 && row > table_z0 && row < table_z1;
    if (on_table) y = 2.0 * table.half_extents.y() + kRadius;
    // On the dome where its surface is above the ground: |x - c| = R + r.
    const Real rho_squared = (x - dome.center.x()) * (x - dome.center.x()) +
                             (z - dome.center.z()) * (z - dome.center.z());
    const Real reach = dome.radius + kRadius;
    if (rho_squared < reach * reach) {
      y = std::max(y, dome.center.y() + std::sqrt(reach * reach - rho_squared));
    }
    // On the ramp's top face, away from its edges: the local height is half_extents.y + r.
    const Real c = std::cos(ramp_angle);
    const Real s = std::sin(ramp_angle);
    const Real dx = x - ramp.center.x();
    const Real ramp_y = ramp.center.y() + (ramp.half_extents.y() + kRadius + s * dx) / c;
    const Real local_x = c * dx + s * (ramp_y - ramp.center.y());
    if (std::abs(local_x) < ramp.half_extents.x() - kRadius &&
        std::abs(z - ramp.center.z()) < ramp.half_extents.z() - kRadius) {
      y = ramp_y;
    }
    world.addParticle(bench::unitParticle(Vec3(x, y, z)));
  }
  for (int s = 0; s < kMixSettleSteps; ++s) world.step();
  return world;
}

void BM_ScenarioC_ColliderMix(benchmark::State& state) {
  World world = bench::settledScene("C mix/" + std::to_string(state.range(0)),
                                    [&] { return colliderMixWorld(state.range(0)); });
  bench::runContactSteps(state, world);
}

void BM_ScenarioC_ColliderMix_GeneralPath(benchmark::State& state) {
  World world = bench::settledScene("C mix/" + std::to_string(state.range(0)),
                                    [&] { return colliderMixWorld(state.range(0)); });
  bench::useGeneralContactPath(world);
  bench::runContactSteps(state, world);
}

BENCHMARK(BM_ScenarioC_ColliderMix)->Arg(1000)->Arg(10000)->Arg(100000);
BENCHMARK(BM_ScenarioC_ColliderMix_GeneralPath)->Arg(1000)->Arg(10000)->Arg(100000);

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
