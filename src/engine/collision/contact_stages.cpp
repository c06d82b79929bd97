#include "engine/collision/contact_stages.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "engine/collision/geometry.h"
#include "engine/solver/contact_workspace.h"
#include "engine/solver/isolated_contact_batch.h"
#include "engine/world/step_context.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

std::uint64_t pairKey(std::uint32_t a, std::uint32_t b) {
  if (a > b) std::swap(a, b);
  return (std::uint64_t{a} << 32) | b;
}

// Appends contacts up to the limit (0: none) and counts the ones beyond it. Position-only
// contacts (Contact::position_only) are not contacts to the limit or the statistics: they are
// always kept, and counted apart.
class ContactSink {
 public:
  ContactSink(std::vector<Contact>& contacts, const std::size_t limit, std::size_t& dropped,
              std::size_t& position_only)
      : contacts_(contacts), limit_(limit), dropped_(dropped), position_only_(position_only) {}
  void push(const Contact& contact) {
    if (Contact* slot = add()) *slot = contact;
  }
  // A new contact to fill in place, or nullptr when it is dropped.
  Contact* add() {
    if (limit_ != 0 && contacts_.size() - position_only_ >= limit_) {
      ++dropped_;
      return nullptr;
    }
    return &contacts_.emplace_back();
  }
  Contact* addPositionOnly() {
    ++position_only_;
    Contact* c = &contacts_.emplace_back();
    c->position_only = true;
    return c;
  }

 private:
  std::vector<Contact>& contacts_;
  std::size_t limit_;
  std::size_t& dropped_;
  std::size_t& position_only_;
};

// Particle i against a surface that does not move in the solver: a collider's, or a body's.
void surfaceContact(Contact* c, const std::uint32_t i, const std::uint64_t key,
                    const ShapeContact& shape, const Material& material) {
  if (c == nullptr) return;
  c->a = i;
  c->key = key;
  c->normal = shape.normal;
  c->penetration = shape.penetration;
  c->restitution = material.restitution;
  c->friction = material.friction;
}

// Colliders whose gap to a particle is wider than the margin but narrower than this (one radius
// of the particle) get a position-only contact when other constraints can move the particle
// within the substep (particle pairs, links): their position corrections and the moves resting
// contacts make with their impulses reach centimetres in a pile that takes a fast impact, and a
// particle moved into a collider it has no contact with stays there, its centre behind a wall or
// under the floor at the end of the step.
Real positionOnlyReach(const Real radius) { return radius; }

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

void buildLinkedPairs(StepContext& ctx) {
  ContactWorkspace& ws = ctx.contacts;
  ws.linked_pairs.clear();
  ctx.links.forEach([&](const auto& kind) {
    for (const auto& link : kind) {
      if (link.anchored()) continue;
      ws.linked_pairs.push_back(
          pairKey(static_cast<std::uint32_t>(ctx.particles.denseIndexUnchecked(link.a)),
                  static_cast<std::uint32_t>(ctx.particles.denseIndexUnchecked(link.b))));
    }
  });
  std::sort(ws.linked_pairs.begin(), ws.linked_pairs.end());
}

// Swept tests for particles that moved more than their radius this substep: each is moved back
// to its earliest time of impact with a collider or another particle, where a contact is made.
void sweepParticles(StepContext& ctx) {
  ContactWorkspace& ws = ctx.contacts;
  ParticleStore& particles = ctx.particles;
  auto x = particles.positions();
  const auto radius = particles.radii();
  const auto inverse_mass = particles.inverseMasses();
  const std::size_t n = particles.size();
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
    ctx.colliders.forEach([&](const auto& shapes) {
      using Shape = typename std::decay_t<decltype(shapes)>::value_type;
      for (const Shape& shape : shapes) {
        const auto candidate = ShapeKind<Shape>::raycast(shape, from, direction, distance, r);
        if (candidate && (!best || candidate->t < best->t)) {
          best = candidate;
          hit = {shape.id, candidate->t / distance, candidate->normal, shape.material.restitution,
                 shape.material.friction};
        }
      }
    });
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
  ctx.contact_stats.ccd_hits = moved;
}

