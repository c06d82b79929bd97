#include "engine/bodies/body_stages.h"

#include <algorithm>
#include <cmath>
#include <type_traits>

#include "engine/bodies/body_collision.h"
#include "engine/bodies/body_motion.h"
#include "engine/bodies/contact_solver.h"
#include "engine/bodies/islands.h"
#include "engine/bodies/particle_pair.h"
#include "engine/collision/narrowphase/any_shape.h"
#include "engine/core/prefetch.h"
#include "engine/forces/body_force_stage.h"
#include "engine/integrators/integrators.h"
#include "engine/solver/contact_workspace.h"
#include "engine/world/step_context.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

// How far ahead of the row being prepared its contact's kept masses are asked for (rows), and
// twice as far the contact itself (generateBodyContacts).
constexpr std::size_t kPrefetchAhead = 4;

// Before the positions stage a particle's position is already the integrator's prediction,
// which a velocity change dv moves on by beta h dv (storeParticles): the particle moves from
// x - beta h v, and its rows see it there, so that v' + s / h >= 0 keeps a gap open at the
// substep's end as for a body.
Real particleLead(const StepContext& ctx) { return positionWeight(ctx.config.integrator) * ctx.h; }

BodyCollisionScene collisionScene(const StepContext& ctx) {
  return BodyCollisionScene{*ctx.bodies,    ctx.colliders,    ctx.colliders_version, ctx.particles,
                            ctx.collisions, ctx.materials,    *ctx.body_settings,    *ctx.joints,
                            ctx.dt,         particleLead(ctx)};
}

// Contacts soften at most to a quarter of the substep rate (stiffer would be unstable); against
// a side that never moves, twice as stiff (nothing on that side gives way).
Softness contactSoftness(const BodySettings& s, const Real h, const bool against_still) {
  const Real hertz = std::min(s.contact_hertz, 0.25 / h);
  return makeSoft(against_still ? 2.0 * hertz : hertz, s.contact_damping_ratio, h);
}

// The solver body of a particle, made on first use.
std::int32_t particleSolverBody(StepContext& ctx, const std::size_t p) {
  BodyWorkspace& ws = *ctx.body_ws;
  if (ws.solver_of_particle.size() != ctx.particles.size()) {
    ws.solver_of_particle.assign(ctx.particles.size(), kNoBody);
  }
  std::int32_t& index = ws.solver_of_particle[p];
  if (index != kNoBody) return index;
  const Real inverse_mass = ctx.particles.inverseMasses()[static_cast<Eigen::Index>(p)];
  if (inverse_mass <= 0.0) return kNoBody;  // immovable: a side that never moves
  SolverBody sb;
  sb.inverse_mass = inverse_mass;
  sb.v = ctx.particles.velocities().col(static_cast<Eigen::Index>(p));
  index = static_cast<std::int32_t>(ws.solver.size());
  ws.solver.push_back(sb);
  ws.particle_of_solver.push_back(static_cast<std::uint32_t>(p));
  return index;
}

// The particles' solver bodies take their velocities and moves from the particle store (the
// particle integrator and contact phase moved them since): from where they move, before the
// positions stage (`predicted`, particleLead).
void loadParticles(StepContext& ctx, const bool predicted) {
  BodyWorkspace& ws = *ctx.body_ws;
  const auto x = ctx.particles.positions();
  const auto v = ctx.particles.velocities();
  const Real lead = predicted ? particleLead(ctx) : 0.0;
  for (std::size_t k = 0; k < ws.particle_of_solver.size(); ++k) {
    const auto p = static_cast<Eigen::Index>(ws.particle_of_solver[k]);
    SolverBody& sb = ws.solver[ws.first_particle + k];
    sb.flew = false;
    sb.v = v.col(p);
    sb.dp = x.col(p) - lead * sb.v - ws.particle_start.col(static_cast<Eigen::Index>(k));
    ws.particle_velocity.col(static_cast<Eigen::Index>(k)) = sb.v;
    ws.particle_moved.col(static_cast<Eigen::Index>(k)) = sb.dp;
  }
}

// Back into the store: the velocity the body solver left, and (when `move`) the position moved
// as the particle's integrator moves it with a velocity change within the substep (beta h dv).
// The particles' positions stage, which comes next, measures its depths after that move.
void storeParticles(StepContext& ctx, const bool move) {
  BodyWorkspace& ws = *ctx.body_ws;
  auto x = ctx.particles.positions();
  auto v = ctx.particles.velocities();
  const Real beta_h = positionWeight(ctx.config.integrator) * ctx.h;
  const bool tell_positions_stage = move && ctx.contacts_active;
  for (std::size_t k = 0; k < ws.particle_of_solver.size(); ++k) {
    const auto p = static_cast<Eigen::Index>(ws.particle_of_solver[k]);
    SolverBody& sb = ws.solver[ws.first_particle + k];
    if (move) {
      // The pseudo-velocity's push out of an overlap moves the particle now and is dropped.
      Vec3 moved =
          beta_h * (sb.v - ws.particle_velocity.col(static_cast<Eigen::Index>(k))) + ctx.h * sb.pv;
      sb.pv.setZero();
      // An impact moved it back to where it touched and turned (resolveImpact); without this it
      // turned where the substep began, up to |v| h short of the surface (a particle at 40 m/s
      // striking a plate with restitution 0.25 turned 10 cm above it).
      if (sb.flew) moved += sb.dp - ws.particle_moved.col(static_cast<Eigen::Index>(k));
      x.col(p) += moved;
      if (tell_positions_stage) ctx.contacts.resolver.addMove(static_cast<std::uint32_t>(p), moved);
    }
    v.col(p) = sb.v;
  }
  if (ws.particle_of_solver.empty()) return;
  ctx.integration.acceleration_valid = false;
  if (keepsVerletHistory(ctx)) {
    for (const std::uint32_t p : ws.particle_of_solver) reseedVerletHistory(ctx, p);
  }
}

