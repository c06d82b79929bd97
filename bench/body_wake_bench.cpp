// Requests that wake many sleeping islands at once. A room of boxes resting apart on a fixed
// floor is one island per box (fixed bodies join none), all asleep; a user then tilts the floor
// (World::setBodyPose) or removes it, and every box on it wakes. BM_BodyWake_SetFloorPose/N and
// BM_BodyWake_RemoveFloor/N time that one request on N sleeping boxes (the world copied, untimed,
// before each); the counter `woken` is how many boxes it woke (all N, or the request is wrong).
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdlib>
#include <vector>

#include "mass_aggregate_sim/engine/world/world.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

struct Room {
  World world;
  BodyId floor;
  std::vector<BodyId> boxes;
};

// N unit cubes 2 m apart on a square grid, resting on a fixed 0.2 m thick floor box wide enough
// for them, stepped until every one sleeps.
Room sleepingRoom(const int n) {
  WorldConfig config;
  config.dt = 1.0 / 60.0;
  config.gravity = Vec3(0.0, 0.0, -9.81);
  Room room{*World::create(config), BodyId{}, {}};
  const int side = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n))));
  const Real half_width = side + 1.0;
  BodySpec floor;
  floor.type = BodyType::kFixed;
  BodyShapeSpec slab;
  slab.geometry = BoxShape{Vec3(half_width, half_width, 0.1)};
  floor.shapes = {slab};
  room.floor = *room.world.addBody(floor);
  for (int k = 0; k < n; ++k) {
    BodySpec cube;
    BodyShapeSpec shape;
    shape.geometry = BoxShape{Vec3::Constant(0.5)};
    cube.shapes = {shape};
    cube.mass = 1.0;
    cube.pose.position = Vec3(2.0 * (k % side) - side + 1.0, 2.0 * (k / side) - side + 1.0, 0.6);
    room.boxes.push_back(*room.world.addBody(cube));
  }
  const BodyStore& bodies = room.world.bodies();
  const auto anyAwake = [&] {
    for (const BodyId id : room.boxes) {
      if (bodies.awake(*bodies.find(id))) return true;
    }
    return false;
  };
  for (int step = 0; step < 600 && anyAwake(); ++step) room.world.step();
  return room;
}

int awakeBoxes(const Room& room) {
  int awake = 0;
  for (const BodyId id : room.boxes) {
    const auto i = room.world.bodies().find(id);
    if (i && room.world.bodies().awake(*i)) ++awake;
  }
  return awake;
}

template <typename Request>
void timeRequest(benchmark::State& state, Request&& request) {
  const Room asleep = sleepingRoom(static_cast<int>(state.range(0)));
  if (awakeBoxes(asleep) != 0) {
    state.SkipWithError("the boxes did not fall asleep");
    return;
  }
  int woken = 0;
  for (auto _ : state) {
    state.PauseTiming();
    Room room = asleep;
    state.ResumeTiming();
    request(room);
    state.PauseTiming();
    woken = awakeBoxes(room);
    state.ResumeTiming();
  }
  state.counters["woken"] = woken;
}

void BM_BodyWake_SetFloorPose(benchmark::State& state) {
  timeRequest(state, [](Room& room) {
    // Tilted by 1 degree about x.
    const Transform tilted{Vec3::Zero(), Quat(Eigen::AngleAxis<Real>(M_PI / 180.0, Vec3::UnitX()))};
    if (!room.world.setBodyPose(room.floor, tilted)) std::abort();
  });
}

void BM_BodyWake_RemoveFloor(benchmark::State& state) {
  timeRequest(state, [](Room& room) {
    if (!room.world.removeBody(room.floor)) std::abort();
  });
}

BENCHMARK(BM_BodyWake_SetFloorPose)->Arg(100)->Arg(1000)->Arg(10000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_BodyWake_RemoveFloor)->Arg(100)->Arg(1000)->Arg(10000)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
