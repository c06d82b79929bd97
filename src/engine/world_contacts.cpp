// World's colliders, links, contact settings, queries and the contact phase of each substep.
#include <algorithm>
#include <cmath>
#include <limits>

#include "mass_aggregate_sim/engine/contact_workspace.h"
#include "mass_aggregate_sim/engine/shape_geometry.h"
#include "mass_aggregate_sim/engine/world.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

bool finitePositive(const Real value) { return std::isfinite(value) && value > 0.0; }

Status checkMaterial(const Material& material) {
  if (!std::isfinite(material.restitution) || material.restitution < 0.0 ||
      material.restitution > 1.0) {
    return Status::error("restitution must be in [0, 1]");
  }
  if (!std::isfinite(material.friction) || material.friction < 0.0) {
    return Status::error("friction must be finite and >= 0");
  }
  return Status::ok();
}

std::uint64_t pairKey(std::uint32_t a, std::uint32_t b) {
  if (a > b) std::swap(a, b);
  return (std::uint64_t{a} << 32) | b;
}

template <typename Collider>
bool eraseCollider(std::vector<Collider>& kind, const ColliderId id) {
  const auto it =
      std::find_if(kind.begin(), kind.end(), [id](const Collider& c) { return c.id == id; });
  if (it == kind.end()) return false;
  kind.erase(it);
  return true;
}

// Appends contacts up to the limit (0: none) and counts the ones beyond it.
class ContactSink {
 public:
  ContactSink(std::vector<Contact>& contacts, const std::size_t limit, std::size_t& dropped)
      : contacts_(contacts), limit_(limit), dropped_(dropped) {}
  void push(const Contact& contact) {
    if (Contact* slot = add()) *slot = contact;
  }
  // A new contact to fill in place, or nullptr when it is dropped.
  Contact* add() {
    if (limit_ != 0 && contacts_.size() >= limit_) {
      ++dropped_;
      return nullptr;
    }
    return &contacts_.emplace_back();
  }

 private:
  std::vector<Contact>& contacts_;
  std::size_t limit_;
  std::size_t& dropped_;
};

void colliderContact(Contact* c, const std::uint32_t i, const std::uint32_t slot,
                     const ColliderId collider, const ShapeContact& shape,
                     const Material& material) {
  if (c == nullptr) return;
  c->a = i;
  c->key = colliderContactKey(slot, collider);
  c->normal = shape.normal;
  c->penetration = shape.penetration;
  c->restitution = material.restitution;
  c->friction = material.friction;
}

// Swept results exist only when sweepParticles() ran this substep.
bool sweptThisSubstep(const ContactWorkspace& ws, const CollisionSettings& settings,
                      const std::size_t n) {
  return settings.continuous && ws.time_of_impact.size() == n && ws.collider_hit.size() == n &&
         ws.pair_is_swept.size() == ws.pairs.size();
}

// Gaps narrower than this get a contact too (speculative: it only stops them closing faster than
// the gap within the substep), so a particle lifted off its support by a neighbour's correction
// does not fall freely for a substep and land with a jolt.
Real contactMargin(const CollisionSettings& settings) { return 2.0 * settings.penetration_slop; }

// beta of x' = x + v h + beta a h^2 for a constant acceleration a: how much of this substep's
// velocity change the integrator's position update already followed.
Real positionWeight(const Integrator integrator) {
  switch (integrator) {
    case Integrator::kExplicitEuler:
      return 0.0;
    case Integrator::kSemiImplicitEuler:
    case Integrator::kImplicitEuler:
      return 1.0;
    case Integrator::kPositionVerlet:
    case Integrator::kVelocityVerlet:
    case Integrator::kRk4:
      return 0.5;
  }
  return 0.0;
}

// Bottom-up order: heights along `up` quantised into buckets of half the smallest radius (at
// least (highest - lowest) / n), so one counting sort orders the contacts in O(contacts + n);
// contacts closer in height than that keep the broadphase's order. Bucket 0 holds the contacts
// without a second particle (colliders, anchored links), which carry a pile from below.
void heightBuckets(const ConstVec3Map& x, const ConstScalarMap& radius, const Vec3& up,
                   std::vector<std::uint32_t>& bucket, std::uint32_t& buckets) {
  const Eigen::Index n = x.cols();
  Real lowest = std::numeric_limits<Real>::infinity();
  Real highest = -lowest;
  Real smallest_radius = lowest;
  for (Eigen::Index i = 0; i < n; ++i) {
    const Real height = up.dot(x.col(i));
    lowest = std::min(lowest, height);
    highest = std::max(highest, height);
    smallest_radius = std::min(smallest_radius, radius[i]);
  }
  const Real range = highest - lowest;
  Real width =
      std::max(range / static_cast<Real>(std::max<Eigen::Index>(n, 1)), 0.5 * smallest_radius);
  if (!(std::isfinite(width) && width > 0.0)) width = 0.0;
  const Real inverse_width = width > 0.0 ? 1.0 / width : 0.0;
  const Real top = std::isfinite(range) ? range * inverse_width : 0.0;
  buckets = static_cast<std::uint32_t>(std::min<Real>(top, static_cast<Real>(n))) + 2;
  bucket.resize(static_cast<std::size_t>(n));
  for (Eigen::Index i = 0; i < n; ++i) {
    const Real t = (up.dot(x.col(i)) - lowest) * inverse_width;
    // Not finite or beyond the range: clamped (t >= 0 is false for NaN).
    const Real clamped = t >= 0.0 ? std::min(t, static_cast<Real>(buckets - 2)) : 0.0;
    bucket[i] = 1 + static_cast<std::uint32_t>(clamped);
  }
}

