#pragma once
// The body solver's contact rows (soft step): prepared once per step, then each substep warm
// started, solved with the bias that removes overlap, and relaxed without it; the impulses kept
// for the next step's warm start.
//
// Restitution is an impact: the first substep in which a contact's points would close within it
// faster than the threshold (judged before the warm start, at the speeds the bodies arrive with),
// the contact's points are solved together (a block solve of their normal rows) so that each
// separates at e times the speed it closed at, and its normal rows then rest for the substep
// (holding from zero in the next ones, as any contact's). Resolved as they come, impacts pass along
// a row of touching-close bodies one by one (Newton's cradle), and a face that lands flat bounces
// without turning.

#include <cstdint>
#include <vector>

#include "engine/bodies/body_contact.h"
#include "engine/bodies/contact_constraint.h"
#include "mass_aggregate_sim/engine/bodies/body_settings.h"

namespace mass_aggregate_sim {
namespace engine {

// One contact's sides as the solver sees them: solver bodies (kNoBody: never moves), the
// centres of mass the anchors are measured from, and each side shape's rounding
// (BodyShapeKind::rounding; 0 for a collider or a particle, which do not turn).
struct ContactSides {
  std::int32_t a = kNoBody;
  std::int32_t b = kNoBody;
  Vec3 center_a = Vec3::Zero();
  Vec3 center_b = Vec3::Zero();
  Real rounding_a = 0.0;
  Real rounding_b = 0.0;
};

// A tangent basis of n: t0 = a unit vector perpendicular to n chosen from n alone (the same n
// always gives the same basis), t1 = n x t0.
void tangentBasis(const Vec3& n, Vec3& t0, Vec3& t1);

// Reads the contact's manifold and carried impulses into `c`, a default ContactConstraint made
// where it is kept (a row is most of a kilobyte: built in place, it is not copied); keeps the
// coupled mass's pseudo-inverse in `inverted` (one of the contact's) so that a resting contact
// whose mass has not changed is not inverted again. No point's lever against turning about the
// normal is shorter than min_twist_lever (BodySettings).
void prepareContact(const BodyContact& contact, std::uint32_t index, const ContactSides& sides,
                    const std::vector<SolverBody>& bodies, const Softness& softness,
                    Real min_twist_lever, BodyContact::InvertedMass& inverted,
                    ContactConstraint& c);
// The row of a prepared contact c with one side held still (taking no impulse): c's geometry and
// impulses, its masses again (inverted kept in `inverted`, as prepareContact keeps its own).
void prepareHeldStill(const ContactConstraint& c, bool a_still,
                      const std::vector<SolverBody>& bodies, BodyContact::InvertedMass& inverted,
                      ContactConstraint& held);
struct ContactPass {
  Real h;
  bool use_bias;
  Real max_push_speed;
  Real restitution_threshold;
  Real slop;
  // The constraints are ordered bottom up along gravity (generateBodyContacts); passes alternate,
  // up then down, so that one carries what stops a fall from the ground up and the next the loads
  // from the top down.
  bool top_down;
  // A pile's base faster than this (the sleep speed) slides: the shock pass leaves its friction to
  // the passes.
  Real still_speed;
};
// What guessRestingLoads works in, kept between steps to spare its allocations.
struct RestingLoadBuffers {
  // A contact a body rests on: the constraint, and which side is below.
  struct Support {
    std::uint32_t constraint;
    std::int32_t below;
  };
  // Per solver body, its supports in constraint order: supports[first[k], first[k + 1]).
  std::vector<std::uint32_t> first;
  std::vector<Support> supports;
  std::vector<std::int32_t> order;  // the bodies resting on something, highest first
  std::vector<Real> load;           // per solver body: its weight and what rests on it (N s)
  std::vector<Vec3> moment;         // per solver body: its load's moment about its centre (N s m)
};

// A first guess for the impulses of resting contacts that carry none: the static load each
// carries. Going down from the highest body, each body's weight plus what rests on it is shared
// over the contacts it rests on (a contact whose normal is within 45 degrees of gravity's line):
// between two level ones by the lever rule (each takes the share that balances the load's moment
// about where it acts), else evenly; each passes its share to the body below, at its points. A
// contact that already carries impulses (warm started) passes those on instead. A contact
// without impulses is guessed whether it is new or lasting (one that went slack, or whose points
// changed their feature ids: with the loads split evenly, guessing only new ones kept the
// 5,050-box pyramid awake past 3 s). One closing or opening faster than gravity builds in two
// substeps is not resting and starts from nothing, and so does one whose nearest point is farther
// than it closes within the step (at that speed and falling freely, 2 g h dt + g dt^2 / 2: 2.7 mm
// at 60 Hz and 4 substeps): a speculative contact that may not touch, where a guessed load held a
// falling column up from below in flight and kept a settled pile of random boxes creeping. Without
// the guess a pyramid of a hundred rows sinks for seconds while the solver's passes carry the load
// down row by row.
void guessRestingLoads(std::vector<ContactConstraint>& constraints,
                       const std::vector<SolverBody>& bodies, const std::vector<Real>& heights,
                       const Vec3& gravity, Real h, Real dt, RestingLoadBuffers& buffers);

// Resolves the impacts of the substep (restitution: contact_solver.h's top), then applies every
// other contact's impulses of the last substep again, and takes each point's separation for the
// passes (takeSeparations) in the same sweep over the contacts.
void warmStartContacts(std::vector<ContactConstraint>& constraints, std::vector<SolverBody>& bodies,
                       const ContactPass& pass);
// Each point's separation now (ContactConstraintPoint::current), for the passes of a substep:
// after the positions move (the warm start takes them itself).
void takeSeparations(std::vector<ContactConstraint>& constraints, std::vector<SolverBody>& bodies);
// One pass over the contacts; with use_bias the overlap is pushed out (softly, at most
// max_push_speed), speculative gaps may close no faster than they can within h, and impacts are
// resolved.
void solveContacts(std::vector<ContactConstraint>& constraints, std::vector<SolverBody>& bodies,
                   const ContactPass& pass);
// Shock propagation (Guendelman, Bridson and Fedkiw 2003, here on velocities and split
// impulses): a contact on which one body rests on another (its normal within 45 degrees of
// gravity's line) is solved once more after the substep's passes, bottom up, with the lower body
// held still, so that each body leaves the substep neither closing on nor sunk into what carries
// it, however far the passes were from converging: a pile of a hundred rows no longer sinks and
// rocks row by row. These impulses act on the upper body alone and are not accumulated (the next
// step warm starts from the passes' impulses): they correct what the passes left, which is zero
// once they converge.
//
// Still means still in the frame of what carries the pile: a body of infinite mass (kinematic)
// under it, directly or through the bodies below, whose motion the lower side then takes (at the
// lower body's centre), so that a column rides a belt, a lift or a turntable; the ground when
// nothing does. The ground's frame holds a pile only while the pile's base (its lowest moving
// body) rests on something still (the ground, a fixed or sleeping body): a pile in flight is left
// to the passes (a box resting on another that was let go was held back a step, and fell 2.7 mm
// further behind it every step). And while the base slides (faster than the sleep speed) only
// along the normals: its friction is the passes' (in the ground's frame a box riding a cart that
// slid at 3 m/s was braked until it fell off). The lower body's own motion is not used: the
// rocking the passes leave in it, times the height of what rests on it, would be handed up the
// pile (tried in session 11: a dropped column of ten cubes drifted 4 cm instead of 1.6 mm at
// 4 x 2). Nor the base's linear motion (tried in session 29: over four seeds the random drop's
// pile kept 17 times the kinetic energy, and nearly three times as many boxes moved > 1 cm).
struct ShockRow {
  std::uint32_t constraint;                // the row in constraints
  ContactConstraint upper_alone;           // the same contact with its lower side taking no impulse
  std::int32_t carrier = kNoBody;          // solver body carrying the pile, if any
  Vec3 lower_from_carrier = Vec3::Zero();  // the lower body's centre from the carrier's
  std::int32_t base = kNoBody;             // the lowest moving body under the row
  bool base_on_still = false;              // base rests on the ground, a fixed or sleeping body
  bool base_grips = false;                 // one of those holds it by static friction
};
void propagateShock(std::vector<ShockRow>& rows, const std::vector<ContactConstraint>& constraints,
                    std::vector<SolverBody>& bodies, const ContactPass& pass);
// The impulses back into the contacts, for the next step's warm start.
void storeImpulses(const std::vector<ContactConstraint>& constraints,
                   std::vector<BodyContact>& contacts);

}  // namespace engine
}  // namespace mass_aggregate_sim