// A joint end as a side of its row: its solver body (kNoBody for the world, a fixed or sleeping
// body, an immovable particle), its anchor from its centre of mass and that centre.
void jointSide(StepContext& ctx, const JointEnd& end, std::int32_t& solver, Vec3& r, Vec3& center,
               Quat& q) {
  const BodyStore& bodies = *ctx.bodies;
  r.setZero();
  q = Quat::Identity();
  if (end.isBody()) {
    const std::size_t i = bodies.denseIndexUnchecked(end.body);
    solver = ctx.body_ws->solver_of_body[i];
    center = bodies.position(i);
    q = bodies.orientation(i);
    r = q * bodies.massFrame(i).inverse().apply(end.point);
    return;
  }
  if (end.isParticle()) {
    const auto p = static_cast<Eigen::Index>(ctx.particles.denseIndexUnchecked(end.particle));
    solver = particleSolverBody(ctx, static_cast<std::size_t>(p));
    center =
        ctx.particles.positions().col(p) - particleLead(ctx) * ctx.particles.velocities().col(p);
    return;
  }
  solver = kNoBody;
  center = end.point;
}

// A particle's contact with a body that does not move this step (fixed or asleep) is the particle
// solver's, as a collider's (ContactWorkspace::BodySurface): the plane through the body's
// surface where the particle met it, n.x = n.x_0 - s_0 at the particle's start x_0, separation
// s_0. Joined to the body solver instead, a pile resting in a sleeping bin was all in it (the
// closure upwards), its contacts body rows in every substep: 1,000 grains cost 4.65 ms a step,
// 0.86 now (BM_GrainBin). A moving body's (one with a solver body) stays the body rows' and is
// lent to the particles' positions stage only, following the body (placeMovingSurfaces): that
// stage, taking a landing column's overlaps out, pushed its lowest grain 3.4 cm into a box.
void addSurface(StepContext& ctx, const BodyContact& contact, const std::size_t p) {
  const Manifold& m = contact.manifold;
  const auto i = static_cast<Eigen::Index>(p);
  if (m.count == 0 || !(ctx.particles.inverseMasses()[i] > 0.0)) return;
  const BodyStore& bodies = *ctx.bodies;
  const std::size_t body = bodies.denseIndexUnchecked(bodies.shapes()[contact.key.shape].body);
  const std::int32_t solver = ctx.body_ws->solver_of_body[body];
  const Vec3 start =
      ctx.particles.positions().col(i) - particleLead(ctx) * ctx.particles.velocities().col(i);
  ContactWorkspace::BodySurface surface;
  surface.particle = static_cast<std::uint32_t>(p);
  surface.shape = contact.key.shape;
  surface.normal = m.normal;
  surface.offset = m.normal.dot(start) - m.points[0].separation;
  surface.material = Material{contact.restitution, contact.friction};
  surface.moves = solver != kNoBody;
  if (surface.moves) {
    BodyWorkspace::MovingSurface& moving = ctx.body_ws->moving_surfaces.emplace_back();
    moving.surface = static_cast<std::uint32_t>(ctx.contacts.body_surfaces.size());
    moving.solver = solver;
    moving.point = start - m.points[0].separation * m.normal;
    moving.normal = m.normal;
    moving.center = bodies.position(body);
  }
  ctx.contacts.body_surfaces.push_back(surface);
}

// Each moving surface where its body will be at the substep's end, as the particles' positions
// are already their integrator's prediction: the plane's point carried by the body's moves since
// the step began (dp, dq about its centre), then on over the substep.
void placeMovingSurfaces(StepContext& ctx) {
  BodyWorkspace& ws = *ctx.body_ws;
  for (const BodyWorkspace::MovingSurface& moving : ws.moving_surfaces) {
    const SolverBody& sb = ws.solver[static_cast<std::size_t>(moving.solver)];
    const Vec3 center = moving.center + sb.dp;
    const Vec3 point = center + sb.dq * Vec3(moving.point - moving.center);
    // At the velocity it had as the substep began: this substep's forces on a body resting on
    // something are what its contacts take back (with them, the plane under a resting pile was
    // h^2 g low: the 4,000-grain bin's deepest grain 0.46 mm into it, 0.33 mm without).
    const Vec3 v = sb.v - ctx.h * sb.acceleration;
    const Vec3 ahead = point + ctx.h * (v + sb.w.cross(point - center));
    ContactWorkspace::BodySurface& surface = ctx.contacts.body_surfaces[moving.surface];
    surface.normal = sb.dq * moving.normal;
    surface.offset = surface.normal.dot(ahead);
  }
}

// Whether c is two particles' contact (not a collider's, not a link's).
bool particlePair(const Contact& c) {
  return c.kind == ContactKind::kContact && c.b != kNoParticle && !c.position_only;
}

