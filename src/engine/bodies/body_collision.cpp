#include "engine/bodies/body_collision.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <type_traits>

#include "engine/collision/narrowphase/any_shape.h"
#include "engine/collision/narrowphase/swept_contact.h"
#include "engine/core/sort_runs.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

// A tree proxy's user data: what it holds, in the top bits, and its index.
enum class ProxyKind : std::uint64_t { kShape = 0, kCollider = 1 };
constexpr int kKindShift = 62;
constexpr std::uint64_t kIndexMask = (std::uint64_t{1} << kKindShift) - 1;

std::uint64_t proxyData(const ProxyKind kind, const std::uint64_t index) {
  return (static_cast<std::uint64_t>(kind) << kKindShift) | index;
}
ProxyKind proxyKind(const std::uint64_t data) { return static_cast<ProxyKind>(data >> kKindShift); }
std::uint64_t proxyIndex(const std::uint64_t data) { return data & kIndexMask; }

// A collider in the tree: its kind's position in ShapeKinds and its index in that kind's array.
std::uint64_t colliderIndex(const std::size_t kind, const std::size_t index) {
  return (static_cast<std::uint64_t>(kind) << 32) | index;
}

Aabb shapeBox(const BodyStore& bodies, const ShapeIndex s, const Real margin) {
  return shapeBounds(bodies.shapes()[s].geometry, Frame(bodies.shapePose(s))).grown(margin);
}

bool awakeBody(const BodyStore& bodies, const BodyId id) {
  return bodies.awake(bodies.denseIndexUnchecked(id));
}

// A contact between live shapes none of whose sides is awake (never a particle's: those are
// found again each step or end).
bool restsAsleep(const BodyStore& bodies, const ContactKey& key) {
  if (key.other == ContactOther::kParticle) return false;
  const BodyShape& a = bodies.shapes()[key.shape];
  if (!a.live || awakeBody(bodies, a.body)) return false;
  if (key.other != ContactOther::kShape) return true;
  const BodyShape& b = bodies.shapes()[static_cast<ShapeIndex>(key.b)];
  return b.live && !awakeBody(bodies, b.body);
}

// The pair, manifold and material the narrowphase found.
void setFound(const FoundContact& found, BodyContact& contact) {
  contact.key = found.key;
  contact.manifold = found.manifold;
  contact.friction = found.friction;
  contact.restitution = found.restitution;
}

// A pair's contact that lasts is the old one (the manifold's friction and twist whatever its
// points: a resting face whose clipped points change ids from step to step keeps its grip, where
// dropped it let the slope boxes of a tall pyramid turn for seconds longer; and the coupled masses
// it kept inverted, which prepareContact inverts again when they have changed) with the new
// manifold, whose points take the normal impulses of the old points with the same feature ids.
void takeManifold(const FoundContact& found, BodyContact& contact) {
  const int old_count = contact.manifold.count;
  std::array<std::uint32_t, Manifold::kMaxPoints> old_ids{};
  for (int j = 0; j < old_count; ++j) old_ids[j] = contact.manifold.points[j].id;
  const std::array<Real, Manifold::kMaxPoints> old_impulses = contact.normal_impulses;
  setFound(found, contact);
  contact.normal_impulses.fill(0.0);
  for (int k = 0; k < contact.manifold.count; ++k) {
    for (int j = 0; j < old_count; ++j) {
      if (old_ids[j] == contact.manifold.points[k].id) {
        contact.normal_impulses[k] = old_impulses[j];
        break;
      }
    }
  }
}

// Calls f(kind index, collider) for every collider of every kind.
template <typename F>
void forEachCollider(const Colliders& colliders, F&& f) {
  std::size_t kind = 0;
  colliders.forEach([&](const auto& array) {
    for (std::size_t i = 0; i < array.size(); ++i) f(kind, i, array[i]);
    ++kind;
  });
}

