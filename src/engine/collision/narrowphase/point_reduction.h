#pragma once
// Choosing at most four of a face contact's points.

#include "engine/collision/narrowphase/manifold.h"

namespace mass_aggregate_sim {
namespace engine {

// Adds to manifold (empty on entry) at most four of the count candidates: all of them when there
// are four or fewer; else the deepest, the one farthest from it, the one farthest from the line
// through those two, and the one that adds the most area to their triangle (the contact plane's
// normal measures areas). "The deepest" is the first candidate within depth_tolerance of the
// deepest, so that near-equal depths (a face resting flat) do not pick by rounding. Other ties go
// to the earlier candidate.
void addReducedPoints(const ManifoldPoint* candidates, int count, const Vec3& normal,
                      Real depth_tolerance, Manifold& manifold);

}  // namespace engine
}  // namespace mass_aggregate_sim
