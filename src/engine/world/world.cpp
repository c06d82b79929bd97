// World: construction, settings, and every request that changes the scene, each validated (by
// its kind) before anything changes. The step is in step.cpp, the guards in energy_guard.cpp.
#include "mass_aggregate_sim/engine/world/world.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>
#include <variant>

#include "engine/bodies/body_workspace.h"
#include "engine/collision/geometry.h"
#include "engine/core/damping_flow.h"
#include "engine/core/state_hash.h"
#include "engine/forces/body_force_stage.h"
#include "engine/integrators/integrator_state.h"
#include "engine/solver/contact_workspace.h"
#include "engine/world/guard_state.h"
#include "engine/world/step_caches.h"

namespace mass_aggregate_sim {
namespace engine {

World::World() = default;

World::World(const WorldConfig& config) : World() {
  const Status valid = setConfig(config);
  if (!valid) throw InvalidConfig("invalid world config: " + valid.message());
}

Result<World> World::create(const WorldConfig& config) {
  const Status valid = validateConfig(config);
  if (!valid) return Status::error("invalid world config: " + valid.message());
  return World(config);
}

World::~World() = default;
World::World(const World&) = default;
World& World::operator=(const World&) = default;
World::World(World&&) noexcept = default;
World& World::operator=(World&&) noexcept = default;

Status World::setConfig(const WorldConfig& config) {
  const Status valid = validateConfig(config);
  if (!valid) return valid;
  if (config.dt != config_.dt) {
    // Keep time exact: restart counting steps of the new dt from the current time.
    time_origin_ = time();
    steps_since_origin_ = 0;
    accumulator_ = 0.0;
  }
  // Another substep length seeds position Verlet's histories again by itself; another integrator
  // must too (a history kept from before would be stale).
  if (config.integrator != config_.integrator) integration_->verlet_history_h = 0.0;
  config_ = config;
  stateChanged();
  return Status::ok();
}

void World::stateChanged() {
  integration_->acceleration_valid = false;
  caches_->forces.forgetAhead();
  guard_->energy_known = false;
}

// --- particles ---

Result<ParticleId> World::addParticle(const ParticleSpec& spec) {
  const Status valid = validateSpec(spec);
  if (!valid) return valid;
  const ParticleId id = particles_.add(spec);
  integration_->verlet_unseeded = true;
  stateChanged();
  return id;
}

Status World::removeParticle(const ParticleId id) {
  const Status valid = particles_.checkReference(id, "particle");
  if (!valid) return valid;
  const auto eraseReferencing = [id](auto& kind, auto refersTo) {
    kind.erase(std::remove_if(kind.begin(), kind.end(),
                              [&](const auto& item) { return refersTo(item, id); }),
               kind.end());
  };
  generators_.forEach([&](auto& kind) {
    using Kind = typename std::decay_t<decltype(kind)>::value_type;
    eraseReferencing(kind, ForceKind<Kind>::refersTo);
  });
  links_.forEach([&](auto& kind) {
    using Kind = typename std::decay_t<decltype(kind)>::value_type;
    eraseReferencing(kind, LinkKind<Kind>::refersTo);
  });
  joints_.forEach([&](auto& kind) {
    kind.erase(std::remove_if(kind.begin(), kind.end(),
                              [&](const auto& joint) {
                                return joint.a.particle == id || joint.b.particle == id;
                              }),
               kind.end());
  });
  removeBodyGeneratorsOf(id);
  materials_.forget(id);
  const Status removed = particles_.remove(id);
  contacts_->resolver.clearWarmStart();
  ++generators_version_;
  stateChanged();
  return removed;
}

Status World::setPosition(const ParticleId id, const Vec3& position) {
  const auto dense = particles_.find(id);
  if (!dense) return Status::error("particle: " + particles_.describeInvalid(id));
  if (!position.allFinite()) return Status::error("position is not finite");
  auto x = particles_.positions();
  // Position Verlet's history moves along, so the particle keeps its velocity.
  particles_.previousPositions().col(*dense) += position - x.col(*dense);
  x.col(*dense) = position;
  stateChanged();
  return Status::ok();
}

Status World::setVelocity(const ParticleId id, const Vec3& velocity) {
  const auto dense = particles_.find(id);
  if (!dense) return Status::error("particle: " + particles_.describeInvalid(id));
  if (!velocity.allFinite()) return Status::error("velocity is not finite");
  if (particles_.inverseMasses()[*dense] <= 0.0 && !velocity.isZero(0.0)) {
    return Status::error("particle " + id.str() + " is immovable: its velocity stays zero");
  }
  particles_.velocities().col(*dense) = velocity;
  particles_.historySeeded()[*dense] = 0.0;
  integration_->verlet_unseeded = true;
  stateChanged();
  return Status::ok();
}

Status World::applyImpulse(const ParticleId id, const Vec3& impulse) {
  const auto dense = particles_.find(id);
  if (!dense) return Status::error("particle: " + particles_.describeInvalid(id));
  if (!impulse.allFinite()) return Status::error("impulse is not finite");
  const Real inverse_mass = particles_.inverseMasses()[*dense];
  if (inverse_mass <= 0.0) {
    return Status::error("particle " + id.str() + " is immovable: an impulse cannot move it");
  }
  // dv = J / m
  const Vec3 dv = impulse * inverse_mass;
  particles_.velocities().col(*dense) += dv;
  // Position Verlet: the half-step velocity behind v gets the kick too (v = d^(h/2) v_half + ...).
  const Real history_h = integration_->verlet_history_h;
  const Real half_decay = dampingFlow(particles_.dampings()[*dense], 0.5 * history_h).decay;
  if (history_h > 0.0 && half_decay > 0.0) {
    particles_.previousPositions().col(*dense) -= history_h * dv / half_decay;
  }
  stateChanged();
  return Status::ok();
}

Status World::addForce(const ParticleId id, const Vec3& force) {
  const auto dense = particles_.find(id);
  if (!dense) return Status::error("particle: " + particles_.describeInvalid(id));
  if (!force.allFinite()) return Status::error("force is not finite");
  particles_.forces().col(*dense) += force;
  has_external_force_ = true;
  // External work: the energy guard takes a new reference. No force cache holds external forces,
  // and no particle's history changes.
  guard_->energy_known = false;
  return Status::ok();
}

// --- force generators and links ---

Status World::removeGenerator(const GeneratorId id) {
  const auto eraseById = [id](auto& kind) {
    const auto it =
        std::find_if(kind.begin(), kind.end(), [id](const auto& item) { return item.id == id; });
    if (it == kind.end()) return false;
    kind.erase(it);
    return true;
  };
  const auto eraseBodyGenerator = [&](auto& kind) {
    using Kind = typename std::decay_t<decltype(kind)>::value_type;
    const auto it =
        std::find_if(kind.begin(), kind.end(), [id](const auto& item) { return item.id == id; });
    if (it == kind.end()) return false;
    wakeBodies(BodyForceKind<Kind>::bodiesOf(*it));
    kind.erase(it);
    return true;
  };
  if (!generators_.any(eraseById) && !links_.any(eraseById) &&
      !body_generators_.any(eraseBodyGenerator)) {
    return Status::error("no force generator or link with id " + std::to_string(id));
  }
  ++generators_version_;
  stateChanged();
  return Status::ok();
}

std::vector<LinkTension> World::linkTensions() const {
  std::vector<LinkTension> out;
  out.reserve(links_.size());
  const ContactResolver& resolver = contacts_->resolver;
  const Real h = resolver.lastSubstep();
  links_.forEach([&](const auto& kind) {
    for (const auto& link : kind) {
      // F = J / h: the impulse the constraint applied over the substep, as a mean force.
      const Real tension = h > 0.0 ? resolver.lastImpulse(linkContactKey(link.id)) / h : 0.0;
      out.push_back(LinkTension{link.id, tension});
    }
  });
  std::sort(out.begin(), out.end(),
            [](const LinkTension& x, const LinkTension& y) { return x.id < y.id; });
  return out;
}

// --- colliders, settings and materials ---

Result<ColliderId> World::nextColliderId() {
  if (next_collider_id_ == std::numeric_limits<ColliderId>::max()) {
    return Status::error("collider ids exhausted");
  }
  return next_collider_id_++;
}

Status World::removeCollider(const ColliderId id) {
  const bool removed = colliders_.any([id](auto& kind) {
    const auto it =
        std::find_if(kind.begin(), kind.end(), [id](const auto& shape) { return shape.id == id; });
    if (it == kind.end()) return false;
    kind.erase(it);
    return true;
  });
  if (!removed) return Status::error("no collider with id " + std::to_string(id));
  ++colliders_version_;
  // What rested on it falls.
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    if (bodies_.type(i) != BodyType::kFixed) bodies_.setAwake(i, true);
  }
  return Status::ok();
}

Status World::setCollisionSettings(const CollisionSettings& settings) {
  const Status valid = validateCollisionSettings(settings);
  if (!valid) return valid;
  collision_settings_ = settings;
  return Status::ok();
}

Status World::setParticleMaterial(const ParticleId id, const Material& material) {
  Status valid = particles_.checkReference(id, "particle");
  if (valid) valid = checkMaterial(material);
  if (!valid) return valid;
  materials_.set(id, material);
  return Status::ok();
}

// --- queries ---

std::optional<RayHit> World::raycast(const Vec3& origin, const Vec3& direction,
                                     const Real max_distance) const {
  std::optional<RayHit> nearest =
      raycastScene(particles_, colliders_, origin, direction, max_distance);
  const Real length = direction.norm();
  if (bodies_.empty() || !(length > 0.0) || !std::isfinite(length) || !origin.allFinite()) {
    return nearest;
  }
  const Vec3 d = direction / length;
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    for (const ShapeIndex s : bodies_.shapesOf(i)) {
      const BodyShape& shape = bodies_.shapes()[s];
      const Real reach = nearest ? nearest->distance : max_distance;
      const std::optional<RayShapeHit> hit = std::visit(
          [&](const auto& g) {
            return BodyShapeKind<std::decay_t<decltype(g)>>::raycast(g, Frame(bodies_.shapePose(s)),
                                                                     origin, d, reach);
          },
          shape.geometry);
      if (!hit || (nearest && hit->t >= nearest->distance)) continue;
      RayHit h;
      h.hit_body = true;
      h.body = bodies_.idAt(i);
      h.distance = hit->t;
      h.point = origin + hit->t * d;
      h.normal = hit->normal;
      nearest = h;
    }
  }
  return nearest;
}