// Calls f(collider) for the collider a tree proxy names.
template <typename F>
void withCollider(const Colliders& colliders, const std::uint64_t index, F&& f) {
  const std::size_t kind = index >> 32;
  const std::size_t i = index & 0xFFFFFFFFu;
  std::size_t k = 0;
  colliders.forEach([&](const auto& array) {
    if (k++ == kind) f(array[i]);
  });
}

template <typename Collider>
Material colliderMaterial(const Collider& c) {
  return c.material;
}

using IdPair = std::pair<std::uint64_t, std::uint64_t>;

// The ends a joint keeps apart from contact (collide_connected false), sorted for lookups.
void collectJoinedEnds(const Joints& joints, std::vector<IdPair>& bodies,
                       std::vector<IdPair>& particles) {
  bodies.clear();
  particles.clear();
  joints.forEach([&](const auto& array) {
    for (const auto& joint : array) {
      if (joint.collide_connected) continue;
      const JointEnd& a = joint.a;
      const JointEnd& b = joint.b;
      if (a.isBody() && b.isBody()) {
        bodies.emplace_back(std::min(a.body.packed(), b.body.packed()),
                            std::max(a.body.packed(), b.body.packed()));
      } else if (a.isBody() && b.isParticle()) {
        particles.emplace_back(a.body.packed(), b.particle.packed());
      } else if (a.isParticle() && b.isBody()) {
        particles.emplace_back(b.body.packed(), a.particle.packed());
      }
    }
  });
  std::sort(bodies.begin(), bodies.end());
  std::sort(particles.begin(), particles.end());
}

bool holds(const std::vector<IdPair>& pairs, const IdPair& pair) {
  return !pairs.empty() && std::binary_search(pairs.begin(), pairs.end(), pair);
}

}  // namespace

ContactPatch contactPatch(const Manifold& manifold) {
  ContactPatch patch;
  patch.offsets.fill(Vec3::Zero());
  for (int k = 0; k < manifold.count; ++k) patch.center += manifold.points[k].point;
  if (manifold.count > 0) patch.center /= static_cast<Real>(manifold.count);
  for (int k = 0; k < manifold.count; ++k) {
    const Vec3 d = manifold.points[k].point - patch.center;
    patch.offsets[k] = d - d.dot(manifold.normal) * manifold.normal;
  }
  return patch;
}

Material combineMaterials(const Material& a, const Material& b) {
  return Material{0.5 * (a.restitution + b.restitution), std::sqrt(a.friction * b.friction)};
}

namespace {

// Pairs that can never touch, whatever happens to their bodies: two colliders, two shapes of one
// body. The rest of the filter (joints, sleep, body types) can change and is applied each step.
bool mayEverTouch(const BodyStore& bodies, const std::uint64_t x, const std::uint64_t y) {
  const ProxyKind kx = proxyKind(x);
  const ProxyKind ky = proxyKind(y);
  if (kx == ProxyKind::kCollider && ky == ProxyKind::kCollider) return false;
  if (kx == ProxyKind::kShape && ky == ProxyKind::kShape) {
    return bodies.shapes()[proxyIndex(x)].body != bodies.shapes()[proxyIndex(y)].body;
  }
  return true;
}

void dropProxy(BodyWorkspace& ws, const std::int32_t proxy) {
  ws.proxy_pairs.removeProxy(proxy);
  ws.tree.destroyProxy(proxy);
}

}  // namespace