// The links and contacts of the particles the body solver moves, as distance rows beside the
// joints: the links as they are, closed over links (a rope's every particle joins when one of
// them touches a body); the contacts pushing only, closed over the particles resting on joined
// ones (above them along -gravity: a pile's weight flows down to the body). A particle beside or
// below rests on something else (the ground); joined, it would bring its own pile into the body
// rows without the ground contacts that hold it up, which stay the particle solver's (closed over
// every contact, the rain of grains on boxes took 1.5 times as long a step).
void coupleParticles(StepContext& ctx, const Softness& link_softness) {
  BodyWorkspace& ws = *ctx.body_ws;
  ws.link_joints.clear();
  ws.link_rows.clear();
  ws.particle_pairs.clear();
  ws.pair_by_key.clear();
  if (ws.particle_of_solver.empty()) return;
  // This substep's particle contacts, when the contact stage made any between particles.
  const bool pairs =
      ctx.contacts_active && ctx.collisions.particle_collisions && !ctx.contacts.pairs.empty();
  if (ctx.links.empty() && !pairs) return;
  const ParticleStore& particles = ctx.particles;
  const auto joinedAt = [&](const std::size_t p) {
    return p < ws.solver_of_particle.size() && ws.solver_of_particle[p] != kNoBody;
  };
  const auto joined = [&](const ParticleId id) {
    return id.valid() && joinedAt(particles.denseIndexUnchecked(id));
  };
  const Vec3 up = -ctx.config.gravity;
  const auto position = particles.positions();
  // Grow the set of joined particles until no link or contact reaches a new one.
  for (bool grew = true; grew;) {
    grew = false;
    ctx.links.forEach([&](const auto& kind) {
      for (const auto& link : kind) {
        if (link.anchored() || joined(link.a) == joined(link.b)) continue;
        const ParticleId outside = joined(link.a) ? link.b : link.a;
        if (particleSolverBody(ctx, particles.denseIndexUnchecked(outside)) != kNoBody) grew = true;
      }
    });
    if (!pairs) continue;
    for (const Contact& c : ctx.contacts.contacts) {
      if (!particlePair(c) || joinedAt(c.a) == joinedAt(c.b)) continue;
      const std::uint32_t outside = joinedAt(c.a) ? c.b : c.a;
      const std::uint32_t inside = joinedAt(c.a) ? c.a : c.b;
      if (!(up.dot(Vec3(position.col(outside) - position.col(inside))) > 0.0)) continue;
      if (particleSolverBody(ctx, outside) != kNoBody) grew = true;
    }
  }
  const auto addRow = [&](const DistanceJoint& joint, const Softness& softness,
                          std::vector<DistanceJoint>& joints, std::vector<JointRow>& rows) {
    JointRow row;
    jointSide(ctx, joint.a, row.a, row.r_a, row.center_a, row.q_a);
    jointSide(ctx, joint.b, row.b, row.r_b, row.center_b, row.q_b);
    if (row.a == kNoBody && row.b == kNoBody) return;
    row.softness = softness;
    row.joint = static_cast<std::uint32_t>(joints.size());
    joints.push_back(joint);
    rows.push_back(row);
  };
  KeptImpulses previous;
  previous.swap(ws.link_impulses);
  ctx.links.forEach([&](const auto& kind) {
    using Kind = typename std::decay_t<decltype(kind)>::value_type;
    for (const auto& link : kind) {
      if (!joined(link.a) && !joined(link.b)) continue;
      const LinkLimits limits = LinkKind<Kind>::limits(link);
      DistanceJoint joint;
      joint.a = JointEnd::atParticle(link.a);
      joint.b = link.anchored() ? JointEnd::inWorld(link.anchor) : JointEnd::atParticle(link.b);
      joint.min_length = limits.pulls_only ? 0.0 : limits.length;
      joint.max_length = limits.length;
      joint.id = link.id;
      if (const KeptImpulses::Entry* kept = previous.find(link.id)) {
        joint.lower_impulse = kept->lower;
        joint.upper_impulse = kept->upper;
      }
      addRow(joint, link_softness, ws.link_joints, ws.link_rows);
    }
  });
  if (!pairs) return;
  const auto radius = particles.radii();
  const auto velocity = particles.velocities();
  const Real lead = particleLead(ctx);
  const ContactResolver& resolver = ctx.contacts.resolver;
  const Real substep_ratio = resolver.lastSubstep() > 0.0 ? ctx.h / resolver.lastSubstep() : 1.0;
  for (const Contact& c : ctx.contacts.contacts) {
    if (!particlePair(c) || !joinedAt(c.a) || !joinedAt(c.b)) continue;
    ParticlePair& pair = ws.particle_pairs.emplace_back();
    pair.a = ws.solver_of_particle[c.a];
    pair.b = ws.solver_of_particle[c.b];
    pair.start_a = position.col(c.a) - lead * velocity.col(c.a);
    pair.start_b = position.col(c.b) - lead * velocity.col(c.b);
    pair.touching = radius[c.a] + radius[c.b];
    pair.friction = c.friction;
    pair.key = c.key;
    if (const KeptImpulses::Entry* kept = ws.pair_impulses.find(c.key)) {
      pair.normal_impulse = kept->lower;
      pair.friction_impulse = kept->friction;
    } else if (resolver.lastImpulses(c.key, pair.normal_impulse, pair.friction_impulse)) {
      // The particle solver's until now (the body under the pile just woke): its impulses, over
      // its last substep, as impulses over this one.
      pair.normal_impulse *= substep_ratio;
      pair.friction_impulse *= substep_ratio;
    }
    ws.pair_by_key.emplace_back(c.key, static_cast<std::uint32_t>(ws.particle_pairs.size() - 1));
  }
  std::sort(ws.pair_by_key.begin(), ws.pair_by_key.end());
}

