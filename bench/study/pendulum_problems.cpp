// The hinged pendulums: a 1 m, 1 kg rod (1 cm square) on a hinge about y at its top end, released
// at 5 degrees, whole or as four 25 cm segments welded by fixed joints.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <vector>

#include "body_scene.h"

namespace mass_aggregate_sim {
namespace study {
namespace {

using engine::FixedJoint;
using engine::HingeJoint;
using engine::JointEnd;

constexpr Real kAmplitude = 5.0 * M_PI / 180.0;
constexpr Real kHalfWidth = 0.005;
constexpr Real kLength = 1.0;
constexpr Real kMass = 1.0;
constexpr Real kDuration = 20.0;

// The complete elliptic integral of the first kind, K(k) = pi / (2 AGM(1, sqrt(1 - k^2))).
Real ellipticK(const Real k) {
  Real a = 1.0;
  Real b = std::sqrt(1.0 - k * k);
  while (std::abs(a - b) > 1e-15 * a) {
    const Real mean = 0.5 * (a + b);
    b = std::sqrt(a * b);
    a = mean;
  }
  return M_PI / (2.0 * a);
}

// The exact period of the rod, segmented or not (the parallel-axis sums of the segments give the
// whole rod's inertia): about its end I = m ((2 w)^2 + L^2) / 12 + m (L / 2)^2, d = L / 2, and
// T = 4 sqrt(I / (m g d)) K(sin(theta0 / 2)) at amplitude theta0.
Real exactPeriod() {
  const Real d = 0.5 * kLength;
  const Real inertia =
      kMass * (std::pow(2.0 * kHalfWidth, 2) + kLength * kLength) / 12.0 + kMass * d * d;
  return 4.0 * std::sqrt(inertia / (kMass * kG * d)) * ellipticK(std::sin(0.5 * kAmplitude));
}

BodyRun swing(const BodyKnobs& knobs, const int segments) {
  World world = bodyWorld(knobs, kG);
  const Quat turn(Eigen::AngleAxisd(kAmplitude, Vec3::UnitY()));
  const Real half = 0.5 * kLength / segments;
  std::vector<BodyId> ids;
  for (int k = 0; k < segments; ++k) {
    ids.push_back(addBox(world, Vec3(kHalfWidth, kHalfWidth, half), kMass / segments,
                         turn * Vec3(0.0, 0.0, -(2 * k + 1) * half), Material{}, turn));
    bool added = true;
    if (k == 0) {
      HingeJoint hinge;
      hinge.a = JointEnd::inWorld(Vec3::Zero());
      hinge.b = JointEnd::onBody(ids[0], Vec3(0.0, 0.0, half));
      hinge.axis = Vec3::UnitY();
      added = static_cast<bool>(world.addJoint(hinge));
    } else {
      FixedJoint weld;
      weld.a = JointEnd::onBody(ids[k - 1], Vec3(0.0, 0.0, -half));
      weld.b = JointEnd::onBody(ids[k], Vec3(0.0, 0.0, half));
      added = static_cast<bool>(world.addJoint(weld));
    }
    if (!added) std::abort();
  }
  std::vector<std::size_t> parts;
  for (const BodyId id : ids) parts.push_back(*world.bodies().find(id));
  // The centre of mass from the anchor (the origin): its angle from straight down.
  const auto angle = [&] {
    Vec3 centre = Vec3::Zero();
    for (const std::size_t i : parts) centre += world.bodies().position(i);
    return std::atan2(centre.x(), -centre.z());
  };
  // It crosses 0 downwards once a period; linear interpolation between steps times the crossing
  // (its error is O(h^3) there, where the angle's second derivative is 0). The amplitude is the
  // last peak, the vertex of the parabola through the three samples around it.
  std::vector<Real> crossings;
  Real before = NAN;
  Real previous = angle();
  Real last_peak = NAN;
  Real worst_drift = 0.0;
  const int steps = stepsIn(kDuration);
  for (int step = 1; step <= steps; ++step) {
    world.step();
    const Real now = angle();
    if (previous > 0.0 && now <= 0.0) {
      crossings.push_back((step - 1 + previous / (previous - now)) * kBodyDt);
    }
    if (previous > 0.0 && previous > before && previous >= now) {
      last_peak = previous - std::pow(now - before, 2) / (8.0 * (now + before - 2.0 * previous));
    }
    before = previous;
    previous = now;
    const Vec3 hinge_point = world.bodies().pose(parts[0]).apply(Vec3(0.0, 0.0, half));
    worst_drift = std::max(worst_drift, hinge_point.norm());
  }
  const Real period = crossings.size() < 2 ? NAN
                                           : (crossings.back() - crossings.front()) /
                                                 static_cast<Real>(crossings.size() - 1);
  return finishRun(world,
                   {period / exactPeriod() - 1.0, last_peak / kAmplitude - 1.0, worst_drift});
}

std::vector<BodyMetric> pendulumMetrics() {
  return {{"period_error", "period / exact period - 1", {1e-2, 1e-3, 1e-4, 1e-5}},
          {"amplitude_change", "last amplitude in 20 s / 5 degrees - 1", {1e-2, 1e-3}},
          {"anchor_drift", "largest distance of the hinge point from its anchor (m)", {1e-3}}};
}

}  // namespace

BodyProblem hingedPendulum() {
  BodyProblem p;
  p.name = "hinged_pendulum";
  p.description = "1 m rod on a hinge at its end, 5 degrees, 20 s; exact period 1.6388 s";
  p.duration = kDuration;
  p.metrics = pendulumMetrics();
  p.run = [](const BodyKnobs& knobs) { return swing(knobs, 1); };
  return p;
}

BodyProblem weldedPendulum() {
  BodyProblem p;
  p.name = "welded_pendulum";
  p.description = "the same rod as four 25 cm segments welded by fixed joints";
  p.duration = kDuration;
  p.metrics = pendulumMetrics();
  p.run = [](const BodyKnobs& knobs) { return swing(knobs, 4); };
  return p;
}

}  // namespace study
}  // namespace mass_aggregate_sim