std::vector<ParticleId> World::overlapSphere(const Vec3& center, const Real radius) const {
  return particlesOverlappingSphere(particles_, center, radius);
}

std::vector<ParticleId> World::overlapBox(const Vec3& center, const Vec3& half_extents) const {
  return particlesOverlappingBox(particles_, center, half_extents);
}

void World::clear() {
  particles_.clear();
  generators_.clear();
  colliders_.clear();
  ++colliders_version_;
  links_.clear();
  bodies_.clear();
  joints_.clear();
  body_generators_.clear();
  body_ws_ = Owned<BodyWorkspace>();
  materials_.clear();
  ++generators_version_;
  last_contact_stats_ = ContactStats{};
  contacts_->resolver.clearWarmStart();
  time_origin_ = 0.0;
  steps_since_origin_ = 0;
  step_count_ = 0;
  accumulator_ = 0.0;
  has_external_force_ = false;
  *guard_ = GuardState{};
  paused_ = false;
  *integration_ = IntegratorState{};
  stateChanged();
}

// --- measurements ---

Real World::kineticEnergy() const {
  const auto v = particles_.velocities();
  const auto inverse_mass = particles_.inverseMasses();
  Real energy = 0.0;
  for (std::size_t i = 0; i < particles_.size(); ++i) {
    if (inverse_mass[i] > 0.0) energy += 0.5 * v.col(i).squaredNorm() / inverse_mass[i];
  }
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    if (!bodies_.dynamic(i)) continue;
    // (m v^2 + w_b.I w_b) / 2, w_b in the principal frame.
    const Vec3 w = bodies_.orientation(i).conjugate() * bodies_.angularVelocity(i);
    energy += 0.5 * (bodies_.mass(i) * bodies_.linearVelocity(i).squaredNorm() +
                     w.dot(bodies_.principalInertia(i).cwiseProduct(w)));
  }
  return energy;
}