void prepareJoints(StepContext& ctx) {
  BodyWorkspace& ws = *ctx.body_ws;
  const BodySettings& s = *ctx.body_settings;
  const Softness softness =
      makeSoft(std::min(s.joint_hertz, 0.25 / ctx.h), s.joint_damping_ratio, ctx.h);
  ws.joints.of_kind.resize(kindCount(JointKinds{}));
  std::size_t kind = 0;
  ctx.joints->forEach([&](auto& array) {
    std::vector<JointRow>& rows = ws.joints.of_kind[kind++];
    rows.clear();
    for (std::size_t j = 0; j < array.size(); ++j) {
      JointRow row;
      jointSide(ctx, array[j].a, row.a, row.r_a, row.center_a, row.q_a);
      jointSide(ctx, array[j].b, row.b, row.r_b, row.center_b, row.q_b);
      if (row.a == kNoBody && row.b == kNoBody) continue;  // nothing it joins can move
      for (const std::int32_t k : {row.a, row.b}) {
        if (k != kNoBody) ctx.body_ws->solver[static_cast<std::size_t>(k)].held = true;
      }
      row.softness = softness;
      row.joint = static_cast<std::uint32_t>(j);
      rows.push_back(row);
    }
  });
  coupleParticles(ctx, softness);
}

template <typename F>
void forEachJointRow(StepContext& ctx, F&& f) {
  std::size_t kind = 0;
  ctx.joints->forEach([&](auto& array) {
    using Kind = typename std::decay_t<decltype(array)>::value_type;
    for (const JointRow& row : ctx.body_ws->joints.of_kind[kind]) {
      f(KindTag<Kind>{}, array[row.joint], row);
    }
    ++kind;
  });
  for (const JointRow& row : ctx.body_ws->link_rows) {
    f(KindTag<DistanceJoint>{}, ctx.body_ws->link_joints[row.joint], row);
  }
}

ContactPass contactPass(const StepContext& ctx, const bool use_bias, const bool top_down) {
  const BodySettings& s = *ctx.body_settings;
  return ContactPass{ctx.h,         use_bias, s.max_push_speed, s.restitution_threshold,
                     s.linear_slop, top_down, s.sleep_speed};
}

void warmStart(StepContext& ctx) {
  BodyWorkspace& ws = *ctx.body_ws;
  forEachJointRow(ctx, [&](auto tag, auto& joint, const JointRow& row) {
    JointKind<typename decltype(tag)::type>::warmStart(joint, row, ws.solver);
  });
  warmStartParticlePairs(ws.particle_pairs, ws.solver);
  warmStartContacts(ws.constraints, ws.solver, contactPass(ctx, true, false));
}

void solvePass(StepContext& ctx, const bool use_bias, const bool top_down) {
  BodyWorkspace& ws = *ctx.body_ws;
  const JointPass pass{ws.solver, ctx.h, use_bias};
  forEachJointRow(ctx, [&](auto tag, auto& joint, const JointRow& row) {
    JointKind<typename decltype(tag)::type>::solve(joint, row, pass);
  });
  solveParticlePairs(ws.particle_pairs, ws.solver, ctx.h);
  solveContacts(ws.constraints, ws.solver, contactPass(ctx, use_bias, top_down));
}

// The shock rows (contact_solver.h), bottom up as the constraints: contacts between two moving
// bodies, one resting on the other (normal within 45 degrees of gravity's line), that carry a
// load (warm started or guessed). Two bodies touching in flight, or held together by a joint,
// carry none and are left to the passes. Each row's carrier is the body of infinite mass (a
// kinematic one) its lower side rests on, directly or through the bodies below it, if any; its
// base the lowest moving body under it, and whether that rests on something still (and through
// which contacts: ws.still_supports, for gripBases).
void prepareShockRows(StepContext& ctx) {
  BodyWorkspace& ws = *ctx.body_ws;
  ws.shock_rows.clear();
  ws.still_supports.clear();
  const Vec3 up = -ctx.config.gravity;
  if (!ctx.body_settings->shock_propagation || up.norm() == 0.0) return;
  const Vec3 up_unit = up.normalized();
  ws.carrier_of.assign(ws.solver.size(), kNoBody);
  ws.carrier_center_of.assign(ws.solver.size(), Vec3::Zero());
  ws.base_of.assign(ws.solver.size(), kNoBody);
  ws.on_still.assign(ws.solver.size(), 0);
  for (std::uint32_t r = 0; r < ws.constraints.size(); ++r) {
    const ContactSides& sides = ws.constraint_sides[r];
    if ((sides.a == kNoBody) == (sides.b == kNoBody)) continue;
    // n points from a to b: b rests on a when n points up.
    const Real vertical = ws.constraints[r].normal.dot(up_unit);
    if (std::abs(vertical) < std::sqrt(0.5)) continue;
    const std::int32_t above = vertical > 0.0 ? sides.b : sides.a;
    if (above == kNoBody) continue;
    ws.on_still[static_cast<std::size_t>(above)] = 1;
    ws.still_supports.emplace_back(r, above);
  }
  for (std::uint32_t r = 0; r < ws.constraints.size(); ++r) {
    if (r + kPrefetchAhead < ws.constraints.size()) {
      ws.kept_masses.prefetch(ws.contacts[ws.constraints[r + kPrefetchAhead].contact],
                              &BodyContact::KeptMasses::upper_alone);
    }
    const ContactConstraint& c = ws.constraints[r];
    if (c.a == kNoBody || c.b == kNoBody) continue;
    const Real vertical = c.normal.dot(up_unit);
    if (std::abs(vertical) < std::sqrt(0.5)) continue;
    if (c.normalLoad() <= 0.0) continue;
    // n points from a to b: b rests on a when n points up.
    const ContactSides& sides = ws.constraint_sides[r];
    const auto lower = static_cast<std::size_t>(vertical > 0.0 ? sides.a : sides.b);
    const auto above = static_cast<std::size_t>(vertical > 0.0 ? sides.b : sides.a);
    const Vec3& lower_center = vertical > 0.0 ? sides.center_a : sides.center_b;
    std::int32_t carrier = ws.carrier_of[lower];
    Vec3 carrier_center = ws.carrier_center_of[lower];
    if (ws.solver[lower].inverse_mass == 0.0) {
      carrier = static_cast<std::int32_t>(lower);
      carrier_center = lower_center;
    }
    if (ws.carrier_of[above] == kNoBody && carrier != kNoBody) {
      ws.carrier_of[above] = carrier;
      ws.carrier_center_of[above] = carrier_center;
    }
    const std::int32_t base =
        ws.base_of[lower] != kNoBody ? ws.base_of[lower] : static_cast<std::int32_t>(lower);
    if (ws.base_of[above] == kNoBody) ws.base_of[above] = base;
    BodyContact& contact = ws.contacts[c.contact];
    ShockRow& row = ws.shock_rows.emplace_back();
    row.constraint = r;
    prepareHeldStill(c, vertical > 0.0, ws.solver, ws.kept_masses.of(contact).upper_alone,
                     row.upper_alone);
    row.carrier = carrier;
    row.lower_from_carrier = lower_center - carrier_center;
    row.base = base;
    row.base_on_still = ws.on_still[static_cast<std::size_t>(base)] != 0;
  }
}