// The candidate pairs are found within this skin (a quarter of the smallest radius) beyond reach
// and kept while no particle has moved more than half of it: two spheres that were not candidates
// were more than the skin apart, so they cannot touch yet.
Real candidateSkin(const Eigen::Ref<const ScalarArray>& radius) {
  const Real smallest = radius.size() > 0 ? radius.minCoeff() : 0.0;
  return std::isfinite(smallest) && smallest > 0.0 ? 0.25 * smallest : 0.0;
}

// Whether the candidate pairs found in an earlier substep still hold (see ContactWorkspace).
bool candidatesStillValid(const ContactWorkspace& ws, const ParticleStore& particles,
                          const CollisionSettings& settings, const Vec3& gravity) {
  const auto x = particles.positions();
  const auto radius = particles.radii();
  if (!ws.candidates_valid || ws.candidate_layout != particles.layoutVersion() ||
      ws.candidate_positions.cols() != x.cols() || ws.candidate_broadphase != settings.broadphase ||
      ws.candidate_slop != settings.penetration_slop || ws.candidate_gravity != gravity ||
      !(ws.candidate_radii.matrix() == radius.matrix())) {
    return false;
  }
  // Moved at most half the skin since the pairs were found (NaN: not valid).
  const Real moved_squared = (x - ws.candidate_positions).colwise().squaredNorm().maxCoeff();
  return moved_squared <= 0.25 * ws.candidate_skin * ws.candidate_skin;
}

// Stable counting sort of `items` by `bucket` (one per item, below `buckets`) through `scratch`;
// nothing moves when they are already in order.
template <typename Item>
void sortByBucket(std::vector<Item>& items, const std::vector<std::uint32_t>& bucket,
                  const std::uint32_t buckets, std::vector<std::uint32_t>& start,
                  std::vector<Item>& scratch) {
  if (std::is_sorted(bucket.begin(), bucket.end())) return;
  start.assign(static_cast<std::size_t>(buckets) + 1, 0);
  for (const std::uint32_t b : bucket) ++start[b + 1];
  for (std::uint32_t b = 0; b < buckets; ++b) start[b + 1] += start[b];
  scratch.resize(items.size());
  for (std::size_t k = 0; k < items.size(); ++k) scratch[start[bucket[k]]++] = items[k];
  items.swap(scratch);
}

}  // namespace

// --- colliders ---

Result<ColliderId> World::nextColliderId() {
  if (next_collider_id_ == std::numeric_limits<ColliderId>::max()) {
    return Status::error("collider ids exhausted");
  }
  return next_collider_id_++;
}

Result<ColliderId> World::addPlane(const PlaneCollider& plane) {
  Status valid = checkMaterial(plane.material);
  if (valid && (!plane.normal.allFinite() || plane.normal.norm() < 1e-9)) {
    valid = Status::error("plane normal must be a finite non-zero vector");
  }
  if (valid && !std::isfinite(plane.offset)) valid = Status::error("plane offset is not finite");
  if (!valid) return valid;
  const Result<ColliderId> id = nextColliderId();
  if (!id) return id;
  PlaneCollider added = plane;
  // n.x < offset stays the same half-space after dividing both sides by |n|.
  const Real length = plane.normal.norm();
  added.normal /= length;
  added.offset /= length;
  added.id = *id;
  colliders_.planes.push_back(added);
  return id;
}

Result<ColliderId> World::addSphere(const SphereCollider& sphere) {
  Status valid = checkMaterial(sphere.material);
  if (valid && !sphere.center.allFinite()) valid = Status::error("sphere center is not finite");
  if (valid && !finitePositive(sphere.radius)) {
    valid = Status::error("sphere radius must be finite and > 0");
  }
  if (!valid) return valid;
  const Result<ColliderId> id = nextColliderId();
  if (!id) return id;
  SphereCollider added = sphere;
  added.id = *id;
  colliders_.spheres.push_back(added);
  return id;
}

