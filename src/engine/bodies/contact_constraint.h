#pragma once
// A body contact as the solver sees it during one step: its two solver bodies, its normal and
// tangents, per point the anchors (from each centre of mass, fixed for the step) with the terms
// of its normal row computed once, the separation it had when prepared (moved on by how far the
// bodies have moved since) and the normal impulse it accumulates, and the friction rows of the
// manifold as a whole with theirs.

#include <array>
#include <cstdint>

#include "engine/bodies/softness.h"
#include "engine/bodies/solver_body.h"
#include "engine/collision/narrowphase/manifold.h"

namespace mass_aggregate_sim {
namespace engine {

struct ContactConstraintPoint {
  // The point from each centre of mass (fixed for the step). The rows' angular parts follow from
  // them when a pass needs them (J_n = [-n, -(r_a x n), n, r_b x n], the tangents' likewise): a
  // pile's rows are streamed from memory at every pass, and recomputing a cross product costs
  // less than reading it.
  Vec3 r_a = Vec3::Zero();
  Vec3 r_b = Vec3::Zero();
  // The separation when prepared: now it is that plus n.(d_b - d_a), d the moves of the anchors
  // (of their cores' points on a rounded side); `current` is that, taken once a substep (the
  // anchors move only between substeps).
  Real separation = 0.0;
  Real current = 0.0;
  Real normal_mass = 0.0;
  Real normal_impulse = 0.0;
  // The point's distance from the manifold's centre in the contact plane, at least
  // BodySettings::min_twist_lever: its lever against turning about the normal.
  Real arm = 0.0;
};

using PointBlock = Eigen::Matrix<Real, Manifold::kMaxPoints, Manifold::kMaxPoints>;

struct ContactConstraint {
  std::int32_t a = kNoBody;
  std::int32_t b = kNoBody;
  std::uint32_t contact = 0;  // index into the step's contacts
  Real inverse_mass_a = 0.0;
  Real inverse_mass_b = 0.0;
  // Each side's rounding (BodyShapeKind::rounding): a point's anchor on a rounded side is its
  // core's point, which turns with the body, plus the rounding along the normal, which does not.
  Real rounding_a = 0.0;
  Real rounding_b = 0.0;
  Vec3 normal = Vec3::UnitZ();
  Vec3 tangent[2] = {Vec3::UnitX(), Vec3::UnitY()};
  Real friction = 0.0;
  Real restitution = 0.0;
  Softness softness;
  // A swept contact (Manifold::slide): its anchors are the touching points themselves, not
  // points midway across the gap.
  bool swept = false;
  // The contact's impact has been resolved this step (restitution: once a step), and in this
  // substep, whose passes its normal rows then sit out. From the next substep they hold from zero
  // like any contact's: a grain struck at the bottom of a landing pile is pushed back down by the
  // grains above it.
  bool impact = false;
  bool impact_now = false;
  int count = 0;
  // The points' normal rows coupled through the bodies, K_ij = J_i M^-1 J_j^T, inverted once: one
  // solve gives every point its share (a face's four points are coupled and K is singular: its
  // pseudo-inverse gives the least-norm share, the symmetric one).
  PointBlock normal_block = PointBlock::Zero();
  std::array<ContactConstraintPoint, Manifold::kMaxPoints> points{};
  // Friction on the manifold as a whole (a patch): two tangent rows at the points' centre (c_a, c_b
  // from each centre of mass), solved together through their coupled mass K_t (inverted in
  // friction_block) and bounded together by mu sum_k j_k, and a twist row about the normal,
  // bounded by mu sum_k j_k arm_k: what the points' own cones would resist, sliding and turning
  // about the centre, with one root a pass instead of one a point.
  Vec3 center_a = Vec3::Zero();
  Vec3 center_b = Vec3::Zero();
  Eigen::Matrix<Real, 2, 2> friction_block = Eigen::Matrix<Real, 2, 2>::Zero();
  Real twist_mass = 0.0;
  Real friction_impulse[2] = {0.0, 0.0};
  Real twist_impulse = 0.0;

  // The load it carries: sum_k j_k over its points.
  Real normalLoad() const {
    Real load = 0.0;
    for (int k = 0; k < count; ++k) load += points[k].normal_impulse;
    return load;
  }
};

}  // namespace engine
}  // namespace mass_aggregate_sim