Material particleMaterial(const StepContext& ctx, const std::size_t dense) {
  return ctx.materials.of(ctx.contacts.slots[dense], Material{ctx.collisions.particle_restitution,
                                                              ctx.collisions.particle_friction});
}

}  // namespace

bool onlyColliderContacts(const StepContext& ctx) {
  return ctx.links.empty() && (!ctx.collisions.particle_collisions || ctx.contacts.pairs.empty());
}

void findPairs(StepContext& ctx) {
  ctx.contact_stats = ContactStats{};
  if (!ctx.contacts_active) return;
  ContactWorkspace& ws = ctx.contacts;
  const CollisionSettings& settings = ctx.collisions;
  const ParticleStore& particles = ctx.particles;
  const std::size_t n = particles.size();
  const auto x = particles.positions();
  const auto radius = particles.radii();
  const bool swept = settings.continuous && static_cast<std::size_t>(ws.substep_start.cols()) == n;
  ws.buckets = 0;
  const Vec3& gravity = ctx.config.gravity;
  if (!(settings.particle_collisions && n > 1)) {
    ws.pairs.clear();
    ws.candidates_valid = false;
  } else if (swept || !candidatesStillValid(ws, particles, settings, gravity)) {
    // Boxes around each sphere, grown by the skin; with swept tests, around its whole path over
    // the substep (then without skin: the list is made again every substep).
    const Real skin = swept ? 0.0 : candidateSkin(radius);
    ws.box_lo.resize(3, static_cast<Eigen::Index>(n));
    ws.box_hi.resize(3, static_cast<Eigen::Index>(n));
    for (std::size_t i = 0; i < n; ++i) {
      const Vec3 r =
          Vec3::Constant(radius[i] + 0.5 * contactMargin(settings.penetration_slop) + 0.5 * skin);
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
      const Real extra = contactMargin(settings.penetration_slop) + skin;
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
      if (gravity.squaredNorm() > 0.0) {
        heightBuckets(x, radius, -gravity.normalized(), ws.particle_bucket, ws.buckets);
        sort_by(
            [&](const IndexPair& p) {
              return std::min(ws.particle_bucket[p.a], ws.particle_bucket[p.b]);
            },
            ws.buckets);
      }
    }
    ws.candidates_valid = !swept;
    if (ws.candidates_valid) {
      ws.candidate_skin = skin;
      ws.candidate_positions = x;
      ws.candidate_radii = radius;
      ws.candidate_layout = particles.layoutVersion();
      ws.candidate_broadphase = settings.broadphase;
      ws.candidate_slop = settings.penetration_slop;
      ws.candidate_gravity = gravity;
    }
  }
  if (settings.particle_collisions && n > 1 && !settings.collide_linked) buildLinkedPairs(ctx);
  if (swept) {
    sweepParticles(ctx);
  } else {
    ws.time_of_impact.clear();
    ws.collider_hit.clear();
    ws.pair_is_swept.clear();
  }
  if (ws.slots_layout != particles.layoutVersion() || ws.slots.size() != n) {
    // Each particle's slot, for the contact keys; it changes only with the layout.
    ws.slots.resize(n);
    for (std::size_t i = 0; i < n; ++i) ws.slots[i] = particles.idAt(i).index;
    ws.slots_layout = particles.layoutVersion();
  }
  ws.contacts.clear();
  ws.position_only_contacts = 0;
  ws.links.clear();
}