void updateBodyProxies(const BodyCollisionScene& scene, BodyStore& bodies, BodyWorkspace& ws) {
  const Real margin = scene.settings.speculative_distance;
  ws.moved.clear();
  if (ws.colliders_version != scene.colliders_version) {
    for (const std::int32_t proxy : ws.collider_proxies) dropProxy(ws, proxy);
    ws.collider_proxies.clear();
    forEachCollider(
        scene.colliders, [&](const std::size_t kind, const std::size_t i, const auto& collider) {
          using Kind = ShapeKind<std::decay_t<decltype(collider)>>;
          const std::optional<Aabb> box = Kind::bounds(collider);
          if (!box) return;  // unbounded: met by every shape
          ws.collider_proxies.push_back(ws.tree.createProxy(
              box->grown(margin), proxyData(ProxyKind::kCollider, colliderIndex(kind, i))));
          ws.moved.push_back(ws.collider_proxies.back());
        });
    ws.colliders_version = scene.colliders_version;
  }
  for (const BodyId id : ws.posed) {
    const auto i = bodies.find(id);
    if (!i) continue;  // removed since
    for (const ShapeIndex s : bodies.shapesOf(*i)) {
      const std::int32_t proxy = bodies.shapes()[s].proxy;
      if (proxy >= 0 && ws.tree.moveProxy(proxy, shapeBox(bodies, s, margin), Vec3::Zero())) {
        ws.moved.push_back(proxy);
      }
    }
  }
  ws.posed.clear();
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const bool awake = bodies.awake(i);
    for (const ShapeIndex s : bodies.shapesOf(i)) {
      BodyShape& shape = bodies.shapes()[s];
      if (!awake && shape.proxy >= 0) continue;  // asleep where it was put
      const Aabb box = shapeBox(bodies, s, margin);
      const Vec3 displacement = bodies.linearVelocity(i) * scene.dt;
      // A body that has diverged (the world reports it; its policy may let it go on) leaves the
      // tree, so it meets nothing, and comes back once its pose is finite again.
      if (!box.lower.allFinite() || !box.upper.allFinite() || !displacement.allFinite()) {
        if (shape.proxy >= 0) dropProxy(ws, shape.proxy);
        shape.proxy = -1;
        continue;
      }
      if (shape.proxy < 0) {
        shape.proxy = ws.tree.createProxy(box, proxyData(ProxyKind::kShape, s), displacement);
        ws.moved.push_back(shape.proxy);
      } else if (ws.tree.moveProxy(shape.proxy, box, displacement)) {
        ws.moved.push_back(shape.proxy);
      }
    }
  }
  // Only a stored box that changed can start or end an overlap: the pairs of the others stand.
  if (ws.moved.empty()) return;
  ws.finder.findPairs(
      ws.tree, ws.moved,
      [&](const std::uint64_t x, const std::uint64_t y) { return mayEverTouch(bodies, x, y); },
      ws.pairs);
  ws.proxy_pairs.update(ws.tree, ws.pairs, ws.moved);
}

void removeBodyProxies(BodyStore& bodies, const std::size_t dense, BodyWorkspace& ws) {
  for (const ShapeIndex s : bodies.shapesOf(dense)) {
    BodyShape& shape = bodies.shapes()[s];
    if (shape.proxy >= 0) dropProxy(ws, shape.proxy);
    shape.proxy = -1;
  }
}