Result<ColliderId> World::addBox(const BoxCollider& box) {
  Status valid = checkMaterial(box.material);
  if (valid && !box.center.allFinite()) valid = Status::error("box center is not finite");
  if (valid && !(box.half_extents.allFinite() && (box.half_extents.array() > 0.0).all())) {
    valid = Status::error("box half_extents must be finite and > 0");
  }
  if (valid && (!box.orientation.coeffs().allFinite() || box.orientation.norm() < 1e-9)) {
    valid = Status::error("box orientation must be a finite non-zero quaternion");
  }
  if (!valid) return valid;
  const Result<ColliderId> id = nextColliderId();
  if (!id) return id;
  BoxCollider added = box;
  added.orientation.normalize();
  added.id = *id;
  colliders_.boxes.push_back(added);
  return id;
}

Result<ColliderId> World::addCapsule(const CapsuleCollider& capsule) {
  Status valid = checkMaterial(capsule.material);
  if (valid && !(capsule.a.allFinite() && capsule.b.allFinite())) {
    valid = Status::error("capsule ends a and b must be finite");
  }
  if (valid && !finitePositive(capsule.radius)) {
    valid = Status::error("capsule radius must be finite and > 0");
  }
  if (!valid) return valid;
  const Result<ColliderId> id = nextColliderId();
  if (!id) return id;
  CapsuleCollider added = capsule;
  added.id = *id;
  colliders_.capsules.push_back(added);
  return id;
}

Status World::removeCollider(const ColliderId id) {
  const bool removed =
      eraseCollider(colliders_.planes, id) || eraseCollider(colliders_.spheres, id) ||
      eraseCollider(colliders_.boxes, id) || eraseCollider(colliders_.capsules, id);
  if (!removed) return Status::error("no collider with id " + std::to_string(id));
  return Status::ok();
}

// --- links ---

Result<GeneratorId> World::addCable(const Cable& cable) {
  Status valid = validateParticleRef(cable.a, "a");
  if (valid) valid = validateParticleRef(cable.b, "b");
  if (valid && cable.a == cable.b) valid = Status::error("a and b must be different particles");
  if (valid && !finitePositive(cable.max_length)) {
    valid = Status::error("max_length must be finite and > 0");
  }
  if (valid) valid = checkMaterial(Material{cable.restitution, 0.0});
  if (!valid) return valid;
  return addGenerator(links_.cables, cable);
}

Result<GeneratorId> World::addRod(const Rod& rod) {
  Status valid = validateParticleRef(rod.a, "a");
  if (valid) valid = validateParticleRef(rod.b, "b");
  if (valid && rod.a == rod.b) valid = Status::error("a and b must be different particles");
  if (valid && !finitePositive(rod.length)) valid = Status::error("length must be finite and > 0");
  if (!valid) return valid;
  return addGenerator(links_.rods, rod);
}

Result<GeneratorId> World::addAnchoredCable(const AnchoredCable& cable) {
  Status valid = validateParticleRef(cable.particle, "particle");
  if (valid && !cable.anchor.allFinite()) valid = Status::error("anchor is not finite");
  if (valid && !finitePositive(cable.max_length)) {
    valid = Status::error("max_length must be finite and > 0");
  }
  if (valid) valid = checkMaterial(Material{cable.restitution, 0.0});
  if (!valid) return valid;
  return addGenerator(links_.anchored_cables, cable);
}

Result<GeneratorId> World::addAnchoredRod(const AnchoredRod& rod) {
  Status valid = validateParticleRef(rod.particle, "particle");
  if (valid && !rod.anchor.allFinite()) valid = Status::error("anchor is not finite");
  if (valid && !finitePositive(rod.length)) valid = Status::error("length must be finite and > 0");
  if (!valid) return valid;
  return addGenerator(links_.anchored_rods, rod);
}

// --- settings and materials ---

Status World::setCollisionSettings(const CollisionSettings& settings) {
  const Status valid = validateCollisionSettings(settings);
  if (!valid) return valid;
  collision_settings_ = settings;
  return Status::ok();
}

Status World::setParticleMaterial(const ParticleId id, const Material& material) {
  Status valid = validateParticleRef(id, "particle");
  if (valid) valid = checkMaterial(material);
  if (!valid) return valid;
  if (slot_has_material_.size() <= id.index) {
    slot_has_material_.resize(id.index + 1, 0);
    slot_material_.resize(id.index + 1);
  }
  if (!slot_has_material_[id.index]) ++custom_material_count_;
  slot_has_material_[id.index] = 1;
  slot_material_[id.index] = material;
  return Status::ok();
}

Material World::particleMaterial(const std::size_t dense) const {
  const std::uint32_t slot = particles_.idAt(dense).index;
  if (slot < slot_has_material_.size() && slot_has_material_[slot]) return slot_material_[slot];
  return Material{collision_settings_.particle_restitution, collision_settings_.particle_friction};
}

