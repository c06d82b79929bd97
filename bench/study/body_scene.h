#pragma once
// What the body problems build their scenes from: z up, g = 9.81, the study's step and knobs.

#include <vector>

#include "body_problems.h"

namespace mass_aggregate_sim {
namespace study {

using engine::BodyId;
using engine::Material;
using engine::Quat;
using engine::Vec3;
using engine::World;

constexpr Real kG = 9.81;

// A world stepping at kBodyDt with the knobs on the default body settings, gravity g along -z.
// Sleeping is off: a resting island would cost nothing and hide what the solver does.
World bodyWorld(const BodyKnobs& knobs, Real g);
// A dynamic box of the given half extents and mass; aborts when the engine refuses it.
BodyId addBox(World& world, const Vec3& half_extents, Real mass, const Vec3& position,
              const Material& material, const Quat& orientation = Quat::Identity());
// The plane z = 0.
void addGround(World& world, const Material& material);
// Steps of kBodyDt in `seconds`.
int stepsIn(Real seconds);
// The run's values; diverged when the world reported a divergence or a value is not finite.
BodyRun finishRun(const World& world, std::vector<Real> values);

}  // namespace study
}  // namespace mass_aggregate_sim