// Whether each shock row's base is gripped by what still thing it rests on: a contact whose
// friction, after this substep's passes, is inside its bound (static friction). A base whose
// friction slides (at its bound, or none: frictionless ground) is driven or gliding, not coming
// to rest, so its pile is not held in the ground's frame by friction (propagateShock).
void gripBases(BodyWorkspace& ws) {
  if (ws.shock_rows.empty()) return;
  ws.grips_still.assign(ws.solver.size(), 0);
  for (const auto& [r, above] : ws.still_supports) {
    const ContactConstraint& c = ws.constraints[r];
    const Real load = c.normalLoad();
    // The passes clamp friction to mu times the load they saw; a hair inside that is sliding.
    const Real friction = std::hypot(c.friction_impulse[0], c.friction_impulse[1]);
    if (load > 0.0 && friction < 0.999 * c.friction * load) {
      ws.grips_still[static_cast<std::size_t>(above)] = 1;
    }
  }
  for (ShockRow& row : ws.shock_rows) {
    row.base_grips = ws.grips_still[static_cast<std::size_t>(row.base)] != 0;
  }
}

}  // namespace

void beginBodyStep(StepContext& ctx) {
  if (!ctx.bodies) return;
  BodyStore& bodies = *ctx.bodies;
  BodyWorkspace& ws = *ctx.body_ws;
  ws.prepared = false;
  ws.solver.clear();
  ws.solver_of_body.assign(bodies.size(), kNoBody);
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    if (!bodies.awake(i) || bodies.type(i) == BodyType::kFixed) continue;
    bodies.refreshWorldInertia(i);
    SolverBody sb;
    sb.v = bodies.linearVelocity(i);
    sb.w = bodies.angularVelocity(i);
    sb.inverse_mass = bodies.inverseMass(i);
    sb.inverse_inertia = bodies.worldInverseInertia(i);
    ws.solver_of_body[i] = static_cast<std::int32_t>(ws.solver.size());
    ws.solver.push_back(sb);
  }
  ws.first_particle = ws.solver.size();
  ws.particle_of_solver.clear();
  ws.solver_of_particle.clear();
  ws.constraints.clear();
}

void integrateBodyVelocities(StepContext& ctx) {
  if (!ctx.bodies) return;
  const BodyStore& bodies = *ctx.bodies;
  BodyWorkspace& ws = *ctx.body_ws;
  const Real h = ctx.h;
  const Vec3& g = ctx.config.gravity;
  const bool generated = !ws.generator_force.empty();
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const std::int32_t k = ws.solver_of_body[i];
    if (k == kNoBody || !bodies.dynamic(i)) continue;
    const auto solver = static_cast<std::size_t>(k);
    SolverBody& sb = ws.solver[solver];
    // The requests' force and torque, and the generators' (body_force_stage.h). A generator's
    // force changes with the state: the body it pushes moves as semi-implicit Euler moves it,
    // x' = x + h v' (the free body's parabola, x' = x + h v' - h^2 a / 2, would gain a spring's
    // energy and hold a body at rest on one at v = h g / 2).
    const bool pushed = generated && !ws.generator_force[solver].isZero(0.0);
    const Vec3 force =
        pushed ? Vec3(bodies.force(i) + ws.generator_force[solver]) : bodies.force(i);
    const Vec3 torque =
        generated ? Vec3(bodies.torque(i) + ws.generator_torque[solver]) : bodies.torque(i);
    if (pushed) sb.held = true;
    // v' = (v + h (g + F / m)) / (1 + h c)
    sb.acceleration = g + bodies.inverseMass(i) * force;
    sb.v = (sb.v + h * sb.acceleration) / (1.0 + h * bodies.linearDamping(i));
    // In the principal frame: the torque's kick, then the gyroscopic term implicitly.
    const Quat q = sb.dq * bodies.orientation(i);
    Vec3 w_body = q.conjugate() * sb.w;
    w_body += h * bodies.inversePrincipalInertia(i).cwiseProduct(q.conjugate() * torque);
    if (ctx.body_settings->gyroscopic) {
      w_body = gyroscopicStep(w_body, bodies.principalInertia(i), h);
    }
    sb.w = (q * w_body) / (1.0 + h * bodies.angularDamping(i));
  }
}