Real World::gravitationalEnergy() const {
  const auto x = particles_.positions();
  const auto inverse_mass = particles_.inverseMasses();
  Real energy = 0.0;
  for (std::size_t i = 0; i < particles_.size(); ++i) {
    if (inverse_mass[i] > 0.0) energy -= config_.gravity.dot(x.col(i)) / inverse_mass[i];
  }
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    if (bodies_.dynamic(i)) energy -= bodies_.mass(i) * config_.gravity.dot(bodies_.position(i));
  }
  return energy;
}

Real World::springEnergy() const {
  const Real particles = caches_->forces.elasticEnergy(ForceScene{
      particles_, generators_, generators_version_, config_.gravity, has_external_force_});
  if (body_generators_.empty()) return particles;
  return particles + bodyGeneratorEnergy(body_generators_, bodies_, particles_);
}

Vec3 World::linearMomentum() const {
  const auto v = particles_.velocities();
  const auto inverse_mass = particles_.inverseMasses();
  Vec3 momentum = Vec3::Zero();
  for (std::size_t i = 0; i < particles_.size(); ++i) {
    if (inverse_mass[i] > 0.0) momentum += v.col(i) / inverse_mass[i];
  }
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    if (bodies_.dynamic(i)) momentum += bodies_.mass(i) * bodies_.linearVelocity(i);
  }
  return momentum;
}