// --- queries ---

std::optional<RayHit> World::raycast(const Vec3& origin, const Vec3& direction,
                                     const Real max_distance) const {
  return raycastScene(particles_, colliders_, origin, direction, max_distance);
}

std::vector<ParticleId> World::overlapSphere(const Vec3& center, const Real radius) const {
  return particlesOverlappingSphere(particles_, center, radius);
}

std::vector<ParticleId> World::overlapBox(const Vec3& center, const Vec3& half_extents) const {
  return particlesOverlappingBox(particles_, center, half_extents);
}

std::vector<LinkTension> World::linkTensions() const {
  std::vector<LinkTension> out;
  out.reserve(links_.size());
  const ContactResolver* resolver = contact_workspace_ ? &contact_workspace_->resolver : nullptr;
  const Real h = resolver ? resolver->lastSubstep() : 0.0;
  const auto add = [&](const GeneratorId id) {
    // F = J / h: the impulse the constraint applied over the substep, as a mean force.
    const Real tension = h > 0.0 ? resolver->lastImpulse(linkContactKey(id)) / h : 0.0;
    out.push_back(LinkTension{id, tension});
  };
  for (const Cable& l : links_.cables) add(l.id);
  for (const Rod& l : links_.rods) add(l.id);
  for (const AnchoredCable& l : links_.anchored_cables) add(l.id);
  for (const AnchoredRod& l : links_.anchored_rods) add(l.id);
  std::sort(out.begin(), out.end(),
            [](const LinkTension& x, const LinkTension& y) { return x.id < y.id; });
  return out;
}

// --- the contact phase ---

bool World::contactsActive() const {
  return !colliders_.empty() || !links_.empty() ||
         (collision_settings_.particle_collisions && particles_.size() > 1);
}

void World::buildLinkedPairs(ContactWorkspace& workspace) const {
  workspace.linked_pairs.clear();
  const auto dense = [this](const ParticleId id) {
    return static_cast<std::uint32_t>(particles_.denseIndexUnchecked(id));
  };
  for (const Cable& cable : links_.cables) {
    workspace.linked_pairs.push_back(pairKey(dense(cable.a), dense(cable.b)));
  }
  for (const Rod& rod : links_.rods) {
    workspace.linked_pairs.push_back(pairKey(dense(rod.a), dense(rod.b)));
  }
  std::sort(workspace.linked_pairs.begin(), workspace.linked_pairs.end());
}

// Swept tests for particles that moved more than their radius this substep: each is moved back
// to its earliest time of impact with a collider or another particle, where a contact is made.
void World::sweepParticles(ContactWorkspace& ws) {
  auto x = particles_.positions();
  const auto radius = particles_.radii();
  const auto inverse_mass = particles_.inverseMasses();
  const std::size_t n = particles_.size();
  const Vec3Array& start = ws.substep_start;
  ws.time_of_impact.assign(n, 1.0);
  ws.collider_hit.assign(n, -1);
  ws.collider_hits.clear();

  for (std::size_t i = 0; i < n; ++i) {
    if (inverse_mass[i] <= 0.0) continue;
    const Vec3 from = start.col(i);
    const Vec3 motion = Vec3(x.col(i)) - from;
    const Real distance = motion.norm();
    // A move shorter than the radius keeps the sphere overlapping whatever the centre crossed.
    if (!(distance > radius[i])) continue;
    const Vec3 direction = motion / distance;
    const Real r = radius[i];
    std::optional<RayShapeHit> best;
    ContactWorkspace::ColliderHit hit{};
    const auto offer = [&](const std::optional<RayShapeHit>& candidate, const ColliderId id,
                           const Material& material) {
      if (candidate && (!best || candidate->t < best->t)) {
        best = candidate;
        hit = {id, candidate->t / distance, candidate->normal, material.restitution,
               material.friction};
      }
    };
    for (const PlaneCollider& c : colliders_.planes) {
      offer(rayVsPlane(from, direction, distance, c, r), c.id, c.material);
    }
    for (const SphereCollider& c : colliders_.spheres) {
      offer(rayVsSphere(from, direction, distance, c.center, c.radius + r), c.id, c.material);
    }
    for (const BoxCollider& c : colliders_.boxes) {
      offer(rayVsBox(from, direction, distance, c, r), c.id, c.material);
    }
    for (const CapsuleCollider& c : colliders_.capsules) {
      offer(rayVsCapsule(from, direction, distance, c, r), c.id, c.material);
    }
    if (best) {
      ws.time_of_impact[i] = hit.time;
      ws.collider_hit[i] = static_cast<std::int32_t>(ws.collider_hits.size());
      ws.collider_hits.push_back(hit);
    }
  }

  ws.pair_is_swept.assign(ws.pairs.size(), 0);
  for (std::size_t k = 0; k < ws.pairs.size(); ++k) {
    const auto [a, b] = ws.pairs[k];
    const Vec3 motion_a = Vec3(x.col(a)) - start.col(a);
    const Vec3 motion_b = Vec3(x.col(b)) - start.col(b);
    if (!(motion_a.norm() > radius[a] || motion_b.norm() > radius[b])) continue;
    const auto s = sweptSpheresTimeOfImpact(Vec3(start.col(a) - start.col(b)), motion_a - motion_b,
                                            radius[a] + radius[b]);
    if (!s) continue;
    ws.pair_is_swept[k] = 1;
    ws.time_of_impact[a] = std::min(ws.time_of_impact[a], *s);
    ws.time_of_impact[b] = std::min(ws.time_of_impact[b], *s);
  }

  std::size_t moved = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const Real s = ws.time_of_impact[i];
    if (s >= 1.0) continue;
    // x(s) = x0 + s (x1 - x0)
    x.col(i) = start.col(i) + s * (Vec3(x.col(i)) - start.col(i));
    ++moved;
  }
  last_contact_stats_.ccd_hits = moved;
}

