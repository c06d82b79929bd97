#pragma once
// The solver stages of a substep: the constraints (contacts, cables, rods) on the velocities,
// then the positions following them.

namespace mass_aggregate_sim {
namespace engine {

class StepContext;

// The velocity phase: each constraint starts from the impulse it ended the last substep with,
// then Gauss-Seidel passes until the velocities settle (ContactResolver); resting contacts'
// particles then move with their impulses (before the body rows change their velocities).
// Collider-only scenes make their contacts here, part by part, while each part is in the cache.
void solveConstraints(StepContext& ctx);
// The position phase: overlaps and link lengths are corrected, and position Verlet's histories
// follow what the solver changed.
void integratePositions(StepContext& ctx);

}  // namespace engine
}  // namespace mass_aggregate_sim
