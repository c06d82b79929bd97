// The first guess of a resting contact's impulses (guessRestingLoads): each body's load, its
// weight and what rests on it where it rests, shared between two level supports so that their
// moments about where the load acts cancel (the lever rule); evenly between supports that are
// not both level.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "engine/bodies/contact_solver.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

constexpr Real kG = 9.81;
constexpr Real kH = 1.0 / 240.0;
constexpr Real kDt = 1.0 / 60.0;
const Vec3 kGravity(0.0, 0.0, -kG);

// Upper body `upper` rests on `lower` (kNoBody: the ground) through a face patch of four points
// at x in [x - 0.1, x + 0.1], y = +-0.5, z = -0.5 from the upper body's centre; `lower_offset`
// is the upper centre from the lower's. `tilt` turns the normal about y away from straight down.
ContactConstraint restingOn(const std::int32_t upper, const std::int32_t lower, const Real x,
                            const Vec3& lower_offset, const Real tilt = 0.0) {
  ContactConstraint c;
  c.a = upper;
  c.b = lower;
  c.normal = Vec3(std::sin(tilt), 0.0, -std::cos(tilt));
  c.count = 4;
  const Real xs[4] = {x - 0.1, x + 0.1, x + 0.1, x - 0.1};
  const Real ys[4] = {-0.5, -0.5, 0.5, 0.5};
  for (int k = 0; k < 4; ++k) {
    c.points[k].r_a = Vec3(xs[k], ys[k], -0.5);
    c.points[k].r_b = c.points[k].r_a + lower_offset;
  }
  return c;
}

std::vector<SolverBody> unitMasses(const std::size_t n) {
  std::vector<SolverBody> bodies(n);
  for (SolverBody& body : bodies) {
    body.inverse_mass = 1.0;
    body.inverse_inertia = 6.0 * Mat3::Identity();
  }
  return bodies;
}

Real impulse(const ContactConstraint& c) {
  Real sum = 0.0;
  for (int k = 0; k < c.count; ++k) sum += c.points[k].normal_impulse;
  return sum;
}

// The moment about y of contact c's impulses on its a side, about a's centre.
Real momentOnA(const ContactConstraint& c) {
  Real moment = 0.0;
  for (int k = 0; k < c.count; ++k) {
    moment += c.points[k].r_a.cross(-c.points[k].normal_impulse * c.normal).y();
  }
  return moment;
}

// A body on two fixed supports whose centres are 0.3 left and 0.2 right of its own: 0.2 / 0.5 of
// its weight on the left one, 0.3 / 0.5 on the right; their moments cancel. Split evenly they
// left it 0.05 m g h of moment.
TEST(RestingLoads, ABodyOnTwoLevelSupportsSplitsItsWeightByTheLeverRule) {
  const std::vector<SolverBody> bodies = unitMasses(1);
  std::vector<ContactConstraint> constraints = {restingOn(0, kNoBody, -0.3, Vec3::Zero()),
                                                restingOn(0, kNoBody, 0.2, Vec3::Zero())};
  RestingLoadBuffers buffers;
  guessRestingLoads(constraints, bodies, {1.0}, kGravity, kH, kDt, buffers);
  const Real weight = kG * kH;
  EXPECT_NEAR(impulse(constraints[0]), 0.4 * weight, 1e-15);
  EXPECT_NEAR(impulse(constraints[1]), 0.6 * weight, 1e-15);
  EXPECT_NEAR(momentOnA(constraints[0]) + momentOnA(constraints[1]), 0.0, 1e-16);
}

// The load a body passes down acts where it rests: a box resting on the right half of a lower
// one (0.2 right of its centre) puts the lower one's load (2 m g h) 0.1 right of its centre,
// and the lower one's supports (0.3 left, 0.2 right) take 0.2 and 0.8 of it.
TEST(RestingLoads, ALoadFromAboveActsWhereItRests) {
  const std::vector<SolverBody> bodies = unitMasses(2);
  std::vector<ContactConstraint> constraints = {restingOn(0, kNoBody, -0.3, Vec3::Zero()),
                                                restingOn(0, kNoBody, 0.2, Vec3::Zero()),
                                                restingOn(1, 0, -0.0, Vec3(0.2, 0.0, 1.0))};
  RestingLoadBuffers buffers;
  guessRestingLoads(constraints, bodies, {1.0, 2.0}, kGravity, kH, kDt, buffers);
  const Real weight = kG * kH;
  EXPECT_NEAR(impulse(constraints[2]), weight, 1e-15);
  EXPECT_NEAR(impulse(constraints[0]), 0.4 * weight, 1e-15);
  EXPECT_NEAR(impulse(constraints[1]), 1.6 * weight, 1e-15);
}

// A load beyond a support rests on that support alone (no support pulls).
TEST(RestingLoads, ALoadBeyondASupportRestsOnItAlone) {
  const std::vector<SolverBody> bodies = unitMasses(1);
  std::vector<ContactConstraint> constraints = {restingOn(0, kNoBody, -0.4, Vec3::Zero()),
                                                restingOn(0, kNoBody, -0.2, Vec3::Zero())};
  RestingLoadBuffers buffers;
  guessRestingLoads(constraints, bodies, {1.0}, kGravity, kH, kDt, buffers);
  EXPECT_EQ(impulse(constraints[0]), 0.0);
  EXPECT_NEAR(impulse(constraints[1]), kG * kH, 1e-15);
}

// A support tilted beyond 10 degrees also pushes sideways, a moment the lever rule leaves out:
// the load is split evenly.
TEST(RestingLoads, SupportsThatAreNotLevelShareEvenly) {
  const std::vector<SolverBody> bodies = unitMasses(1);
  std::vector<ContactConstraint> constraints = {restingOn(0, kNoBody, -0.3, Vec3::Zero(), 0.3),
                                                restingOn(0, kNoBody, 0.2, Vec3::Zero())};
  RestingLoadBuffers buffers;
  guessRestingLoads(constraints, bodies, {1.0}, kGravity, kH, kDt, buffers);
  EXPECT_NEAR(impulse(constraints[0]), 0.5 * kG * kH, 1e-15);
  EXPECT_NEAR(impulse(constraints[1]), 0.5 * kG * kH, 1e-15);
}

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
