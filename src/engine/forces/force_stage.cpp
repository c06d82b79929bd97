#include "engine/forces/force_stage.h"

#include "engine/forces/body_force_stage.h"
#include "engine/forces/particle_acceleration.h"
#include "engine/forces/stiff_spring_stage.h"
#include "engine/solver/contact_workspace.h"
#include "engine/world/step_context.h"

namespace mass_aggregate_sim {
namespace engine {

const DenseSprings& ForceStage::springs(const ForceScene& scene) {
  // Springs change only through add and remove (a new generators version), dense indices only
  // through the store's layout.
  if (springs_layout_ != scene.particles.layoutVersion() ||
      springs_version_ != scene.generators_version) {
    springs_ = resolveDenseSprings(scene.generators.of<Spring>(), scene.particles);
    springs_layout_ = scene.particles.layoutVersion();
    springs_version_ = scene.generators_version;
  }
  return springs_;
}

void ForceStage::generatorForces(const ForceScene& scene, const Eigen::Ref<const Vec3Array>& x,
                                 const Eigen::Ref<const Vec3Array>& v, const Real h,
                                 Eigen::Ref<Vec3Array> force, Real* elastic) {
  const ForceEvaluation e{scene.particles, x, v, scene.gravity.norm(), h, springs(scene)};
  accumulateGeneratorForces(scene.generators, e, force, elastic);
}

void ForceStage::accelerations(const ForceScene& scene, const Eigen::Ref<const Vec3Array>& x,
                               const Eigen::Ref<const Vec3Array>& v, const Real h,
                               Eigen::Ref<Vec3Array> out, const bool with_external) {
  const ParticleStore& particles = scene.particles;
  const std::size_t n = particles.size();
  const auto inverse_mass = particles.inverseMasses();
  const auto mobility = particles.mobility();
  const auto own_acceleration = particles.accelerations();
  // Without any, a constant +0 instead of reading them (as the semi-implicit Euler pass does).
  const bool any_own = particles.anyOwnAcceleration();
  const Vec3 g = scene.gravity;
  const bool external = with_external && scene.external;
  const bool forces = !scene.generators.empty() || external;
  if (forces) {
    if (external) {
      out = particles.forces();
    } else {
      out.setZero();
    }
    generatorForces(scene, x, v, h, out);
  }
  for (std::size_t i = 0; i < n; ++i) {
    for (Eigen::Index c = 0; c < 3; ++c) {
      const Real own = any_own ? own_acceleration(c, i) : 0.0;
      const Real uniform = uniformAcceleration(mobility[i], g[c], own);
      out(c, i) = forces ? particleAcceleration(out(c, i), inverse_mass[i], uniform) : uniform;
    }
  }
}

Real ForceStage::evaluateAhead(const ForceScene& scene, const Real h) {
  const auto x = scene.particles.positions();
  const auto v = scene.particles.velocities();
  ahead_.setZero(3, x.cols());
  Real elastic = 0.0;
  generatorForces(scene, x, v, h, ahead_, &elastic);
  ahead_valid_ = true;
  return elastic;
}

bool ForceStage::takeForcesAhead(const ForceScene& scene, Vec3Array& force) {
  const bool valid = ahead_valid_ && !scene.external && ahead_.cols() == force.cols();
  ahead_valid_ = false;
  if (valid) force.swap(ahead_);
  return valid;
}

void ForceStage::externalAccelerations(const ForceScene& scene, Vec3Array& out) {
  const std::size_t n = scene.particles.size();
  out.resize(3, static_cast<Eigen::Index>(n));
  if (!scene.external) {
    out.setZero();
    return;
  }
  const auto force = scene.particles.forces();
  const auto inverse_mass = scene.particles.inverseMasses();
  for (std::size_t i = 0; i < n; ++i) out.col(i) = force.col(i) * inverse_mass[i];
}

Real ForceStage::elasticEnergy(const ForceScene& scene) {
  const Eigen::Ref<const Vec3Array> x(scene.particles.positions());
  const Eigen::Ref<const Vec3Array> v(scene.particles.velocities());
  const ForceEvaluation e{scene.particles, x, v, scene.gravity.norm(), 0.0, springs(scene)};
  return generatorPotentialEnergy(scene.generators, e);
}

void applyForces(StepContext& ctx) {
  applyBodyForces(ctx);
  ParticleStore& particles = ctx.particles;
  if (ctx.contacts_active && ctx.collisions.continuous) {
    ctx.contacts.substep_start = particles.positions();
  }
  const auto& stiff = ctx.generators.of<StiffSpring>();
  if (stiff.empty()) {
    ctx.caches.stiff.clear();
    return;
  }
  Vec3Array& total = ctx.caches.stage_a[2];
  total.resize(3, static_cast<Eigen::Index>(particles.size()));
  ctx.accelerations(particles.positions(), particles.velocities(), total);
  prepareStiffSprings(stiff, particles, total, ctx.h, ctx.caches.stiff);
}

}  // namespace engine
}  // namespace mass_aggregate_sim