Vec3 World::angularMomentum() const {
  const auto x = particles_.positions();
  const auto v = particles_.velocities();
  const auto inverse_mass = particles_.inverseMasses();
  Vec3 momentum = Vec3::Zero();
  for (std::size_t i = 0; i < particles_.size(); ++i) {
    if (inverse_mass[i] > 0.0) momentum += x.col(i).cross(Vec3(v.col(i))) / inverse_mass[i];
  }
  for (std::size_t i = 0; i < bodies_.size(); ++i) {
    if (!bodies_.dynamic(i)) continue;
    // x m v plus I w, I = R diag(I_p) R^T.
    const Quat& q = bodies_.orientation(i);
    const Vec3 spin =
        q * bodies_.principalInertia(i).cwiseProduct(q.conjugate() * bodies_.angularVelocity(i));
    momentum += bodies_.mass(i) * bodies_.position(i).cross(bodies_.linearVelocity(i)) + spin;
  }
  return momentum;
}

std::uint64_t World::stateHash() const {
  StateHasher hasher;
  hasher.add(static_cast<std::uint64_t>(particles_.size()));
  hasher.add(step_count_);
  hasher.add(time());
  const auto x = particles_.positions();
  const auto v = particles_.velocities();
  const auto previous = particles_.previousPositions();
  const auto previous_external = particles_.previousExternalAccelerations();
  const bool verlet = config_.integrator == Integrator::kPositionVerlet;
  for (std::size_t i = 0; i < particles_.size(); ++i) {
    hasher.add(particles_.idAt(i).packed());
    hasher.add(x.col(i));
    hasher.add(v.col(i));
    if (verlet) {
      hasher.add(previous.col(i));
      hasher.add(previous_external.col(i));
    }
  }
  // What the integrator and the contacts carry into the next substep is state too.
  const IntegratorState& integration = *integration_;
  if (config_.integrator == Integrator::kVelocityVerlet && integration.acceleration_valid) {
    const Vec3Array& a = integration.internal_acceleration;
    for (Eigen::Index i = 0; i < a.cols(); ++i) hasher.add(Vec3(a.col(i)));
  }
  contacts_->resolver.addToHash(hasher);
  // Bodies and joints, only where there are any (a particle world's hash is as it was).
  if (!bodies_.empty() || !joints_.empty()) {
    hasher.add(static_cast<std::uint64_t>(bodies_.size()));
    for (std::size_t i = 0; i < bodies_.size(); ++i) {
      hasher.add(bodies_.idAt(i).packed());
      hasher.add(bodies_.position(i));
      const Quat& q = bodies_.orientation(i);
      hasher.add(Vec3(q.x(), q.y(), q.z()));
      hasher.add(q.w());
      hasher.add(bodies_.linearVelocity(i));
      hasher.add(bodies_.angularVelocity(i));
      hasher.add(static_cast<std::uint64_t>(bodies_.awake(i)));
      hasher.add(bodies_.sleepTime(i));
    }
    for (const BodyContact& c : body_ws_->contacts) {
      hasher.add(static_cast<std::uint64_t>(c.key.other));
      hasher.add(static_cast<std::uint64_t>(c.key.shape));
      hasher.add(c.key.b);
      for (int k = 0; k < c.manifold.count; ++k) {
        hasher.add(static_cast<std::uint64_t>(c.manifold.points[k].id));
        hasher.add(c.normal_impulses[k]);
      }
      hasher.add(c.friction_impulse);
      hasher.add(c.twist_impulse);
      // The coupled masses a contact keeps inverted (their inverses follow from them) are
      // refreshed only when they change beyond rounding: state that steers the solve.
      const BodyContact::KeptMasses& masses = body_ws_->kept_masses.of(c);
      for (const BodyContact::InvertedMass* kept : {&masses.coupled, &masses.upper_alone}) {
        for (int i = 0; i < c.manifold.count; ++i) {
          for (int j = 0; j < c.manifold.count; ++j) hasher.add(kept->mass(i, j));
        }
      }
    }
    joints_.forEach([&](const auto& kind) {
      using Kind = typename std::decay_t<decltype(kind)>::value_type;
      for (const auto& joint : kind) JointKind<Kind>::addToHash(joint, hasher);
    });
    for (const KeptImpulses::Entry& link : body_ws_->link_impulses.entries()) {
      hasher.add(link.key);
      hasher.add(link.lower);
      hasher.add(link.upper);
    }
    for (const KeptImpulses::Entry& pair : body_ws_->pair_impulses.entries()) {
      hasher.add(pair.key);
      hasher.add(pair.lower);
      hasher.add(pair.friction);
    }
  }
  return hasher.value();
}

}  // namespace engine
}  // namespace mass_aggregate_sim
