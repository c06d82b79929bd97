// A free body tumbling about its intermediate axis: no torque, so its energy and angular momentum
// must hold while it flips over and back.
#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "body_scene.h"

namespace mass_aggregate_sim {
namespace study {

BodyProblem torqueFreeTumble() {
  constexpr Real kDuration = 20.0;
  BodyProblem p;
  p.name = "torque_free_tumble";
  p.description =
      "free body, inertia diag(1, 2, 3) kg m^2, w = (0.01, 2, 0.01) rad/s (intermediate axis), "
      "no gravity, 20 s";
  p.duration = kDuration;
  p.metrics = {{"energy_drift", "largest |E / E0 - 1|", {1e-6, 1e-9}},
               {"momentum_drift", "largest | |L| / |L0| - 1 |", {1e-6, 1e-9}},
               {"momentum_turn", "largest |L - L0| / |L0| (its direction too)", {1e-2, 1e-3}}};
  p.run = [](const BodyKnobs& knobs) {
    World world = bodyWorld(knobs, 0.0);
    // 12 kg, sqrt(2) x 1 m and (almost) no thickness: I = m (b^2 + c^2) / 12 ... = (1, 2, 3).
    const BodyId body =
        addBox(world, Vec3(0.5 * std::sqrt(2.0), 0.5, 1e-7), 12.0, Vec3::Zero(), Material{});
    if (!world.setBodyVelocity(body, Vec3::Zero(), Vec3(0.01, 2.0, 0.01))) std::abort();
    const Vec3 l0 = world.angularMomentum();
    const Real e0 = world.kineticEnergy();
    Real worst_e = 0.0;
    Real worst_l = 0.0;
    Real worst_turn = 0.0;
    const int steps = stepsIn(kDuration);
    for (int step = 0; step < steps; ++step) {
      world.step();
      const Vec3 l = world.angularMomentum();
      worst_e = std::max(worst_e, std::abs(world.kineticEnergy() / e0 - 1.0));
      worst_l = std::max(worst_l, std::abs(l.norm() / l0.norm() - 1.0));
      worst_turn = std::max(worst_turn, (l - l0).norm() / l0.norm());
    }
    return finishRun(world, {worst_e, worst_l, worst_turn});
  };
  return p;
}

}  // namespace study
}  // namespace mass_aggregate_sim