// Nothing moves and no particle can wake anything: the contacts stay as they are, no row is made
// (a sleeping pile costs next to nothing).
bool nothingToFind(const StepContext& ctx) {
  return ctx.body_ws->solver.empty() && ctx.particles.empty();
}

void findBodyPairs(StepContext& ctx) {
  if (!ctx.bodies) return;
  BodyStore& bodies = *ctx.bodies;
  BodyWorkspace& ws = *ctx.body_ws;
  if (ctx.substep != 0) {
    placeMovingSurfaces(ctx);
    return;
  }
  updateBodyProxies(collisionScene(ctx), bodies, ws);
  ctx.contacts.body_surfaces.clear();
  ws.moving_surfaces.clear();
  if (nothingToFind(ctx)) return;
  findBodyContacts(collisionScene(ctx), ws);
  // A sleeping island touched by an awake body wakes now: its kept contacts get rows this step
  // (listed again here) and are found again from the next.
  if (wakeTouchedIslands(bodies, ws, *ctx.joints)) {
    listAwakeContacts(bodies, ws);
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      if (!bodies.awake(i) || bodies.type(i) == BodyType::kFixed) continue;
      if (ws.solver_of_body[i] != kNoBody) continue;
      bodies.refreshWorldInertia(i);
      SolverBody sb;
      sb.inverse_mass = bodies.inverseMass(i);
      sb.inverse_inertia = bodies.worldInverseInertia(i);
      ws.solver_of_body[i] = static_cast<std::int32_t>(ws.solver.size());
      ws.solver.push_back(sb);
    }
    ws.first_particle = ws.solver.size();
  }
  // The contacts with an awake side bottom up along gravity (by each contact's first point; ties
  // in key order): the others of a pile that mostly sleeps are passed over.
  std::vector<std::pair<Real, std::uint32_t>>& order = ws.contact_order;
  order.clear();
  const Vec3 up = -ctx.config.gravity;
  for (const std::uint32_t c : ws.awake_contacts) {
    const Manifold& m = ws.contacts[c].manifold;
    order.emplace_back(m.count > 0 ? up.dot(m.points[0].point) : 0.0, c);
  }
  std::sort(order.begin(), order.end());
  // The particles' contacts with bodies are made here, before the particles' own, so the
  // particle solver can take them first with the colliders' (a pile is held up from below).
  if (!ctx.contacts_active) return;
  for (const auto& entry : order) {
    const BodyContact& contact = ws.contacts[entry.second];
    if (contact.key.other != ContactOther::kParticle) continue;
    addSurface(ctx, contact, *ctx.particles.find(ParticleId::fromPacked(contact.key.b)));
  }
  placeMovingSurfaces(ctx);
}

