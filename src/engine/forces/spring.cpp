// The spring kind (spring.h): springs and bungees, between particles or to an anchor. Their hot
// loops are in spring_runs.cpp.
#include "mass_aggregate_sim/engine/forces/spring.h"

#include <algorithm>

#include "engine/core/checks.h"
#include "engine/forces/force_evaluation.h"
#include "engine/forces/force_laws.h"
#include "engine/integrators/implicit_system.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

// dF_a/dx_a of F_a = -k (l - L) n, d = x_a - x_b, n = d / l: -k (n n^T + (1 - L/l) (I - n n^T)),
// with the transverse factor clamped at 0 (a compressed spring's transverse term would make the
// system indefinite); D = dF_a/dv_a = -c n n^T for the dashpot.
void springJacobians(const Vec3& d, const Spring& spring, Mat3& k, Mat3& dv) {
  const Real length = d.norm();
  if (length < kMinSpringLength || (spring.pull_only && length <= spring.rest_length)) {
    k.setZero();
    dv.setZero();
    return;
  }
  const Vec3 n = d / length;
  const Mat3 nn = n * n.transpose();
  const Real transverse = std::max(Real{0.0}, 1.0 - spring.rest_length / length);
  k = -spring.stiffness * (nn + transverse * (Mat3::Identity() - nn));
  dv = -spring.damping * nn;
}

}  // namespace

DrawnSegment ForceKind<Spring>::drawn(const Spring& spring, const ParticleStore& particles) {
  const auto x = particles.positions();
  const Vec3 a = x.col(particles.denseIndexUnchecked(spring.a));
  const Vec3 b =
      spring.anchored() ? spring.anchor : Vec3(x.col(particles.denseIndexUnchecked(spring.b)));
  const Real extension = (a - b).norm() - spring.rest_length;
  const Real tension = springTension(extension, spring.stiffness, spring.pull_only);
  return DrawnSegment{a, b, tension};
}

Status ForceKind<Spring>::validate(Spring& spring, const ParticleStore& particles) {
  if (spring.anchored()) {
    const Status particle = particles.checkReference(spring.a, "particle");
    if (!particle) return particle;
    if (!spring.anchor.allFinite()) return Status::error("anchor is not finite");
  } else {
    Status end = particles.checkReference(spring.a, "a");
    if (end) end = particles.checkReference(spring.b, "b");
    if (!end) return end;
    if (spring.a == spring.b) return Status::error("a and b must be different particles");
  }
  if (!finiteNonNegative(spring.stiffness)) {
    return Status::error("stiffness must be finite and >= 0");
  }
  if (!finiteNonNegative(spring.rest_length)) {
    return Status::error("rest_length must be finite and >= 0");
  }
  if (!finiteNonNegative(spring.damping)) return Status::error("damping must be finite and >= 0");
  return Status::ok();
}

void ForceKind<Spring>::accumulate(const std::vector<Spring>& springs, const ForceEvaluation& e,
                                   Eigen::Ref<Vec3Array> force, Real* elastic) {
  accumulateDenseSprings(e.springs, e.x, e.v, force, elastic);
}

Real ForceKind<Spring>::energy(const std::vector<Spring>& springs, const ForceEvaluation& e) {
  return denseSpringEnergy(e.springs, ConstVec3Map(e.x.data(), 3, e.x.cols()));
}

void ForceKind<Spring>::linearise(const std::vector<Spring>& springs, ImplicitSystem& system) {
  const auto& x = system.positions();
  Mat3 k;
  Mat3 d;
  for (const Spring& spring : springs) {
    const std::size_t a = system.index(spring.a);
    if (spring.anchored()) {
      springJacobians(x.col(a) - spring.anchor, spring, k, d);
      system.addSingle(a, k, d);
    } else {
      const std::size_t b = system.index(spring.b);
      springJacobians(x.col(a) - x.col(b), spring, k, d);
      system.addPair(a, b, k, d);
    }
  }
}

void ForceKind<Spring>::stiffness(const std::vector<Spring>& springs,
                                  const ParticleStore& particles,
                                  std::vector<StiffnessTerm>& terms) {
  for (const Spring& spring : springs) {
    StiffnessTerm term;
    term.id = spring.id;
    term.a = particles.denseIndexUnchecked(spring.a);
    if (!spring.anchored()) term.b = particles.denseIndexUnchecked(spring.b);
    term.stiffness = spring.stiffness;
    term.damping = spring.damping;
    terms.push_back(term);
  }
}

}  // namespace engine
}  // namespace mass_aggregate_sim
