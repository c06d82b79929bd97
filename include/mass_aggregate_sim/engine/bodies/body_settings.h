#pragma once

#include "mass_aggregate_sim/engine/core/status.h"
#include "mass_aggregate_sim/engine/core/types.h"

namespace mass_aggregate_sim {
namespace engine {

// How the world steps and solves rigid bodies (only worlds with bodies use these). The body
// solver is a substepped soft-constraint solver: each substep integrates velocities, warm starts,
// solves every joint and contact once with a bias that removes overlap and joint error softly,
// integrates positions, and relaxes once without the bias (so the bias leaves no velocity
// behind); restitution is applied once after the substeps.
struct BodySettings {
  // While a body can move, the world takes at least this many substeps per step (particles take
  // the same); once every body is fixed or asleep, from the step after, the particles' own.
  int substeps = 4;
  // Passes over the joints and contacts per substep (the first warm started), and relaxing passes
  // after the positions move.
  int iterations = 2;
  int relax_iterations = 0;
  // Resting contacts that carry no impulse start from the static load they carry (a guess the
  // passes refine, shared between two level supports by the lever rule); not those whose gap
  // does not close within the step (contact_solver.h).
  bool guess_loads = true;
  // A last pass per substep over the contacts where one body rests on another, bottom up, with
  // the lower body held still (shock propagation; still as the kinematic body the pile rests on
  // moves, if any): tall piles stand with few passes.
  bool shock_propagation = true;
  // Contacts act as springs of this frequency (Hz) and damping ratio on overlap; capped at a
  // quarter of the substep rate. Joints likewise. A contact's overlap is pushed out by
  // pseudo-velocities (no momentum), so the ratio only sets how fast: at omega / (2 zeta +
  // h omega) per second, and a pile the passes leave sinking at speed u rests with overlap
  // u / that rate. Box2D's ratio of 10 (made for a bias that becomes real velocity) gives 9/s
  // at the default substeps: the 5,050-box pyramid rests 1.5 mm deep and keeps rocking at the
  // sleep speed; 2 gives 39/s. Below about 1.5 the push-out lifts boxes of a dropped pile fast
  // enough to gain energy.
  Real contact_hertz = 30.0;
  Real contact_damping_ratio = 2.0;
  Real joint_hertz = 60.0;
  Real joint_damping_ratio = 2.0;
  // Fastest speed (m/s) at which overlap is pushed out.
  Real max_push_speed = 3.0;
  // Shapes closer than this (m) already get contact points (speculative contacts).
  Real speculative_distance = 0.02;
  // Overlap (m) left alone, so resting contacts do not jitter; what a pile may settle into.
  Real linear_slop = 0.00005;
  // The least lever (m) of a contact's friction against turning about its normal: a point
  // contact is a small patch in fact, and a body held by two points with none would turn about
  // the line through them for ever, a pendulum without loss (a box pinched between two corners
  // in a pile, keeping its island awake). A contact resists that turn with up to
  // mu sum_k j_k max(arm_k, min_twist_lever), arm_k a point's distance from the contact's centre
  // (a particle's contact: arm_k alone, since a particle cannot turn back).
  Real min_twist_lever = 0.001;
  // Closing speeds (m/s) below this do not bounce (restitution acts above it).
  Real restitution_threshold = 1.0;
  // Sleeping: an island whose every body has been slower than sleep_speed (m/s, at any point of
  // the body) for time_to_sleep (s) sleeps until something touches or changes it.
  bool sleep = true;
  Real sleep_speed = 0.05;
  Real time_to_sleep = 0.5;
  // Continuous collision: a body's contacts are looked for as far out as it (and what it meets)
  // can move in the step, |v| dt + |w| dt reach, and such a speculative row lets a gap close
  // only as far as it is wide, so the body arrives on the surface at its time of impact within
  // the substep and bounces from there, at any speed, against colliders and bodies alike. What it
  // cannot see is a point that is not the nearest at the step's start (a long body spinning past
  // an edge). Off: only speculative_distance, and a body crossing a thin wall in one substep
  // passes through it.
  bool continuous = true;
  // The gyroscopic term w x I w, integrated implicitly; off only to see what it does (a body
  // spun about its intermediate axis then never flips, and angular momentum is not conserved).
  bool gyroscopic = true;
  // A body faster than this (m/s) has run away: the world reports a divergence (its policy
  // applies), as it does for a non-finite pose or velocity.
  Real runaway_speed = 1e4;
};

// Every field equal (body_settings.cpp lists them; a field added here must be added there).
bool operator==(const BodySettings& a, const BodySettings& b);
inline bool operator!=(const BodySettings& a, const BodySettings& b) { return !(a == b); }

// Finite values in range: substeps in [1, 64], iterations in [1, 64], relax iterations in
// [0, 64], frequencies > 0, damping ratios >= 0, speeds,
// distances and times > 0 (slop and twist lever >= 0).
Status validateBodySettings(const BodySettings& settings);

}  // namespace engine
}  // namespace mass_aggregate_sim