namespace {

// The particle contacts the body solver has pair rows for (coupleParticles), found among this
// substep's, in a pile that rests on moving bodies alone: their velocities are that solver's
// (two solvers on one pile undid each other's lateral pushes, and the particle solver ran all its
// passes every substep). A pile that also rests on something else (a collider, a still body, a
// particle the body solver does not move) stays in both: split between them along its contacts,
// the part on the ground slid for seconds.
void leavePairsToBodySolver(StepContext& ctx) {
  BodyWorkspace& ws = *ctx.body_ws;
  if (!ws.prepared || ws.particle_pairs.empty()) return;
  for (ParticlePair& pair : ws.particle_pairs) pair.alone = false;
  std::vector<Contact>& contacts = ctx.contacts.contacts;
  const std::size_t count = ws.particle_of_solver.size();
  const auto joined = [&](const std::uint32_t p) {
    const std::int32_t k = p < ws.solver_of_particle.size() ? ws.solver_of_particle[p] : kNoBody;
    return k == kNoBody ? count : static_cast<std::size_t>(k) - ws.first_particle;
  };
  // The piles, and whether each rests elsewhere.
  UnionFind& piles = ws.piles;
  std::vector<std::uint8_t>& elsewhere = ws.pile_rests_elsewhere;
  piles.reset(count);
  elsewhere.assign(count, 0);
  for (const Contact& c : contacts) {
    if (c.kind != ContactKind::kContact || c.position_only) continue;
    const std::size_t a = joined(c.a);
    const std::size_t b = c.b == kNoParticle ? count : joined(c.b);
    if (a == count && b == count) continue;
    if (c.b != kNoParticle && a != count && b != count) {
      piles.join(a, b);
      continue;
    }
    elsewhere[a != count ? a : b] = 1;
  }
  for (std::size_t k = 0; k < count; ++k) {
    if (elsewhere[k]) elsewhere[piles.find(k)] = 1;
  }
  for (std::uint32_t i = 0; i < contacts.size(); ++i) {
    Contact& c = contacts[i];
    if (!particlePair(c)) continue;
    const auto it = std::lower_bound(ws.pair_by_key.begin(), ws.pair_by_key.end(),
                                     std::pair<std::uint64_t, std::uint32_t>{c.key, 0});
    if (it == ws.pair_by_key.end() || it->first != c.key) continue;
    if (elsewhere[piles.find(joined(c.a))]) continue;
    c.body_solved = true;
    ParticlePair& pair = ws.particle_pairs[it->second];
    pair.alone = true;
    pair.contact = i;
  }
}

// What the pair rows ended the substep with, kept as the particle solver keeps its own contacts'
// impulses: it warm starts from them when it takes the contacts back (the body under the pile
// asleep, its grains no longer the body solver's).
void handBackPairImpulses(StepContext& ctx) {
  ContactResolver& resolver = ctx.contacts.resolver;
  for (const ParticlePair& pair : ctx.body_ws->particle_pairs) {
    if (!pair.alone) continue;
    resolver.keepImpulses(pair.contact, pair.key, pair.normal_impulse, pair.friction_impulse);
  }
}

// The step's body rows, made in its first substep.
void generateStepBodyContacts(StepContext& ctx) {
  BodyStore& bodies = *ctx.bodies;
  BodyWorkspace& ws = *ctx.body_ws;
  const BodySettings& settings = *ctx.body_settings;
  if (nothingToFind(ctx)) {
    ws.awake_contacts.clear();
    ws.constraints.clear();
    ws.constraint_sides.clear();
    ws.shock_rows.clear();
    ws.link_joints.clear();
    ws.link_rows.clear();
    ws.particle_pairs.clear();
    ws.pair_by_key.clear();
    for (std::vector<JointRow>& rows : ws.joints.of_kind) rows.clear();
    ws.prepared = false;
    return;
  }
  const auto side = [&](const ShapeIndex s, Vec3& center, Real& rounding) {
    const std::size_t i = bodies.denseIndexUnchecked(bodies.shapes()[s].body);
    center = bodies.position(i);
    rounding = shapeRounding(bodies.shapes()[s].geometry);
    return ws.solver_of_body[i];
  };
  // The rows in the order findBodyPairs gave the contacts (bottom up).
  const std::vector<std::pair<Real, std::uint32_t>>& order = ws.contact_order;
  ws.constraints.clear();
  ws.constraint_sides.clear();
  // Each contact reads its kept masses, 512 bytes in a pool apart from it; in a pile a few
  // thousand contacts wide they are out of the cache: ask for a contact's while preparing the
  // one kPrefetchAhead before it in the order, and for the contact itself (its slot's index is in
  // it) twice as far ahead.
  for (std::size_t i = 0; i < order.size(); ++i) {
    if (i + 2 * kPrefetchAhead < order.size()) {
      prefetchBytes(&ws.contacts[order[i + 2 * kPrefetchAhead].second], sizeof(BodyContact));
    }
    if (i + kPrefetchAhead < order.size()) {
      ws.kept_masses.prefetch(ws.contacts[order[i + kPrefetchAhead].second],
                              &BodyContact::KeptMasses::coupled);
    }
    const std::uint32_t c = order[i].second;
    BodyContact& contact = ws.contacts[c];
    ContactSides sides;
    sides.a = side(contact.key.shape, sides.center_a, sides.rounding_a);
    switch (contact.key.other) {
      case ContactOther::kShape:
        sides.b = side(static_cast<ShapeIndex>(contact.key.b), sides.center_b, sides.rounding_b);
        break;
      case ContactOther::kCollider:
        sides.b = kNoBody;
        break;
      case ContactOther::kParticle: {
        // On a still body: the particle solver's (findBodyPairs made it a BodySurface).
        if (sides.a == kNoBody && ctx.contacts_active) continue;
        const std::size_t p = *ctx.particles.find(ParticleId::fromPacked(contact.key.b));
        sides.b = particleSolverBody(ctx, p);
        sides.center_b = ctx.particles.positions().col(static_cast<Eigen::Index>(p));
        break;
      }
    }
    if (sides.a == kNoBody && sides.b == kNoBody) continue;
    for (const std::int32_t k : {sides.a, sides.b}) {
      if (k != kNoBody) ws.solver[static_cast<std::size_t>(k)].held = true;
    }
    const bool still = sides.a == kNoBody || sides.b == kNoBody;
    // A particle cannot turn: a twist on its contact would turn the body with nothing turning
    // back, so the particle's point keeps no lever.
    const Real min_twist_lever =
        contact.key.other == ContactOther::kParticle ? 0.0 : settings.min_twist_lever;
    prepareContact(contact, static_cast<std::uint32_t>(c), sides, ws.solver,
                   contactSoftness(settings, ctx.h, still), min_twist_lever,
                   ws.kept_masses.of(contact).coupled, ws.constraints.emplace_back());
    ws.constraint_sides.push_back(sides);
  }
  if (settings.guess_loads) {
    std::vector<Real>& heights = ws.heights;
    heights.assign(ws.solver.size(), 0.0);
    const Vec3 up = -ctx.config.gravity;
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      const std::int32_t k = ws.solver_of_body[i];
      if (k != kNoBody) heights[static_cast<std::size_t>(k)] = up.dot(bodies.position(i));
    }
    const auto x = ctx.particles.positions();
    for (std::size_t k = 0; k < ws.particle_of_solver.size(); ++k) {
      heights[ws.first_particle + k] =
          up.dot(Vec3(x.col(static_cast<Eigen::Index>(ws.particle_of_solver[k]))));
    }
    guessRestingLoads(ws.constraints, ws.solver, heights, ctx.config.gravity, ctx.h, ctx.dt,
                      ws.resting_loads);
  }
  prepareShockRows(ctx);
  prepareJoints(ctx);
  // Where the particles move from (particleLead): their solver bodies' moves are measured from
  // here.
  const auto count = static_cast<Eigen::Index>(ws.particle_of_solver.size());
  ws.particle_start.resize(3, count);
  ws.particle_velocity.resize(3, count);
  ws.particle_moved.resize(3, count);
  const auto x = ctx.particles.positions();
  const auto v = ctx.particles.velocities();
  const Real lead = particleLead(ctx);
  for (Eigen::Index k = 0; k < count; ++k) {
    const auto p = static_cast<Eigen::Index>(ws.particle_of_solver[k]);
    ws.particle_start.col(k) = x.col(p) - lead * v.col(p);
  }
  ws.prepared = !ws.solver.empty();
}

}  // namespace

