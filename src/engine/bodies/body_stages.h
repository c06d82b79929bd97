#pragma once
// The rigid bodies' part of each stage of a step (world/step.cpp), the soft step of a
// substepped impulse solver: once per step the broadphase and the narrowphase make the contacts
// and the rows are prepared; every substep integrates velocities, warm starts and solves the
// joints and contacts with their bias, integrates positions and relaxes them without it; after
// the substeps, restitution, the impulses kept for warm starting, the state written back and the
// islands put to sleep. Each returns at once in a world without bodies.

namespace mass_aggregate_sim {
namespace engine {

class StepContext;

// beginStep: the solver bodies of the awake bodies, their world inertia refreshed.
void beginBodyStep(StepContext& ctx);
// v += h (g + F / m), w by the torque and the gyroscopic term (implicit), damping.
void integrateBodyVelocities(StepContext& ctx);
// First substep: the tree follows the awake bodies; the narrowphase; islands an awake body
// touches wake; the contacts ordered bottom up; a particle's contact with a body lent to the
// particle solver as the body's surface (ContactWorkspace::BodySurface): a still body's (fixed or
// asleep) to hold the particle, a moving body's to keep it out in the positions stage. Every
// substep: the moving bodies' surfaces follow them.
void findBodyPairs(StepContext& ctx);
// First substep: the particles that touch moving bodies join the body solver; the rows of the
// step.
void generateBodyContacts(StepContext& ctx);
// Warm start, then one pass over the joints and contacts with their bias.
void solveBodyConstraints(StepContext& ctx);
// Positions follow the velocities; one relaxing pass without the bias.
void integrateBodyPositions(StepContext& ctx);
// Restitution, impulses kept, state written back, sleeping islands.
void finaliseBodies(StepContext& ctx);

}  // namespace engine
}  // namespace mass_aggregate_sim
