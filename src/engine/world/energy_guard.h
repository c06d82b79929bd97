#pragma once
// The energy guard (WorldConfig::energy_growth_limit) and the check for non-finite values.

namespace mass_aggregate_sim {
namespace engine {

class StepContext;
struct StabilityReport;

// Whether the energy guard judges this world's steps: a limit is set, some generator can run
// away, and nothing does work the guard's energy cannot count (external forces, per-particle
// accelerations, a generator's uncounted work).
bool energyGuardApplies(const StepContext& ctx);
// After a step that the guard judges (no contacts acted): the first after a change gives the
// reference, the others are compared with it (see WorldConfig::energy_growth_limit). A non-finite
// value is reported instead of judged.
void judgeEnergy(StepContext& ctx, const StabilityReport& report, int substeps_used);
// A non-finite position or velocity, reported with the first such particle; with `runaway` (after
// a step in which contacts or links acted) and every value finite, a particle faster than
// CollisionSettings::runaway_speed, reported with the fastest (found in the same pass).
void detectNonFinite(StepContext& ctx, bool runaway = false);
// A body whose pose or velocities are not finite, or that moves faster than the bodies' runaway
// speed (BodySettings::runaway_speed), reported with the first such body. Checked every step.
void detectBodyNonFinite(StepContext& ctx);

}  // namespace engine
}  // namespace mass_aggregate_sim
