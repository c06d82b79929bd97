#pragma once
// The body solver's state between steps (the broadphase tree, the contacts with their warm
// starts) and the buffers of a step (solver bodies, contact rows, the joints' rows).

#include <cstdint>
#include <utility>
#include <vector>

#include "engine/bodies/body_contact.h"
#include "engine/bodies/contact_constraint.h"
#include "engine/bodies/contact_solver.h"
#include "engine/bodies/joint_rows.h"
#include "engine/bodies/kept_impulses.h"
#include "engine/bodies/kept_mass_pool.h"
#include "engine/bodies/particle_pair.h"
#include "engine/bodies/solver_body.h"
#include "engine/collision/body_pairs.h"
#include "engine/collision/dynamic_tree.h"
#include "engine/core/union_find.h"
#include "mass_aggregate_sim/engine/joints/distance_joint.h"

namespace mass_aggregate_sim {
namespace engine {

struct BodyWorkspace {
  // Fat boxes are the tight ones grown by this (m): a shape moving less is not reinserted.
  static constexpr Real kTreeMargin = 0.1;

  DynamicTree tree{kTreeMargin};
  PairFinder finder;
  // Every pair of overlapping stored boxes that may ever touch (mayEverTouch), kept from step to
  // step: only the proxies whose boxes changed (moved) are queried.
  PersistentPairs proxy_pairs;
  std::vector<ProxyPair> pairs;           // the moved proxies' new pairs, this step
  std::vector<std::uint8_t> awake_proxy;  // by proxy id: an awake body's shape, this step
  std::vector<std::int32_t> moved;
  // Bodies set to a new pose while not awake (fixed ones; a step never moves them): their proxies
  // follow at the next pair stage.
  std::vector<BodyId> posed;
  // The static colliders other than planes, in the tree; remade when the colliders change.
  std::vector<std::int32_t> collider_proxies;
  std::uint64_t colliders_version = ~std::uint64_t{0};
  // Sorted by key; their impulses warm start the next step (state, hashed with the world).
  std::vector<BodyContact> contacts;
  KeptMassPool kept_masses;  // the contacts' (state, hashed with them)
  // Indices into contacts, ascending, of those with an awake side or a particle this step (the
  // rest of a pile that mostly sleeps is passed over): made with the contacts, and again when
  // islands wake.
  std::vector<std::uint32_t> awake_contacts;
  std::vector<FoundContact> found;
  std::vector<BodyContact> next_contacts;
  std::vector<std::pair<ContactKey, std::uint32_t>> keys;
  std::vector<Real> travel;  // per body: how far its points may move this step
  // Per shape: its frame, made in the step numbered shape_frame_step (the contacts' count of
  // steps is frame_step).
  std::vector<Frame> shape_frames;
  std::vector<std::uint64_t> shape_frame_step;
  std::uint64_t frame_step = 0;
  // The ends of the joints that do not collide_connected, this step: (body, body) with the lower
  // packed id first, and (body, particle), both as packed ids, sorted.
  std::vector<std::pair<std::uint64_t, std::uint64_t>> joined_bodies;
  std::vector<std::pair<std::uint64_t, std::uint64_t>> joined_particles;

  // This step: one solver body per awake dynamic or kinematic body, then one per particle that
  // touches a body or is held by a joint; kNoBody for the rest.
  std::vector<SolverBody> solver;
  std::vector<std::int32_t> solver_of_body;      // by dense body index
  std::vector<std::int32_t> solver_of_particle;  // by dense particle index (when any)
  std::vector<std::uint32_t>
      particle_of_solver;  // dense particle index of solver[first_particle + k]
  std::size_t first_particle = 0;
  Vec3Array particle_start;     // where they moved from when the step began (particleLead)
  Vec3Array particle_velocity;  // their velocities before the body solver, this substep
  Vec3Array particle_moved;     // their moves since particle_start, as the body solver loaded them
  std::vector<ContactConstraint> constraints;
  std::vector<ContactSides> constraint_sides;  // each constraint's sides as prepared
  std::vector<ShockRow> shock_rows;            // bottom up, as the constraints
  std::vector<std::int32_t> carrier_of;  // per solver body: what carries its pile (shock rows)
  std::vector<Vec3> carrier_center_of;
  std::vector<std::int32_t> base_of;   // per solver body: the lowest moving body of its pile
  std::vector<std::uint8_t> on_still;  // per solver body: it rests on something still
  // (row, solver body): a contact through which a moving body rests on something still
  std::vector<std::pair<std::uint32_t, std::int32_t>> still_supports;
  std::vector<std::uint8_t> grips_still;  // per solver body: one of them holds it by friction
  std::vector<std::pair<Real, std::uint32_t>> contact_order;  // (height, contact) of the rows
  // The moving bodies' surfaces lent to the particles' positions stage
  // (ContactWorkspace::BodySurface::moves): the surface, its body's solver body, and as the step
  // began a point of the plane, its normal and the body's centre.
  struct MovingSurface {
    std::uint32_t surface = 0;
    std::int32_t solver = kNoBody;
    Vec3 point = Vec3::Zero();
    Vec3 normal = Vec3::UnitZ();
    Vec3 center = Vec3::Zero();
  };
  std::vector<MovingSurface> moving_surfaces;
  // The particle links (cables, rods) of the particles the body solver moves, and of the
  // particles linked to those: solved with the joints, so that a rope of particles holding a body
  // carries its load (the particle solver alone cannot see the body). Their impulses, by link id,
  // warm start the next step (state, with the joints').
  std::vector<DistanceJoint> link_joints;
  std::vector<JointRow> link_rows;
  KeptImpulses link_impulses;  // by link id
  // The contacts between those particles and the particles resting on them (closed upwards):
  // their rows (particle_pair.h), with friction where the pile rests on moving bodies alone (the
  // particle solver then leaves them to this one). Their impulses, by contact key, warm start the
  // next step (state, as the links').
  std::vector<ParticlePair> particle_pairs;
  std::vector<std::pair<std::uint64_t, std::uint32_t>> pair_by_key;  // (key, pair), sorted
  // The particles the body solver moves (by solver body less first_particle) joined into piles
  // by their contacts, and per pile root whether it rests on anything but moving bodies
  // (leavePairsToBodySolver).
  UnionFind piles;
  std::vector<std::uint8_t> pile_rests_elsewhere;
  KeptImpulses pair_impulses;  // by contact key: the normal impulse (lower) and the friction
  std::vector<Real> heights;   // per solver body, along -gravity
  RestingLoadBuffers resting_loads;
  // The force generators on bodies, this substep: per moving body (by solver body; empty without
  // generators) their force and torque about the centre of mass; the particles' external forces,
  // the user's of the step and theirs.
  std::vector<Vec3> generator_force;
  std::vector<Vec3> generator_torque;
  Vec3Array user_particle_forces;
  Vec3Array particle_forces;
  JointRows joints;
  bool prepared = false;  // the step's rows exist (bodies awake, or particles touching them)
};

}  // namespace engine
}  // namespace mass_aggregate_sim