bool World::generateColliderContacts(ContactWorkspace& ws, const std::size_t begin,
                                     const std::size_t end, std::size_t& dropped) {
  const auto x = particles_.positions();
  const auto radius = particles_.radii();
  const auto inverse_mass = particles_.inverseMasses();
  const std::size_t n = particles_.size();
  const CollisionSettings& settings = collision_settings_;
  const bool swept = sweptThisSubstep(ws, settings, n);
  const Real margin = contactMargin(settings);
  ContactSink sink(ws.contacts, settings.max_contacts, dropped);
  bool in_two = false;
  for (std::size_t i = begin; i < end; ++i) {
    if (inverse_mass[i] <= 0.0) continue;
    const std::size_t contacts_before = ws.contacts.size();
    const Vec3 xi = x.col(i);
    const Real r = radius[i];
    const auto index = static_cast<std::uint32_t>(i);
    // The collider a swept test stopped this particle at gets a contact even when just touching.
    const ContactWorkspace::ColliderHit* hit = nullptr;
    if (swept && ws.collider_hit[i] >= 0 &&
        ws.time_of_impact[i] == ws.collider_hits[ws.collider_hit[i]].time) {
      hit = &ws.collider_hits[ws.collider_hit[i]];
    }
    const auto add = [&](const std::optional<ShapeContact>& shape, const ColliderId id,
                         const Material& material) {
      if (hit && hit->collider == id) {
        // Stopped at its time of impact: touching, whatever rounding says.
        const ShapeContact touching{shape ? shape->normal : hit->normal,
                                    shape ? std::max(shape->penetration, Real{0.0}) : 0.0};
        colliderContact(sink.add(), index, ws.slots[i], id, touching, material);
      } else if (shape) {
        colliderContact(sink.add(), index, ws.slots[i], id, *shape, material);
      }
    };
    for (const PlaneCollider& c : colliders_.planes) {
      // sphereVsPlane() inline: most spheres are far from most planes.
      const Real penetration = r - (c.normal.dot(xi) - c.offset);
      if (penetration > -margin) {
        add(ShapeContact{c.normal, penetration}, c.id, c.material);
      } else if (hit) {
        add(std::nullopt, c.id, c.material);
      }
    }
    for (const SphereCollider& c : colliders_.spheres) {
      add(sphereVsSphere(xi, r, c.center, c.radius, margin), c.id, c.material);
    }
    for (const BoxCollider& c : colliders_.boxes)
      add(sphereVsBox(xi, r, c, margin), c.id, c.material);
    for (const CapsuleCollider& c : colliders_.capsules) {
      add(sphereVsCapsule(xi, r, c, margin), c.id, c.material);
    }
    if (ws.contacts.size() - contacts_before > 1) in_two = true;
  }
  return in_two;
}

