// A unit cube dropped flat onto the ground with restitution 0.5: it must leave at e times the
// speed it arrived with.
#include <algorithm>
#include <cmath>

#include "body_scene.h"

namespace mass_aggregate_sim {
namespace study {

BodyProblem cubeBounce() {
  constexpr Real kRestitution = 0.5;
  constexpr Real kDrop = 1.0;  // m from the bottom face to the ground
  // It lands at sqrt(2 h / g) = 0.452 s and, leaving at 2.215 m/s, flies until 0.903 s.
  constexpr Real kInFlight = 0.6;
  BodyProblem p;
  p.name = "cube_bounce";
  p.description = "unit cube (1 kg) dropped flat from 1 m, restitution 0.5; rebound 2.215 m/s";
  p.duration = kInFlight;
  p.metrics = {{"rebound_error", "rebound speed / (e sqrt(2 g h)) - 1", {1e-2, 3e-3, 1e-3}},
               {"spin", "largest |w| (rad/s): a flat drop must not turn the cube", {}}};
  p.run = [](const BodyKnobs& knobs) {
    World world = bodyWorld(knobs, kG);
    const Material material{kRestitution, 0.5};
    addGround(world, material);
    const BodyId cube =
        addBox(world, Vec3::Constant(0.5), 1.0, Vec3(0.0, 0.0, 0.5 + kDrop), material);
    const std::size_t i = *world.bodies().find(cube);
    Real worst_w = 0.0;
    const int steps = stepsIn(kInFlight);
    for (int step = 0; step < steps; ++step) {
      world.step();
      worst_w = std::max(worst_w, world.bodies().angularVelocity(i).norm());
    }
    // In flight, clear of the ground, a body moves exactly for a constant acceleration
    // (body_stages.cpp), so v^2 + 2 g (z - 0.5) is the speed it left the ground with. A cube
    // still on the ground did not bounce.
    const Real v = world.bodies().linearVelocity(i).z();
    const Real height = world.bodies().position(i).z() - 0.5;
    const Real rebound = height > 0.05 ? std::sqrt(v * v + 2.0 * kG * height) : 0.0;
    const Real exact = kRestitution * std::sqrt(2.0 * kG * kDrop);
    return finishRun(world, {rebound / exact - 1.0, worst_w});
  };
  return p;
}

}  // namespace study
}  // namespace mass_aggregate_sim
