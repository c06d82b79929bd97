// Semi-implicit (symplectic) Euler, the default: v' = (v + a h) d^h, x' = x + v' h. First order,
// symplectic. Its update is one vectorised pass (semi_implicit_pass.cpp) that also sums the
// energy guard's energies, or probes the state for the divergence check, when nothing moves the
// particles after it.
#include "engine/integrators/integrators.h"
#include "engine/integrators/semi_implicit_pass.h"
#include "engine/world/step_context.h"

namespace mass_aggregate_sim {
namespace engine {

void integrateSemiImplicitEuler(StepContext& ctx) {
  ParticleStore& particles = ctx.particles;
  auto x = particles.positions();
  auto v = particles.velocities();
  Vec3Array& a = ctx.integration.acceleration;
  const bool has_forces = !ctx.generators.empty() || ctx.scene.external;
  // The generator forces at this state, from the guard's evaluation ahead when it made them,
  // else from the force stage; the pass divides by the masses and adds the uniform accelerations.
  if (has_forces && !ctx.caches.forces.takeForcesAhead(ctx.scene, a)) {
    if (ctx.scene.external) {
      a = particles.forces();
    } else {
      a.setZero();
    }
    ctx.caches.forces.generatorForces(ctx.scene, x, v, ctx.h, a);
  }
  const Vec3& gravity = ctx.config.gravity;
  const Real g[3] = {gravity.x(), gravity.y(), gravity.z()};
  SemiImplicitInputs in;
  in.count = particles.size();
  in.h = ctx.h;
  in.gravity = g;
  in.inverse_mass = particles.inverseMasses().data();
  in.mobility = particles.mobility().data();
  in.own_acceleration = particles.anyOwnAcceleration() ? particles.accelerations().data() : nullptr;
  in.damping_factor = ctx.caches.damping.decay.data();
  in.mass = ctx.caches.stability.mass.data();
  const PassMeasure measure = ctx.pass_sums_energies   ? PassMeasure::kEnergies
                              : ctx.pass_probes_finite ? PassMeasure::kFiniteProbe
                                                       : PassMeasure::kNothing;
  PassMeasurements measured;
  // The contact phase is the one stage after the pass that reads the substep's accelerations.
  const bool keep_acceleration = ctx.contacts_active;
  semiImplicitEulerPass(in, has_forces, keep_acceleration, a.data(), x.data(), v.data(), measure,
                        measured);
  ctx.caches.pass_energies_valid = measure == PassMeasure::kEnergies;
  if (ctx.caches.pass_energies_valid) ctx.caches.pass_energies = measured.energies.sums(g);
  ctx.caches.pass_finite_valid = measure == PassMeasure::kFiniteProbe;
  ctx.caches.pass_finite = measured.all_finite;
}

}  // namespace engine
}  // namespace mass_aggregate_sim
