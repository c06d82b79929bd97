#pragma once
// Sleeping by islands: bodies joined by touching contacts or joints form an island (union-find
// over the dynamic bodies); an island whose every body has been slow for time_to_sleep sleeps
// (its velocities zeroed, not stepped) until something wakes it: a request on one of its bodies,
// an awake body or a fast particle touching it. Sleeping changes no hash rule: a sleeping body's
// state is hashed like any other.

#include <cstddef>
#include <vector>

#include "engine/bodies/body_workspace.h"
#include "mass_aggregate_sim/engine/bodies/body_settings.h"
#include "mass_aggregate_sim/engine/bodies/body_store.h"
#include "mass_aggregate_sim/engine/joints/joints.h"

namespace mass_aggregate_sim {
namespace engine {

// How many islands the dynamic bodies form as the sleep stage forms them (through the last
// step's touching shape contacts and the joints between two bodies; fixed and kinematic bodies
// join none), awake or asleep; a dynamic body touching nothing is an island.
std::size_t countIslands(const BodyStore& bodies, const BodyWorkspace& ws, const Joints& joints);
// Wakes the islands of the dense bodies `seeds`: every body reached from one through contacts and
// joints (a seed that is awake or not dynamic wakes alone). One pass over the links serves every
// seed, so that a fixed floor moved under a thousand separate resting boxes wakes them at the cost
// of one island, not a thousand.
void wakeIslands(BodyStore& bodies, const BodyWorkspace& ws, const Joints& joints,
                 const std::vector<std::size_t>& seeds);
// The island of dense body `body` alone.
void wakeIsland(BodyStore& bodies, const BodyWorkspace& ws, const Joints& joints, std::size_t body);
// Wakes the sleeping islands an awake body touches or is joined to; true when any woke.
bool wakeTouchedIslands(BodyStore& bodies, const BodyWorkspace& ws, const Joints& joints);
// After a step: each awake body's slow time, then the islands that may sleep. `busy` marks the
// bodies a fast particle touches (kept awake).
void updateSleep(BodyStore& bodies, const BodyWorkspace& ws, const Joints& joints,
                 const BodySettings& settings, Real dt, const std::vector<std::uint8_t>& busy);

}  // namespace engine
}  // namespace mass_aggregate_sim