void World::generateContacts(ContactWorkspace& ws, std::size_t& dropped) {
  const auto x = particles_.positions();
  const auto radius = particles_.radii();
  const auto inverse_mass = particles_.inverseMasses();
  const std::size_t n = particles_.size();
  const CollisionSettings& settings = collision_settings_;
  const bool swept = sweptThisSubstep(ws, settings, n);
  const Real margin = contactMargin(settings);
  ContactSink sink(ws.contacts, settings.max_contacts, dropped);

  // Colliders first: a pile is held up from the ground, so its contacts come first in each pass.
  ws.particle_in_two_collider_contacts =
      !colliders_.empty() && generateColliderContacts(ws, 0, n, dropped);

  if (settings.particle_collisions) {
    const bool filter = !settings.collide_linked && !ws.linked_pairs.empty();
    const bool custom_materials = custom_material_count_ > 0;
    // The contacts of a large pile (beyond the caches) are written faster than the hardware
    // prefetch fetches their lines: ask for them a few contacts ahead (the vector keeps its
    // capacity from substep to substep).
    const bool prefetch = ws.pairs.size() * sizeof(Contact) > (std::size_t{8} << 20);
    for (std::size_t k = 0; k < ws.pairs.size(); ++k) {
      if (prefetch && ws.contacts.size() + 32 < ws.contacts.capacity()) {
        __builtin_prefetch(ws.contacts.data() + ws.contacts.size() + 32, 1);
      }
      const auto [a, b] = ws.pairs[k];
      if (inverse_mass[a] <= 0.0 && inverse_mass[b] <= 0.0) continue;
      if (filter &&
          std::binary_search(ws.linked_pairs.begin(), ws.linked_pairs.end(), pairKey(a, b))) {
        continue;
      }
      const Vec3 d = Vec3(x.col(a)) - x.col(b);
      const Real distance = d.norm();
      const Real reach = radius[a] + radius[b];
      Real penetration = reach - distance;
      if (!(penetration > -margin)) {
        // A swept pair stopped at its time of impact touches; one stopped earlier by something
        // else is left to the next substep.
        const bool touching = swept && ws.pair_is_swept[k] && penetration > -1e-9 * reach;
        if (!touching) continue;
        penetration = std::max(penetration, Real{0.0});
      }
      Contact* c = sink.add();
      if (c == nullptr) continue;
      c->a = a;
      c->b = b;
      // Written in place (a Vec3 chosen by ?: went through a stack slot).
      if (distance > 1e-12) {
        c->normal = d * (1.0 / distance);
      } else {
        c->normal = Vec3::UnitZ();
      }
      c->penetration = penetration;
      c->key = pairContactKey(ws.slots[a], ws.slots[b]);
      if (custom_materials) {
        const Material ma = particleMaterial(a);
        const Material mb = particleMaterial(b);
        c->restitution = 0.5 * (ma.restitution + mb.restitution);
        c->friction = std::sqrt(ma.friction * mb.friction);
      } else {
        c->restitution = settings.particle_restitution;
        c->friction = settings.particle_friction;
      }
    }
  }

  const auto dense = [this](const ParticleId id) {
    return static_cast<std::uint32_t>(particles_.denseIndexUnchecked(id));
  };
  const auto link = [&](const ContactKind kind, const GeneratorId id, const std::uint32_t a,
                        const std::uint32_t b, const Vec3& anchor, const Real length,
                        const Real restitution) {
    // Every link is listed: a rod holds either way, and a slack cable is checked again after
    // the position passes, which may stretch it.
    Contact c;
    c.a = a;
    c.b = b;
    c.kind = kind;
    c.link = static_cast<std::uint32_t>(ws.links.size());
    ws.links.push_back(LinkGeometry{anchor, length});
    c.restitution = restitution;
    c.key = linkContactKey(id);
    sink.push(c);
  };
  for (const Cable& l : links_.cables) {
    link(ContactKind::kCable, l.id, dense(l.a), dense(l.b), Vec3::Zero(), l.max_length,
         l.restitution);
  }
  for (const Rod& l : links_.rods) {
    link(ContactKind::kRod, l.id, dense(l.a), dense(l.b), Vec3::Zero(), l.length, 0.0);
  }
  for (const AnchoredCable& l : links_.anchored_cables) {
    link(ContactKind::kCable, l.id, dense(l.particle), kNoParticle, l.anchor, l.max_length,
         l.restitution);
  }
  for (const AnchoredRod& l : links_.anchored_rods) {
    link(ContactKind::kRod, l.id, dense(l.particle), kNoParticle, l.anchor, l.length, 0.0);
  }
}