bool generateColliderContacts(StepContext& ctx, const std::size_t begin, const std::size_t end) {
  ContactWorkspace& ws = ctx.contacts;
  const ParticleStore& particles = ctx.particles;
  const auto x = particles.positions();
  const auto radius = particles.radii();
  const auto inverse_mass = particles.inverseMasses();
  const CollisionSettings& settings = ctx.collisions;
  const bool swept = ws.sweptThisSubstep(settings.continuous, particles.size());
  const Real margin = contactMargin(settings.penetration_slop);
  ContactSink sink(ws.contacts, settings.max_contacts, ctx.dropped, ws.position_only_contacts);
  bool in_two = false;
  for (std::size_t i = begin; i < end; ++i) {
    if (inverse_mass[i] <= 0.0) continue;
    int made = 0;  // contacts of this particle, not position-only
    const Vec3 xi = x.col(i);
    const Real r = radius[i];
    // How far the shapes are looked for: the margin, or the reach of position-only contacts.
    const Real reach = ws.collider_position_only ? std::max(margin, positionOnlyReach(r)) : margin;
    const auto index = static_cast<std::uint32_t>(i);
    // The collider a swept test stopped this particle at gets a contact even when just touching.
    const ContactWorkspace::ColliderHit* hit = nullptr;
    if (swept && ws.collider_hit[i] >= 0 &&
        ws.time_of_impact[i] == ws.collider_hits[ws.collider_hit[i]].time) {
      hit = &ws.collider_hits[ws.collider_hit[i]];
    }
    ctx.colliders.forEach([&](const auto& shapes) {
      using Shape = typename std::decay_t<decltype(shapes)>::value_type;
      for (const Shape& shape : shapes) {
        const std::optional<ShapeContact> contact = ShapeKind<Shape>::contact(shape, xi, r, reach);
        const std::uint64_t key = colliderContactKey(ws.slots[i], shape.id);
        if (hit && hit->collider == shape.id) {
          // Stopped at its time of impact: touching, whatever rounding says.
          const ShapeContact touching{contact ? contact->normal : hit->normal,
                                      contact ? std::max(contact->penetration, Real{0.0}) : 0.0};
          surfaceContact(sink.add(), index, key, touching, shape.material);
          ++made;
        } else if (contact && contact->penetration > -margin) {
          surfaceContact(sink.add(), index, key, *contact, shape.material);
          ++made;
        } else if (contact) {
          surfaceContact(sink.addPositionOnly(), index, key, *contact, shape.material);
        }
      }
    });
    if (made > 1) in_two = true;
  }
  return in_two;
}

void addBodySurfaceContacts(StepContext& ctx) {
  ContactWorkspace& ws = ctx.contacts;
  const auto x = ctx.particles.positions();
  const auto radius = ctx.particles.radii();
  const Real margin = contactMargin(ctx.collisions.penetration_slop);
  ContactSink sink(ws.contacts, ctx.collisions.max_contacts, ctx.dropped,
                   ws.position_only_contacts);
  for (const ContactWorkspace::BodySurface& surface : ws.body_surfaces) {
    const Real penetration = surface.offset - surface.normal.dot(x.col(surface.particle));
    if (!(penetration > -positionOnlyReach(radius[surface.particle]))) continue;
    const std::uint32_t slot = ws.slots[surface.particle];
    surfaceContact(penetration > -margin && !surface.moves ? sink.add() : sink.addPositionOnly(),
                   surface.particle,
                   surface.moves ? movingSurfaceContactKey(slot, surface.shape)
                                 : stillSurfaceContactKey(slot, surface.shape),
                   ShapeContact{surface.normal, penetration}, surface.material);
  }
}

int otherColliderContacts(const void* const context, const std::size_t i, GroupContact& contact) {
  const StepContext& ctx = *static_cast<const StepContext*>(context);
  const ContactWorkspace& ws = ctx.contacts;
  const ParticleStore& particles = ctx.particles;
  if (ws.sweptThisSubstep(ctx.collisions.continuous, particles.size()) && ws.collider_hit[i] >= 0 &&
      ws.time_of_impact[i] == ws.collider_hits[ws.collider_hit[i]].time) {
    return 2;
  }
  const Vec3 xi = particles.positions().col(i);
  const Real r = particles.radii()[i];
  const Real margin = contactMargin(ctx.collisions.penetration_slop);
  int count = 0;
  ctx.colliders.forEach([&](const auto& shapes) {
    using Shape = typename std::decay_t<decltype(shapes)>::value_type;
    if constexpr (!std::is_same_v<Shape, PlaneCollider>) {
      for (const Shape& shape : shapes) {
        if (count > 1) return;
        const std::optional<ShapeContact> found = ShapeKind<Shape>::contact(shape, xi, r, margin);
        if (!found) continue;
        if (count++ == 0) {
          contact =
              GroupContact{*found, shape.material.restitution, shape.material.friction, shape.id};
        }
      }
    }
  });
  return count;
}