void generateBodyContacts(StepContext& ctx) {
  if (!ctx.bodies) return;
  if (ctx.substep == 0) generateStepBodyContacts(ctx);
  leavePairsToBodySolver(ctx);
}

void solveBodyConstraints(StepContext& ctx) {
  if (!ctx.bodies || !ctx.body_ws->prepared) return;
  loadParticles(ctx, true);
  warmStart(ctx);
  for (int i = 0; i < ctx.body_settings->iterations; ++i) solvePass(ctx, true, i % 2 == 1);
  BodyWorkspace& ws = *ctx.body_ws;
  gripBases(ws);
  propagateShock(ws.shock_rows, ws.constraints, ws.solver, contactPass(ctx, true, false));
  storeParticles(ctx, true);
}

void integrateBodyPositions(StepContext& ctx) {
  if (!ctx.bodies) return;
  BodyWorkspace& ws = *ctx.body_ws;
  const Real h = ctx.h;
  for (std::size_t k = 0; k < ws.first_particle; ++k) {
    SolverBody& sb = ws.solver[k];
    // Free: x' = x + h v + h^2 a / 2 = x + h v' - h^2 a / 2 (v' = v + h a), exact for a
    // constant a; held: x' = x + h v', the solver's assumption.
    sb.dp += sb.held ? Vec3(h * (sb.v + sb.pv)) : Vec3(h * sb.v - 0.5 * h * h * sb.acceleration);
    sb.dq = (rotationOver(sb.w + sb.pw, h) * sb.dq).normalized();
    sb.dq_matrix = sb.dq.toRotationMatrix();
    sb.pv.setZero();
    sb.pw.setZero();
    sb.flew = false;
  }
  if (!ws.prepared) return;
  if (ctx.body_settings->relax_iterations > 0) {
    loadParticles(ctx, false);
    takeSeparations(ws.constraints, ws.solver);
    for (int i = 0; i < ctx.body_settings->relax_iterations; ++i) {
      solvePass(ctx, false, i % 2 == 1);
    }
    storeParticles(ctx, false);
  }
  handBackPairImpulses(ctx);
}

void finaliseBodies(StepContext& ctx) {
  if (!ctx.bodies) return;
  BodyStore& bodies = *ctx.bodies;
  BodyWorkspace& ws = *ctx.body_ws;
  if (ws.prepared) storeImpulses(ws.constraints, ws.contacts);
  ws.link_impulses.clear();
  for (const DistanceJoint& link : ws.link_joints) {
    ws.link_impulses.add(link.id, link.lower_impulse, link.upper_impulse);
  }
  ws.link_impulses.sortByKey();
  ws.pair_impulses.clear();
  for (const ParticlePair& pair : ws.particle_pairs) {
    ws.pair_impulses.add(pair.key, pair.normal_impulse, 0.0, pair.friction_impulse);
  }
  ws.pair_impulses.sortByKey();
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    bodies.force(i).setZero();
    bodies.torque(i).setZero();
    const std::int32_t k = ws.solver_of_body[i];
    if (k == kNoBody) continue;
    const SolverBody& sb = ws.solver[static_cast<std::size_t>(k)];
    bodies.position(i) += sb.dp;
    bodies.orientation(i) = (sb.dq * bodies.orientation(i)).normalized();
    bodies.linearVelocity(i) = sb.v;
    bodies.angularVelocity(i) = sb.w;
  }
  // Bodies a fast particle touches stay awake.
  std::vector<std::uint8_t> busy(bodies.size(), 0);
  std::vector<std::size_t> woken;
  const auto v = ctx.particles.velocities();
  for (const BodyContact& c : ws.contacts) {
    if (c.key.other != ContactOther::kParticle) continue;
    const auto p = ctx.particles.find(ParticleId::fromPacked(c.key.b));
    if (!p || v.col(static_cast<Eigen::Index>(*p)).norm() < ctx.body_settings->sleep_speed) {
      continue;
    }
    const std::size_t i = bodies.denseIndexUnchecked(bodies.shapes()[c.key.shape].body);
    busy[i] = 1;
    if (!bodies.awake(i)) woken.push_back(i);
  }
  wakeIslands(bodies, ws, *ctx.joints, woken);
  // Particles never sleep: a body joined to one stays awake with it.
  ctx.joints->forEach([&](const auto& kind) {
    for (const auto& joint : kind) {
      if (!joint.a.isParticle() && !joint.b.isParticle()) continue;
      for (const JointEnd* end : {&joint.a, &joint.b}) {
        if (end->isBody()) busy[bodies.denseIndexUnchecked(end->body)] = 1;
      }
    }
  });
  // And so does a body a force generator joins to another body or a particle.
  if (ctx.body_generators) markJoinedBodies(*ctx.body_generators, bodies, busy);
  updateSleep(bodies, ws, *ctx.joints, *ctx.body_settings, ctx.dt, busy);
}

}  // namespace engine
}  // namespace mass_aggregate_sim