// Only collider contacts: each particle's are made together, so they are made and solved in parts
// of particles while they are still in the cache (the same results as all at once: see
// ContactResolver::beginParts). Where no particle of a part meets two colliders, every contact of
// the part is isolated without counting.
void World::resolveColliderContactsInParts(ContactWorkspace& ws, const Real h) {
  constexpr std::size_t kPartParticles = 256;
  const std::size_t n = particles_.size();
  const CollisionSettings& settings = collision_settings_;
  // Frictionless planes only and no swept tests: groups of four particles that each meet at most
  // one plane go through solvePlaneGroups(), with no Contact written.
  bool plane_groups = !sweptThisSubstep(ws, settings, n) && colliders_.spheres.empty() &&
                      colliders_.boxes.empty() && colliders_.capsules.empty();
  ws.batch_planes.clear();
  for (const PlaneCollider& c : colliders_.planes) {
    plane_groups = plane_groups && !(c.material.friction > 0.0);
    ws.batch_planes.push_back(BatchPlane{
        {c.normal.x(), c.normal.y(), c.normal.z()}, c.offset, c.material.restitution, c.id});
  }
  ws.resolver.beginParts(static_cast<Eigen::Index>(n), h, positionWeight(config_.integrator));
  for (std::size_t begin = 0; begin < n && !colliders_.empty(); begin += kPartParticles) {
    const std::size_t end = std::min(n, begin + kPartParticles);
    std::size_t i = begin;
    while (i < end) {
      if (plane_groups) {
        i = ws.resolver.addPlaneGroups(
            ws.batch_planes.data(), ws.batch_planes.size(), i, end, ws.slots.data(),
            ConstScalarMap(particles_.radii().data(), n), particles_.positions(),
            particles_.velocities(), particles_.inverseMasses(), acceleration_, h,
            settings.penetration_slop, contactMargin(settings));
        if (i >= end) break;
      }
      // The group the lanes stopped at (or the whole part): made and solved the general way.
      const std::size_t stop = plane_groups ? std::min(end, i + 4) : end;
      ws.contacts.clear();
      const bool in_two = generateColliderContacts(ws, i, stop, dropped_this_step_);
      ws.resolver.addPart(ws.contacts, particles_.positions(), particles_.velocities(),
                          particles_.inverseMasses(), acceleration_, h, settings.penetration_slop,
                          in_two ? IsolatedContacts::kFind : IsolatedContacts::kAll);
      i = stop;
    }
  }
  ws.resolver.finishParts(particles_.positions(), particles_.velocities(),
                          particles_.inverseMasses(), acceleration_, h, settings,
                          last_contact_stats_);
  last_contact_stats_.contacts = ws.resolver.partsContactCount();
}