void generateContacts(StepContext& ctx) {
  if (!ctx.contacts_active) return;
  ContactWorkspace& ws = ctx.contacts;
  const CollisionSettings& settings = ctx.collisions;
  // Collider-only scenes: made part by part as the solver takes them (solveConstraints).
  if (onlyColliderContacts(ctx) && settings.max_contacts == 0) return;
  const ParticleStore& particles = ctx.particles;
  const auto x = particles.positions();
  const auto radius = particles.radii();
  const auto inverse_mass = particles.inverseMasses();
  const std::size_t n = particles.size();
  const bool swept = ws.sweptThisSubstep(settings.continuous, n);
  const Real margin = contactMargin(settings.penetration_slop);
  ContactSink sink(ws.contacts, settings.max_contacts, ctx.dropped, ws.position_only_contacts);

  // Colliders first: a pile is held up from the ground, so its contacts come first in each pass.
  // Position-only collider contacts when pairs or links can move a particle.
  ws.collider_position_only =
      !ctx.links.empty() || (settings.particle_collisions && !ws.pairs.empty());
  ws.particle_in_two_collider_contacts =
      !ctx.colliders.empty() && generateColliderContacts(ctx, 0, n);
  if (ctx.bodies) addBodySurfaceContacts(ctx);

  if (settings.particle_collisions) {
    const bool filter = !settings.collide_linked && !ws.linked_pairs.empty();
    const bool custom_materials = ctx.materials.any();
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
        const Material ma = particleMaterial(ctx, a);
        const Material mb = particleMaterial(ctx, b);
        c->restitution = 0.5 * (ma.restitution + mb.restitution);
        c->friction = std::sqrt(ma.friction * mb.friction);
      } else {
        c->restitution = settings.particle_restitution;
        c->friction = settings.particle_friction;
      }
    }
  }

  // Every link is listed: a rod holds either way, and a slack cable is checked again after the
  // position passes, which may stretch it.
  ctx.links.forEach([&](const auto& kind) {
    using Link = typename std::decay_t<decltype(kind)>::value_type;
    for (const Link& link : kind) {
      const LinkLimits limits = LinkKind<Link>::limits(link);
      Contact c;
      c.a = static_cast<std::uint32_t>(particles.denseIndexUnchecked(link.a));
      c.b = link.anchored() ? kNoParticle
                            : static_cast<std::uint32_t>(particles.denseIndexUnchecked(link.b));
      c.kind = limits.pulls_only ? ContactKind::kCable : ContactKind::kRod;
      c.link = static_cast<std::uint32_t>(ws.links.size());
      ws.links.push_back(LinkGeometry{link.anchor, limits.length});
      c.restitution = limits.restitution;
      c.key = linkContactKey(link.id);
      sink.push(c);
    }
  });

  const Vec3& gravity = ctx.config.gravity;
  if (gravity.squaredNorm() > 0.0 && ws.contacts.size() > 1 && !ctx.links.empty()) {
    // Bottom up along gravity (colliders first): a forward pass carries the support from the
    // ground to the top of a pile. Without links the contacts already are in that order: the
    // collider ones (bucket 0), then those of the pairs, sorted when the list was made. Links
    // (listed last) are sorted in with the others by the buckets of now.
    if (ws.buckets == 0) {
      heightBuckets(x, radius, -gravity.normalized(), ws.particle_bucket, ws.buckets);
    }
    const std::uint32_t buckets = ws.buckets;
    ws.item_bucket.resize(ws.contacts.size());
    for (std::size_t k = 0; k < ws.contacts.size(); ++k) {
      const Contact& c = ws.contacts[k];
      ws.item_bucket[k] =
          c.b == kNoParticle ? 0 : std::min(ws.particle_bucket[c.a], ws.particle_bucket[c.b]);
    }
    sortByBucket(ws.contacts, ws.item_bucket, buckets, ws.bucket_start, ws.sorted_contacts);
  }
}

}  // namespace engine
}  // namespace mass_aggregate_sim
