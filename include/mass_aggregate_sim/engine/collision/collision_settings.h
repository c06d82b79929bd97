#pragma once

#include <cstddef>
#include <optional>
#include <string>

#include "mass_aggregate_sim/engine/core/status.h"
#include "mass_aggregate_sim/engine/core/types.h"

namespace mass_aggregate_sim {
namespace engine {

// How candidate particle pairs are found before the exact sphere test.
enum class Broadphase {
  kSortAndSweep,  // sort boxes along the axis of largest spread, sweep the overlapping intervals
  kUniformGrid,   // hash boxes into cells about one particle across, test pairs sharing a cell
};

// Names as used in scenes and parameters: sort_and_sweep, uniform_grid.
const char* broadphaseName(Broadphase broadphase);
std::optional<Broadphase> parseBroadphase(const std::string& name);
std::string broadphaseNames();

struct CollisionSettings {
  bool particle_collisions = false;  // particles collide with each other (spheres of their radius)
  Broadphase broadphase = Broadphase::kSortAndSweep;
  bool continuous = false;  // swept tests so fast particles cannot tunnel
  // Material of particle-particle contacts, unless both particles were given their own.
  Real particle_restitution = 0.5;
  Real particle_friction = 0.0;
  int max_iterations = 20;        // Gauss-Seidel passes per phase (velocity, position)
  Real penetration_slop = 0.001;  // m of overlap left alone, so resting contacts do not jitter
  bool collide_linked = false;    // particles joined by a cable or rod still collide
  Real rod_tolerance = 1e-9;      // relative length error a rod is allowed
  // m/s: a velocity pass changing no velocity by more than this ends the phase. 1e-4 m/s moves a
  // particle by 1e-4 h per substep (under 2 um at 60 Hz); warm-started resting contacts reach it
  // in one or two passes, where 1e-9 was never reached in a pile.
  Real velocity_tolerance = 1e-4;
  std::size_t max_contacts = 0;  // 0: the contact buffer grows; else extra contacts are dropped
  // m/s: a particle faster than this at the end of a step in which contacts or links acted is a
  // divergence (as BodySettings::runaway_speed for bodies). The energy guard judges only steps
  // without them; this catches a chain or pile that runs away while its state is still finite.
  Real runaway_speed = 1e4;
};

// Finite values, restitution in [0, 1], friction >= 0, max_iterations in [1, 10000], slop >= 0,
// tolerances and the runaway speed > 0.
Status validateCollisionSettings(const CollisionSettings& settings);

// What the contact phase did in the last substep (dropped: summed over the last step).
struct ContactStats {
  std::size_t contacts = 0;       // contacts and active link constraints
  int iterations = 0;             // velocity passes plus position passes
  Real max_penetration = 0;       // largest overlap (or link length error) left, m
  Real max_closing_velocity = 0;  // largest closing speed left along a normal, m/s
  std::size_t dropped = 0;        // contacts not resolved because max_contacts was reached
  int velocity_iterations = 0;
  int position_iterations = 0;
  std::size_t ccd_hits = 0;  // particles moved back to their time of impact
};

}  // namespace engine
}  // namespace mass_aggregate_sim
