#pragma once
// The body solver's contact rows (soft step): prepared once per step, then each substep warm
// started, solved with the bias that removes overlap, and relaxed without it; the impulses kept
// for the next step's warm start.
//
// Restitution is an impact: the first biased pass in which a contact's points would close within
// the substep faster than the threshold, the contact's points are solved together (a block solve
// of their normal rows) so that each separates at e times the speed it closed at, and its normal
// rows then rest for the step. Resolved as they come, impacts pass along a row of touching-close
// bodies one by one (Newton's cradle), and a face that lands flat bounces without turning.

#include <vector>

#include "engine/bodies/body_contact.h"
#include "engine/bodies/contact_constraint.h"
#include "mass_aggregate_sim/engine/bodies/body_settings.h"

namespace mass_aggregate_sim {
namespace engine {

// One contact's sides as the solver sees them: solver bodies (kNoBody: never moves) and the
// centres of mass the anchors are measured from.
struct ContactSides {
  std::int32_t a = kNoBody;
  std::int32_t b = kNoBody;
  Vec3 center_a = Vec3::Zero();
  Vec3 center_b = Vec3::Zero();
};

// A tangent basis of n: t0 = a unit vector perpendicular to n chosen from n alone (the same n
// always gives the same basis), t1 = n x t0.
void tangentBasis(const Vec3& n, Vec3& t0, Vec3& t1);

ContactConstraint prepareContact(const BodyContact& contact, std::uint32_t index,
                                 const ContactSides& sides, const std::vector<SolverBody>& bodies,
                                 const Softness& softness);
void warmStartContacts(std::vector<ContactConstraint>& constraints,
                       std::vector<SolverBody>& bodies);
struct ContactPass {
  Real h;
  bool use_bias;
  Real max_push_speed;
  Real restitution_threshold;
  Real slop;
};
// One pass over the contacts; with use_bias the overlap is pushed out (softly, at most
// max_push_speed), speculative gaps may close no faster than they can within h, and impacts are
// resolved.
void solveContacts(std::vector<ContactConstraint>& constraints, std::vector<SolverBody>& bodies,
                   const ContactPass& pass);
// The impulses back into the contacts, for the next step's warm start.
void storeImpulses(const std::vector<ContactConstraint>& constraints,
                   std::vector<BodyContact>& contacts);

}  // namespace engine
}  // namespace mass_aggregate_sim
