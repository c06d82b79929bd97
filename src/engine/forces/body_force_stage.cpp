#include "engine/forces/body_force_stage.h"

#include <type_traits>

#include "engine/bodies/body_workspace.h"
#include "engine/world/step_context.h"

namespace mass_aggregate_sim {
namespace engine {

const SolverBody* BodyForceScene::solverBody(const std::size_t dense) const {
  if (!ws_ || dense >= ws_->solver_of_body.size()) return nullptr;
  const std::int32_t k = ws_->solver_of_body[dense];
  return k == kNoBody ? nullptr : &ws_->solver[static_cast<std::size_t>(k)];
}

ForceEnd BodyForceScene::end(const JointEnd& end) const {
  ForceEnd out;
  if (end.isParticle()) {
    const std::size_t p = particles_.denseIndexUnchecked(end.particle);
    out.position = particles_.positions().col(static_cast<Eigen::Index>(p));
    out.velocity = particles_.velocities().col(static_cast<Eigen::Index>(p));
    out.particle = static_cast<std::int64_t>(p);
    return out;
  }
  if (!end.isBody()) {
    out.position = end.point;
    return out;
  }
  const std::size_t i = bodies_.denseIndexUnchecked(end.body);
  const Vec3 local = bodies_.massFrame(i).inverse().apply(end.point);
  const SolverBody* sb = solverBody(i);
  if (sb) {
    // The step has moved the centre by dp and turned the body by dq so far: q = dq q0.
    out.r = (sb->dq * bodies_.orientation(i)) * local;
    out.position = bodies_.position(i) + sb->dp + out.r;
    out.velocity = sb->velocityAt(out.r);
    out.solver = ws_->solver_of_body[i];
  } else {
    out.r = bodies_.orientation(i) * local;
    out.position = bodies_.position(i) + out.r;
    out.velocity = bodies_.velocityAt(i, out.position);
  }
  return out;
}

Real BodyForceScene::mobility(const JointEnd& end) const {
  if (end.isParticle()) {
    const std::size_t p = particles_.denseIndexUnchecked(end.particle);
    return particles_.inverseMasses()[static_cast<Eigen::Index>(p)];
  }
  if (!end.isBody()) return 0.0;
  const std::size_t i = bodies_.denseIndexUnchecked(end.body);
  const Vec3 r = bodies_.massFrame(i).inverse().apply(end.point);
  return bodies_.inverseMass(i) + r.squaredNorm() * bodies_.inversePrincipalInertia(i).maxCoeff();
}

ForceEnd BodyForceScene::centre(const BodyId body) const {
  ForceEnd out;
  const std::size_t i = bodies_.denseIndexUnchecked(body);
  const SolverBody* sb = solverBody(i);
  out.position = bodies_.position(i);
  if (sb) {
    out.position += sb->dp;
    out.velocity = sb->v;
    out.solver = ws_->solver_of_body[i];
  } else {
    out.velocity = bodies_.linearVelocity(i);
  }
  return out;
}

Transform BodyForceScene::massPose(const BodyId body) const {
  const std::size_t i = bodies_.denseIndexUnchecked(body);
  const SolverBody* sb = solverBody(i);
  if (!sb) return Transform{bodies_.position(i), bodies_.orientation(i)};
  return Transform{bodies_.position(i) + sb->dp, sb->dq * bodies_.orientation(i)};
}

Vec3 BodyForceScene::angularVelocity(const BodyId body) const {
  const std::size_t i = bodies_.denseIndexUnchecked(body);
  const SolverBody* sb = solverBody(i);
  return sb ? sb->w : bodies_.angularVelocity(i);
}

void BodyForceSums::add(const ForceEnd& end, const Vec3& f) {
  if (end.solver != kNoBody) {
    const auto k = static_cast<std::size_t>(end.solver);
    force_[k] += f;
    torque_[k] += end.r.cross(f);
  } else if (end.particle >= 0 && particle_force_) {
    particle_force_->col(static_cast<Eigen::Index>(end.particle)) += f;
  }
}

void BodyForceSums::addTorque(const ForceEnd& end, const Vec3& torque) {
  if (end.solver != kNoBody) torque_[static_cast<std::size_t>(end.solver)] += torque;
}

bool bodyForcesReachParticles(const BodyForceGenerators& generators) {
  bool reach = false;
  generators.forEach([&](const auto& kind) {
    using Kind = typename std::decay_t<decltype(kind)>::value_type;
    for (const auto& generator : kind) {
      reach = reach || BodyForceKind<Kind>::reachesParticle(generator);
    }
  });
  return reach;
}

Real bodyGeneratorEnergy(const BodyForceGenerators& generators, const BodyStore& bodies,
                         const ParticleStore& particles) {
  const BodyForceScene scene(bodies, particles, nullptr, 0.0);
  Real energy = 0.0;
  generators.forEach([&](const auto& kind) {
    using Kind = typename std::decay_t<decltype(kind)>::value_type;
    if (!kind.empty()) energy += BodyForceKind<Kind>::energy(kind, scene);
  });
  return energy;
}

void markJoinedBodies(const BodyForceGenerators& generators, const BodyStore& bodies,
                      std::vector<std::uint8_t>& busy) {
  generators.forEach([&](const auto& kind) {
    using Kind = typename std::decay_t<decltype(kind)>::value_type;
    for (const auto& generator : kind) {
      if (!BodyForceKind<Kind>::joins(generator)) continue;
      for (const BodyId body : BodyForceKind<Kind>::bodiesOf(generator)) {
        busy[bodies.denseIndexUnchecked(body)] = 1;
      }
    }
  });
}

void applyBodyForces(StepContext& ctx) {
  if (!ctx.bodies) return;
  BodyWorkspace& ws = *ctx.body_ws;
  if (!ctx.body_generators || ctx.body_generators->empty()) {
    ws.generator_force.clear();
    ws.generator_torque.clear();
    return;
  }
  ws.generator_force.assign(ws.first_particle, Vec3::Zero());
  ws.generator_torque.assign(ws.first_particle, Vec3::Zero());
  ParticleStore& particles = ctx.particles;
  const bool reach = ctx.body_forces_reach_particles;
  if (reach) {
    // The user's forces hold for the whole step; these change every substep.
    if (ctx.substep == 0) ws.user_particle_forces = particles.forces();
    ws.particle_forces = ws.user_particle_forces;
  }
  const BodyForceScene scene(*ctx.bodies, particles, &ws, ctx.config.gravity.norm());
  BodyForceSums sums(ws.generator_force, ws.generator_torque,
                     reach ? &ws.particle_forces : nullptr);
  ctx.body_generators->forEach([&](const auto& kind) {
    using Kind = typename std::decay_t<decltype(kind)>::value_type;
    if (!kind.empty()) BodyForceKind<Kind>::accumulate(kind, scene, sums);
  });
  if (reach) particles.forces() = ws.particle_forces;
}

}  // namespace engine
}  // namespace mass_aggregate_sim