void findBodyContacts(const BodyCollisionScene& scene, BodyWorkspace& ws) {
  const BodyStore& bodies = scene.bodies;
  const Real speculative = scene.settings.speculative_distance;
  // Continuous collision: speculative margins grow with the motion over the step, so fast
  // bodies meet what they are about to hit (and bounce off it) instead of passing into it.
  std::vector<Real>& travel = ws.travel;
  travel.resize(bodies.size());
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    travel[i] = scene.settings.continuous && bodies.awake(i)
                    ? scene.dt * (bodies.linearVelocity(i).norm() +
                                  bodies.angularVelocity(i).norm() * bodies.reach(i))
                    : 0.0;
  }
  const auto travelOf = [&](const ShapeIndex s) {
    return travel[bodies.denseIndexUnchecked(bodies.shapes()[s].body)];
  };
  collectJoinedEnds(scene.joints, ws.joined_bodies, ws.joined_particles);
  const auto joinedBodies = [&](const BodyId a, const BodyId b) {
    return holds(ws.joined_bodies,
                 IdPair{std::min(a.packed(), b.packed()), std::max(a.packed(), b.packed())});
  };
  // Each shape's frame once a step, when a pair first needs it: a shape meets many candidates
  // (a small sphere in a pile, dozens), and the narrowphase wants its rotation as a matrix.
  ++ws.frame_step;
  ws.shape_frames.resize(bodies.shapes().size());
  ws.shape_frame_step.resize(bodies.shapes().size(), 0);
  const auto frameOf = [&](const ShapeIndex s) -> const Frame& {
    if (ws.shape_frame_step[s] != ws.frame_step) {
      ws.shape_frames[s] = Frame(bodies.shapePose(s));
      ws.shape_frame_step[s] = ws.frame_step;
    }
    return ws.shape_frames[s];
  };
  std::vector<FoundContact>& found = ws.found;
  found.clear();
  const auto keep = [&](const ContactKey& key, const Manifold& manifold, const Material& material) {
    if (manifold.count == 0) return;
    found.push_back(FoundContact{key, manifold, material.friction, material.restitution});
  };

  // Shape pairs and shapes against bounded colliders, from the tree's overlapping boxes: every
  // pair with an awake shape that may touch now.
  const auto touchable = [&](const std::uint64_t x, const std::uint64_t y) {
    if (proxyKind(x) == ProxyKind::kShape && proxyKind(y) == ProxyKind::kShape) {
      const BodyShape& a = bodies.shapes()[proxyIndex(x)];
      const BodyShape& b = bodies.shapes()[proxyIndex(y)];
      if (joinedBodies(a.body, b.body)) return false;
      const std::size_t ia = bodies.denseIndexUnchecked(a.body);
      const std::size_t ib = bodies.denseIndexUnchecked(b.body);
      // Two bodies that cannot move against each other never touch.
      if (!bodies.dynamic(ia) && !bodies.dynamic(ib)) return false;
      return bodies.awake(ia) || bodies.awake(ib);
    }
    const std::uint64_t shape = proxyKind(x) == ProxyKind::kShape ? x : y;
    const std::size_t i = bodies.denseIndexUnchecked(bodies.shapes()[proxyIndex(shape)].body);
    return bodies.awake(i) && bodies.dynamic(i);
  };
  // A pair touches only with an awake shape: most pairs of a pile that mostly sleeps are passed
  // over on two bytes.
  std::vector<std::uint8_t>& awake_proxy = ws.awake_proxy;
  awake_proxy.assign(static_cast<std::size_t>(ws.tree.idBound()), 0);
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    if (!bodies.awake(i)) continue;
    for (const ShapeIndex s : bodies.shapesOf(i)) {
      const std::int32_t proxy = bodies.shapes()[s].proxy;
      if (proxy >= 0) awake_proxy[static_cast<std::size_t>(proxy)] = 1;
    }
  }
  for (const ProxyPair& pair : ws.proxy_pairs.pairs()) {
    if (!awake_proxy[static_cast<std::size_t>(pair.a)] &&
        !awake_proxy[static_cast<std::size_t>(pair.b)]) {
      continue;
    }
    const std::uint64_t x = ws.tree.userData(pair.a);
    const std::uint64_t y = ws.tree.userData(pair.b);
    if (!touchable(x, y)) continue;
    if (proxyKind(x) == ProxyKind::kShape && proxyKind(y) == ProxyKind::kShape) {
      const auto sa = static_cast<ShapeIndex>(std::min(proxyIndex(x), proxyIndex(y)));
      const auto sb = static_cast<ShapeIndex>(std::max(proxyIndex(x), proxyIndex(y)));
      const BodyShape& a = bodies.shapes()[sa];
      const BodyShape& b = bodies.shapes()[sb];
      const std::size_t ia = bodies.denseIndexUnchecked(a.body);
      const std::size_t ib = bodies.denseIndexUnchecked(b.body);
      keep(ContactKey{ContactOther::kShape, sa, sb},
           sweptContact(SweptShape{a.geometry, frameOf(sa), bodies.linearVelocity(ia)},
                        SweptShape{b.geometry, frameOf(sb), bodies.linearVelocity(ib)},
                        speculative + travel[ia] + travel[ib], scene.dt),
           combineMaterials(a.material, b.material));
      continue;
    }
    const std::uint64_t shape_data = proxyKind(x) == ProxyKind::kShape ? x : y;
    const std::uint64_t collider_data = proxyKind(x) == ProxyKind::kShape ? y : x;
    const auto s = static_cast<ShapeIndex>(proxyIndex(shape_data));
    const BodyShape& shape = bodies.shapes()[s];
    const Frame& frame = frameOf(s);
    const Vec3& velocity = bodies.linearVelocity(bodies.denseIndexUnchecked(shape.body));
    const Real margin = speculative + travelOf(s);
    withCollider(scene.colliders, proxyIndex(collider_data), [&](const auto& collider) {
      using Kind = ShapeKind<std::decay_t<decltype(collider)>>;
      const auto collide_at = [&](const Real t) {
        Manifold manifold;
        Kind::bodyContact(collider, shape.geometry, advanced(frame, velocity, t), margin, manifold);
        return manifold;
      };
      keep(ContactKey{ContactOther::kCollider, s, collider.id},
           sweptContact(collide_at, velocity, Vec3::Zero(), scene.dt),
           combineMaterials(shape.material, colliderMaterial(collider)));
    });
  }

  // Unbounded colliders (planes) against every awake dynamic body's shapes.
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    if (!bodies.awake(i) || !bodies.dynamic(i)) continue;
    for (const ShapeIndex s : bodies.shapesOf(i)) {
      const BodyShape& shape = bodies.shapes()[s];
      const Frame& frame = frameOf(s);
      scene.colliders.forEach([&](const auto& array) {
        for (const auto& collider : array) {
          using Kind = ShapeKind<std::decay_t<decltype(collider)>>;
          if (Kind::bounds(collider)) continue;
          Manifold manifold;
          Kind::bodyContact(collider, shape.geometry, frame, speculative + travel[i], manifold);
          keep(ContactKey{ContactOther::kCollider, s, collider.id}, manifold,
               combineMaterials(shape.material, colliderMaterial(collider)));
        }
      });
    }
  }

  // Particles (spheres of their radius) against every body shape near them.
  const ParticleStore& particles = scene.particles;
  if (!particles.empty()) {
    const auto x = particles.positions();
    const auto radius = particles.radii();
    const Material particle_default{scene.collisions.particle_restitution,
                                    scene.collisions.particle_friction};
    const auto v = particles.velocities();
    for (std::size_t p = 0; p < particles.size(); ++p) {
      const Vec3 velocity = v.col(p);
      const Frame particle_frame(x.col(p) - scene.particle_lead * velocity, Mat3::Identity());
      const Vec3& center = particle_frame.position;
      const Real r = radius[p];
      const AnyBodyShape sphere = SphereShape{r};
      const Real margin = speculative + scene.dt * velocity.norm();
      const Aabb box{center - Vec3::Constant(r + margin), center + Vec3::Constant(r + margin)};
      const ParticleId id = particles.idAt(p);
      ws.tree.query(box, [&](const std::int32_t proxy) {
        const std::uint64_t data = ws.tree.userData(proxy);
        if (proxyKind(data) != ProxyKind::kShape) return true;
        const auto s = static_cast<ShapeIndex>(proxyIndex(data));
        const BodyShape& shape = bodies.shapes()[s];
        if (holds(ws.joined_particles, IdPair{shape.body.packed(), id.packed()})) return true;
        const Vec3& body_velocity = bodies.linearVelocity(bodies.denseIndexUnchecked(shape.body));
        keep(ContactKey{ContactOther::kParticle, s, id.packed()},
             sweptContact(SweptShape{shape.geometry, frameOf(s), body_velocity},
                          SweptShape{sphere, particle_frame, velocity}, margin + travelOf(s),
                          scene.dt),
             combineMaterials(shape.material, scene.materials.of(id.index, particle_default)));
        return true;
      });
    }
  }

  // Warm starts: the new contacts in key order, each taking over the old contact of its pair
  // (both lists sorted by key). Sorted through their keys, and only the light found manifolds
  // before that: a contact with its inverted masses is most of a kilobyte. The keys come in
  // sorted runs: the tree's pairs, then each plane's (the particles' are not).
  std::vector<std::pair<ContactKey, std::uint32_t>>& keys = ws.keys;
  keys.clear();
  for (std::uint32_t i = 0; i < found.size(); ++i) keys.emplace_back(found[i].key, i);
  sortRuns(keys, [](const auto& x, const auto& y) { return x.first < y.first; });
  // Contacts where no side is awake stay as they were: nothing has moved them.
  const auto staysAsleep = [&](const BodyContact& kept) {
    if (!restsAsleep(bodies, kept.key)) return false;
    return kept.key.other != ContactOther::kShape ||
           !joinedBodies(bodies.shapes()[kept.key.shape].body,
                         bodies.shapes()[static_cast<ShapeIndex>(kept.key.b)].body);
  };
  // No contact begins or ends (a pile at rest, awake or partly asleep): every old contact is
  // found again or stays asleep, and each found one takes its manifold where it is.
  const auto foundAgain = [&](const std::size_t k, const BodyContact& c) {
    return k < keys.size() && keys[k].first == c.key;
  };
  std::size_t k = 0;
  bool in_place = true;
  for (const BodyContact& c : ws.contacts) {
    if (foundAgain(k, c)) {
      ++k;
    } else if (!staysAsleep(c)) {
      in_place = false;
      break;
    }
  }
  if (in_place && k == keys.size()) {
    ws.awake_contacts.clear();
    k = 0;
    for (std::uint32_t i = 0; i < ws.contacts.size(); ++i) {
      if (!foundAgain(k, ws.contacts[i])) continue;
      takeManifold(found[keys[k++].second], ws.contacts[i]);
      ws.awake_contacts.push_back(i);
    }
    return;
  }
  std::vector<BodyContact>& next = ws.next_contacts;
  next.clear();
  auto old = ws.contacts.begin();
  for (const auto& [key, index] : keys) {
    while (old != ws.contacts.end() && old->key < key) ++old;
    const FoundContact& f = found[index];
    if (old != ws.contacts.end() && old->key == key) {
      takeManifold(f, next.emplace_back(*old));
    } else {
      setFound(f, next.emplace_back());
    }
  }
  const std::size_t fresh = next.size();
  for (const BodyContact& kept : ws.contacts) {
    if (staysAsleep(kept)) next.push_back(kept);
  }
  if (next.size() != fresh) {
    std::inplace_merge(next.begin(), next.begin() + static_cast<std::ptrdiff_t>(fresh), next.end(),
                       [](const BodyContact& p, const BodyContact& q) { return p.key < q.key; });
  }
  ws.kept_masses.keepOnly(ws.contacts, next);
  ws.contacts.swap(next);
  listAwakeContacts(bodies, ws);
}

std::vector<std::size_t> bodiesNear(const BodyStore& bodies, const BodyWorkspace& ws,
                                    const Aabb& box) {
  std::vector<std::size_t> near;
  ws.tree.query(box, [&](const std::int32_t proxy) {
    const std::uint64_t data = ws.tree.userData(proxy);
    if (proxyKind(data) == ProxyKind::kShape) {
      near.push_back(bodies.denseIndexUnchecked(bodies.shapes()[proxyIndex(data)].body));
    }
    return true;
  });
  return near;
}

void listAwakeContacts(const BodyStore& bodies, BodyWorkspace& ws) {
  ws.awake_contacts.clear();
  for (std::uint32_t i = 0; i < ws.contacts.size(); ++i) {
    if (!restsAsleep(bodies, ws.contacts[i].key)) ws.awake_contacts.push_back(i);
  }
}

}  // namespace engine
}  // namespace mass_aggregate_sim