void World::resolveContacts(const Real h) {
  if (!contact_workspace_) contact_workspace_ = std::make_unique<ContactWorkspace>();
  ContactWorkspace& ws = *contact_workspace_;
  const CollisionSettings& settings = collision_settings_;
  const std::size_t n = particles_.size();
  const auto x = particles_.positions();
  const auto radius = particles_.radii();
  const bool swept = settings.continuous && static_cast<std::size_t>(ws.substep_start.cols()) == n;
  last_contact_stats_ = ContactStats{};

  const bool bottom_up = config_.gravity.squaredNorm() > 0.0;
  std::uint32_t buckets = 0;
  const auto find_buckets = [&] {
    if (buckets != 0 || !bottom_up) return;
    heightBuckets(ConstVec3Map(x.data(), 3, x.cols()), ConstScalarMap(radius.data(), radius.size()),
                  -config_.gravity.normalized(), ws.particle_bucket, buckets);
  };
  if (!(settings.particle_collisions && n > 1)) {
    ws.pairs.clear();
    ws.candidates_valid = false;
  } else if (swept || !candidatesStillValid(ws, particles_, settings, config_.gravity)) {
    // Boxes around each sphere, grown by the skin; with swept tests, around its whole path over
    // the substep (then without skin: the list is made again every substep).
    const Real skin = swept ? 0.0 : candidateSkin(radius);
    ws.box_lo.resize(3, static_cast<Eigen::Index>(n));
    ws.box_hi.resize(3, static_cast<Eigen::Index>(n));
    for (std::size_t i = 0; i < n; ++i) {
      const Vec3 r = Vec3::Constant(radius[i] + 0.5 * contactMargin(settings) + 0.5 * skin);
      Vec3 lo = x.col(i);
      Vec3 hi = lo;
      if (swept) {
        lo = lo.cwiseMin(ws.substep_start.col(i));
        hi = hi.cwiseMax(ws.substep_start.col(i));
      }
      ws.box_lo.col(i) = lo - r;
      ws.box_hi.col(i) = hi + r;
    }
    ws.broadphase.findPairs(settings.broadphase, ws.box_lo, ws.box_hi, ws.pairs);
    if (!swept) {
      // Only pairs within reach + margin + skin can touch before the list is made again (each
      // sphere moves at most half the skin): the boxes' corners are left out here, once.
      const Real extra = contactMargin(settings) + skin;
      const auto kept = std::remove_if(ws.pairs.begin(), ws.pairs.end(), [&](const IndexPair& p) {
        const Real bound = radius[p.a] + radius[p.b] + extra;
        // Kept unless clearly beyond (the slack covers rounding in the squares).
        return !((x.col(p.a) - x.col(p.b)).squaredNorm() <= bound * bound * (1.0 + 1e-9));
      });
      ws.pairs.erase(kept, ws.pairs.end());
    }
    if (ws.pairs.size() > 1) {
      // Pairs in the order (height bucket, a, b), by three stable counting sorts from the last
      // key: bottom up for the resolver, in memory order within a layer, and the same whichever
      // broadphase found them.
      const auto sort_by = [&](const auto key, const std::uint32_t key_count) {
        ws.item_bucket.resize(ws.pairs.size());
        for (std::size_t k = 0; k < ws.pairs.size(); ++k) ws.item_bucket[k] = key(ws.pairs[k]);
        sortByBucket(ws.pairs, ws.item_bucket, key_count, ws.bucket_start, ws.sorted_pairs);
      };
      const auto particle_count = static_cast<std::uint32_t>(n);
      sort_by([](const IndexPair& p) { return p.b; }, particle_count);
      sort_by([](const IndexPair& p) { return p.a; }, particle_count);
      if (bottom_up) {
        find_buckets();
        sort_by(
            [&](const IndexPair& p) {
              return std::min(ws.particle_bucket[p.a], ws.particle_bucket[p.b]);
            },
            buckets);
      }
    }
    ws.candidates_valid = !swept;
    if (ws.candidates_valid) {
      ws.candidate_skin = skin;
      ws.candidate_positions = x;
      ws.candidate_radii = radius;
      ws.candidate_layout = particles_.layoutVersion();
      ws.candidate_broadphase = settings.broadphase;
      ws.candidate_slop = settings.penetration_slop;
      ws.candidate_gravity = config_.gravity;
    }
  }
  if (settings.particle_collisions && n > 1 && !settings.collide_linked) buildLinkedPairs(ws);
  if (swept) {
    sweepParticles(ws);
  } else {
    ws.time_of_impact.clear();
    ws.collider_hit.clear();
    ws.pair_is_swept.clear();
  }

  if (ws.slots_layout != particles_.layoutVersion() || ws.slots.size() != n) {
    // Each particle's slot, for the contact keys; it changes only with the layout.
    ws.slots.resize(n);
    for (std::size_t i = 0; i < n; ++i) ws.slots[i] = particles_.idAt(i).index;
    ws.slots_layout = particles_.layoutVersion();
  }
  ws.contacts.clear();
  ws.links.clear();
  const bool only_collider_contacts =
      links_.empty() && (!settings.particle_collisions || ws.pairs.empty());
  if (only_collider_contacts && settings.max_contacts == 0) {
    resolveColliderContactsInParts(ws, h);
  } else {
    generateContacts(ws, dropped_this_step_);
    if (bottom_up && ws.contacts.size() > 1) {
      // Bottom up along gravity (colliders first): a forward pass carries the support from the
      // ground to the top of a pile. Without links the contacts already are in that order: the
      // collider ones (bucket 0), then those of the pairs, sorted when the list was made. Links
      // (listed last) are sorted in with the others by the buckets of now.
      if (!links_.empty()) {
        find_buckets();
        ws.item_bucket.resize(ws.contacts.size());
        for (std::size_t k = 0; k < ws.contacts.size(); ++k) {
          const Contact& c = ws.contacts[k];
          ws.item_bucket[k] =
              c.b == kNoParticle ? 0 : std::min(ws.particle_bucket[c.a], ws.particle_bucket[c.b]);
        }
        sortByBucket(ws.contacts, ws.item_bucket, buckets, ws.bucket_start, ws.sorted_contacts);
      }
    }
    // Isolated contacts are looked for when all contacts are with colliders (most are then
    // isolated: a particle meets two colliders only in a corner); with particle pairs or links
    // few are, and the count would cost more than it saves.
    IsolatedContacts isolated = IsolatedContacts::kNone;
    if (only_collider_contacts) {
      isolated =
          ws.particle_in_two_collider_contacts ? IsolatedContacts::kFind : IsolatedContacts::kAll;
    }
    ws.resolver.resolve(ws.contacts, ws.links, particles_.positions(), particles_.velocities(),
                        particles_.inverseMasses(), acceleration_, h, settings,
                        positionWeight(config_.integrator), last_contact_stats_, isolated);
    last_contact_stats_.contacts = ws.contacts.size();
  }
  last_contact_stats_.dropped = dropped_this_step_;

  const auto& touched = ws.resolver.touched();
  if (touched.empty() && last_contact_stats_.ccd_hits == 0) return;
  // The integrators' caches must follow what the resolver changed.
  acceleration_valid_ = false;
  if (config_.integrator == Integrator::kPositionVerlet && verlet_history_h_ == h) {
    auto previous = particles_.previousPositions();
    const auto v = particles_.velocities();
    const auto xs = particles_.positions();
    // x_prev = x - v h + a h^2 / 2, as when the history is first seeded.
    const auto reseed = [&](const std::size_t i) {
      previous.col(i) = xs.col(i) - v.col(i) * h + 0.5 * h * h * acceleration_.col(i);
    };
    for (const std::uint32_t i : touched) reseed(i);
    if (swept) {
      for (std::size_t i = 0; i < n; ++i) {
        if (ws.time_of_impact[i] < 1.0) reseed(i);
      }
    }
  }
}

}  // namespace engine
}  // namespace mass_aggregate_sim
