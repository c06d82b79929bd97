#pragma once
// The collision stages of a substep, after the integrator has moved the particles.

#include <cstddef>

namespace mass_aggregate_sim {
namespace engine {

class StepContext;
struct GroupContact;

// Candidate particle pairs (kept between substeps while valid) and, with continuous collision,
// the swept tests that move fast particles back to their time of impact.
void findPairs(StepContext& ctx);
// The contacts of the substep: particles against every collider shape, particle pairs, and the
// links' constraints, bottom up along gravity. Collider-only scenes make them part by part in the
// solver stage instead (solveConstraints), while each part is in the cache.
void generateContacts(StepContext& ctx);
// The collider contacts of particles [begin, end), appended to ctx.contacts.contacts; true when
// one of them met two or more colliders.
bool generateColliderContacts(StepContext& ctx, std::size_t begin, std::size_t end);
// The contacts of particle i with the colliders other than planes (which the solver's collider
// groups test in lanes), for solveColliderGroups(): 0, 1 (in `contact`), or 2 when there are two
// or more or a swept test stopped the particle. `context` is the StepContext.
int otherColliderContacts(const void* context, std::size_t i, GroupContact& contact);
// The particles' contacts with bodies' surfaces (ContactWorkspace::BodySurface), at their
// positions now, appended to ctx.contacts.contacts as colliders' are made (a moving body's
// position-only).
void addBodySurfaceContacts(StepContext& ctx);
// Whether only collider contacts can occur this substep (no links, no particle pairs).
bool onlyColliderContacts(const StepContext& ctx);

// Gaps narrower than this get a contact too (speculative: it only stops them closing faster than
// the gap within the substep), so a particle lifted off its support by a neighbour's correction
// does not fall freely for a substep and land with a jolt.
inline double contactMargin(const double penetration_slop) { return 2.0 * penetration_slop; }

}  // namespace engine
}  // namespace mass_aggregate_sim
