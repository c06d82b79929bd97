// The point spring kind (point_spring.h): validation, force and energy.
#include "mass_aggregate_sim/engine/forces/point_spring.h"

#include "engine/core/checks.h"
#include "engine/forces/body_force_stage.h"
#include "engine/forces/force_laws.h"
#include "engine/joints/joint_ends.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

bool still(const JointEnd& end, const JointScene& scene) {
  if (end.isBody()) {
    return scene.bodies.type(scene.bodies.denseIndexUnchecked(end.body)) == BodyType::kFixed;
  }
  if (end.isParticle()) {
    return scene.particles.inverseMasses()[static_cast<Eigen::Index>(
               scene.particles.denseIndexUnchecked(end.particle))] <= 0.0;
  }
  return true;
}

}  // namespace

Status BodyForceKind<PointSpring>::validate(PointSpring& spring, const JointScene& scene) {
  Status valid = checkJointEnd(spring.a, scene, "a", false);
  if (valid) valid = checkJointEnd(spring.b, scene, "b", false);
  if (!valid) return valid;
  if (!spring.a.isBody() && !spring.b.isBody()) {
    return Status::error(
        "a point spring needs a body at one end at least (particles alone use a spring)");
  }
  if (spring.a.isBody() && spring.b.isBody() && spring.a.body == spring.b.body) {
    return Status::error("a point spring's ends are on the same body");
  }
  if (still(spring.a, scene) && still(spring.b, scene)) {
    return Status::error("neither end of the point spring can move");
  }
  if (!finiteNonNegative(spring.stiffness)) {
    return Status::error("stiffness must be finite and >= 0");
  }
  if (!finiteNonNegative(spring.damping)) return Status::error("damping must be finite and >= 0");
  if (!std::isfinite(spring.rest_length)) return Status::error("rest_length is not finite");
  if (spring.rest_length < 0.0) {
    const BodyForceScene ends(scene.bodies, scene.particles, nullptr, 0.0);
    spring.rest_length = (ends.end(spring.a).position - ends.end(spring.b).position).norm();
  }
  return Status::ok();
}

std::vector<BodyId> BodyForceKind<PointSpring>::bodiesOf(const PointSpring& spring) {
  std::vector<BodyId> bodies;
  for (const JointEnd* end : {&spring.a, &spring.b}) {
    if (end->isBody()) bodies.push_back(end->body);
  }
  return bodies;
}

void BodyForceKind<PointSpring>::accumulate(const std::vector<PointSpring>& springs,
                                            const BodyForceScene& scene, BodyForceSums& sums) {
  for (const PointSpring& spring : springs) {
    const ForceEnd a = scene.end(spring.a);
    const ForceEnd b = scene.end(spring.b);
    Vec3 f;
    if (!springForce(a.position.data(), b.position.data(), a.velocity.data(), b.velocity.data(),
                     spring.stiffness, spring.rest_length, spring.damping, spring.pull_only,
                     f.data())) {
      continue;
    }
    sums.add(a, f);
    sums.add(b, -f);
  }
}

DrawnSegment BodyForceKind<PointSpring>::drawn(const PointSpring& spring, const BodyStore& bodies,
                                               const ParticleStore& particles) {
  const BodyForceScene scene(bodies, particles, nullptr, 0.0);
  const Vec3 a = scene.end(spring.a).position;
  const Vec3 b = scene.end(spring.b).position;
  const Real extension = (a - b).norm() - spring.rest_length;
  const Real tension = springTension(extension, spring.stiffness, spring.pull_only);
  return DrawnSegment{a, b, tension};
}

Real BodyForceKind<PointSpring>::energy(const std::vector<PointSpring>& springs,
                                        const BodyForceScene& scene) {
  Real energy = 0.0;
  for (const PointSpring& spring : springs) {
    const Real extension =
        (scene.end(spring.a).position - scene.end(spring.b).position).norm() - spring.rest_length;
    if (spring.pull_only && extension <= 0.0) continue;
    // k (l - L)^2 / 2
    energy += 0.5 * spring.stiffness * extension * extension;
  }
  return energy;
}

void BodyForceKind<PointSpring>::stiffness(const std::vector<PointSpring>& springs,
                                           const BodyForceScene& scene,
                                           std::vector<BodyStiffnessTerm>& terms) {
  for (const PointSpring& spring : springs) {
    BodyStiffnessTerm term;
    term.id = spring.id;
    term.stiffness = spring.stiffness;
    term.damping = spring.damping;
    const JointEnd* ends[2] = {&spring.a, &spring.b};
    for (int e = 0; e < 2; ++e) {
      term.mobility[e] = scene.mobility(*ends[e]);
      if (ends[e]->isParticle()) term.particle[e] = scene.end(*ends[e]).particle;
    }
    terms.push_back(term);
  }
}

}  // namespace engine
}  // namespace mass_aggregate_sim
