#include "engine/collision/dynamic_tree.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <random>
#include <vector>

#include "engine/collision/body_pairs.h"
#include "engine/collision/ray_segment.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

constexpr Real kMargin = 0.1;
constexpr Real kRegion = 20.0;

// std::uniform_real_distribution's output differs between standard libraries; this mapping of the
// engine's (fully specified) 32-bit words does not.
class Random {
 public:
  explicit Random(const unsigned seed) : engine_(seed) {}
  Real uniform(const Real lo, const Real hi) {
    return lo + (hi - lo) * (static_cast<Real>(engine_()) / 4294967296.0);
  }
  std::size_t index(const std::size_t n) { return static_cast<std::size_t>(engine_() % n); }
  Vec3 point(const Real half) {
    return Vec3(uniform(-half, half), uniform(-half, half), uniform(-half, half));
  }
  Aabb box(const Real half) {
    const Vec3 c = point(half);
    const Vec3 h(uniform(0.05, 1.0), uniform(0.05, 1.0), uniform(0.05, 1.0));
    return Aabb{c - h, c + h};
  }
  Vec3 direction() {
    Vec3 d;
    do {
      d = point(1.0);
    } while (d.norm() < 0.1);
    return d.normalized();
  }

 private:
  std::mt19937 engine_;
};

Aabb shifted(const Aabb& box, const Vec3& by) { return Aabb{box.lower + by, box.upper + by}; }

// A tree and what it should hold: the live proxies and their tight boxes, by id.
struct Scene {
  DynamicTree tree{kMargin};
  std::vector<Aabb> tight;
  std::vector<char> live;
  std::vector<std::int32_t> live_ids;  // in no particular order, to pick from

  std::int32_t create(const Aabb& box) {
    const std::int32_t id = tree.createProxy(box, 1000u + live_ids.size());
    const auto i = static_cast<std::size_t>(id);
    if (i >= live.size()) {
      live.resize(i + 1, 0);
      tight.resize(i + 1);
    }
    EXPECT_FALSE(live[i]);
    live[i] = 1;
    tight[i] = box;
    live_ids.push_back(id);
    return id;
  }
  std::int32_t pick(Random& random) const { return live_ids[random.index(live_ids.size())]; }
  void destroy(const std::int32_t id) {
    tree.destroyProxy(id);
    live[static_cast<std::size_t>(id)] = 0;
    const auto it = std::find(live_ids.begin(), live_ids.end(), id);
    *it = live_ids.back();
    live_ids.pop_back();
  }
  // Sorted.
  std::vector<std::int32_t> ids() const {
    std::vector<std::int32_t> result;
    for (std::size_t i = 0; i < live.size(); ++i) {
      if (live[i]) result.push_back(static_cast<std::int32_t>(i));
    }
    return result;
  }
  // Moves by a small step (often inside the fat box) or a large one, and checks the stored box.
  bool move(const std::int32_t id, Random& random) {
    const bool large = random.index(4) == 0;
    const Vec3 step = random.point(large ? 2.0 : 0.06);
    const Aabb to = shifted(tight[static_cast<std::size_t>(id)], step);
    const Aabb before = tree.fatAabb(id);
    const bool moved = tree.moveProxy(id, to, step);
    // The box it will sweep next: to stretched by step.
    const Aabb reach{to.lower + step.cwiseMin(Vec3::Zero()),
                     to.upper + step.cwiseMax(Vec3::Zero())};
    EXPECT_EQ(moved, !before.contains(reach));
    if (moved) {
      const Aabb fat = reach.grown(kMargin);
      EXPECT_EQ(tree.fatAabb(id).lower, fat.lower);
      EXPECT_EQ(tree.fatAabb(id).upper, fat.upper);
    } else {
      EXPECT_EQ(tree.fatAabb(id).lower, before.lower);
      EXPECT_EQ(tree.fatAabb(id).upper, before.upper);
    }
    tight[static_cast<std::size_t>(id)] = to;
    return moved;
  }
  // A batch of random destroys, creates and moves.
  void churn(Random& random, const int operations, std::vector<std::int32_t>* moved = nullptr) {
    for (int i = 0; i < operations; ++i) {
      const std::size_t kind = random.index(10);
      if (kind == 0 && !live_ids.empty()) {
        destroy(pick(random));
      } else if (kind == 1 || live_ids.empty()) {
        const std::int32_t id = create(random.box(kRegion));
        if (moved != nullptr) moved->push_back(id);
      } else {
        const std::int32_t id = pick(random);
        if (move(id, random) && moved != nullptr) moved->push_back(id);
      }
    }
  }

  std::vector<std::int32_t> queryTree(const Aabb& box) const {
    std::vector<std::int32_t> hits;
    tree.query(box, [&](const std::int32_t id) {
      hits.push_back(id);
      return true;
    });
    return hits;
  }
  std::vector<std::int32_t> queryBrute(const Aabb& box) const {
    std::vector<std::int32_t> hits;
    for (const std::int32_t id : ids()) {
      if (tree.fatAabb(id).overlaps(box)) hits.push_back(id);
    }
    return hits;
  }
  // Everything the tree should answer, checked against brute force.
  void check(Random& random) const {
    ASSERT_TRUE(tree.validate());
    ASSERT_EQ(tree.proxyCount(), static_cast<int>(live_ids.size()));
    for (const std::int32_t id : ids()) {
      ASSERT_TRUE(tree.isProxy(id));
      ASSERT_TRUE(tree.fatAabb(id).contains(tight[static_cast<std::size_t>(id)]));
    }
    for (int q = 0; q < 40; ++q) {
      const Aabb box = q % 4 == 0 ? random.box(kRegion).grown(3.0) : random.box(kRegion);
      std::vector<std::int32_t> hits = queryTree(box);
      std::sort(hits.begin(), hits.end());
      ASSERT_EQ(std::adjacent_find(hits.begin(), hits.end()), hits.end());
      ASSERT_EQ(hits, queryBrute(box));
    }
  }
};

Scene randomScene(Random& random, const int n) {
  Scene scene;
  for (int i = 0; i < n; ++i) scene.create(random.box(kRegion));
  return scene;
}

TEST(DynamicTree, EmptyTreeAnswersNothing) {
  const DynamicTree tree(kMargin);
  EXPECT_EQ(tree.height(), 0);
  EXPECT_EQ(tree.proxyCount(), 0);
  EXPECT_EQ(tree.areaRatio(), 0.0);
  EXPECT_TRUE(tree.validate());
  int calls = 0;
  tree.query(Aabb{Vec3::Constant(-1e9), Vec3::Constant(1e9)},
             [&](std::int32_t) { return ++calls > 0; });
  tree.rayCast(Vec3::Zero(), Vec3::UnitX(), 1e9, [&](std::int32_t, Real t) { return ++calls, t; });
  EXPECT_EQ(calls, 0);
}

TEST(DynamicTree, RandomCreateDestroyMoveMatchesBruteForceQueries) {
  Random random(11);
  Scene scene = randomScene(random, 3000);
  scene.check(random);
  for (int batch = 0; batch < 12; ++batch) {
    scene.churn(random, 1500);
    scene.check(random);
  }
  // Down to nothing and back: the free list is reused.
  while (!scene.live_ids.empty()) scene.destroy(scene.pick(random));
  scene.check(random);
  EXPECT_EQ(scene.tree.height(), 0);
  const std::int32_t bound = scene.tree.idBound();
  for (int i = 0; i < 500; ++i) scene.create(random.box(kRegion));
  EXPECT_EQ(scene.tree.idBound(), bound);
  scene.check(random);
}

TEST(DynamicTree, RayCastVisitsExactlyTheCrossedBoxes) {
  Random random(12);
  Scene scene = randomScene(random, 2500);
  for (int batch = 0; batch < 4; ++batch) {
    scene.churn(random, 800);
    for (int r = 0; r < 100; ++r) {
      const Vec3 origin = random.point(kRegion + 5.0);
      Vec3 direction = random.direction();
      if (r % 10 == 0) direction = Vec3::Unit(static_cast<Eigen::Index>(random.index(3)));
      const Real max_t = random.uniform(1.0, 40.0);
      const RaySegment ray(origin, direction);

      std::vector<std::int32_t> hits;
      scene.tree.rayCast(origin, direction, max_t, [&](const std::int32_t id, const Real t) {
        EXPECT_EQ(t, max_t);
        hits.push_back(id);
        return t;
      });
      std::vector<std::int32_t> expected;
      Real closest = max_t;
      std::int32_t closest_id = DynamicTree::kNull;
      for (const std::int32_t id : scene.ids()) {
        Real t = 0.0;
        if (!ray.enters(scene.tree.fatAabb(id), max_t, t)) continue;
        expected.push_back(id);
        if (closest_id == DynamicTree::kNull || t < closest) {
          closest = t;
          closest_id = id;
        }
      }
      std::sort(hits.begin(), hits.end());
      ASSERT_EQ(hits, expected);

      // Clipping at each hit's entry leaves the closest one.
      Real found = max_t;
      std::int32_t found_id = DynamicTree::kNull;
      int calls = 0;
      scene.tree.rayCast(origin, direction, max_t, [&](const std::int32_t id, const Real t) {
        ++calls;
        Real entry = 0.0;
        EXPECT_TRUE(ray.enters(scene.tree.fatAabb(id), t, entry));
        if (entry < found || found_id == DynamicTree::kNull) {
          found = entry;
          found_id = id;
        }
        // 0 would stop: an origin inside a box is the closest hit there is.
        return entry > 0.0 ? entry : 0.0;
      });
      EXPECT_LE(calls, static_cast<int>(expected.size()));
      ASSERT_EQ(found_id == DynamicTree::kNull, closest_id == DynamicTree::kNull);
      if (closest_id != DynamicTree::kNull) {
        EXPECT_EQ(found, closest);
      }
    }
  }
}

TEST(DynamicTree, RaySegmentSlabTestHandlesAxisAlignedAndInsideRays) {
  const Aabb box{Vec3(1.0, -1.0, -1.0), Vec3(2.0, 1.0, 1.0)};
  Real t = -1.0;
  EXPECT_TRUE(RaySegment(Vec3::Zero(), Vec3::UnitX()).enters(box, 10.0, t));
  EXPECT_EQ(t, 1.0);
  EXPECT_FALSE(RaySegment(Vec3::Zero(), Vec3::UnitX()).enters(box, 0.5, t));
  EXPECT_FALSE(RaySegment(Vec3::Zero(), -Vec3::UnitX()).enters(box, 10.0, t));
  // Along a face (zero direction components with the origin on the slab's bound).
  EXPECT_TRUE(RaySegment(Vec3(0.0, 1.0, -1.0), Vec3::UnitX()).enters(box, 10.0, t));
  EXPECT_EQ(t, 1.0);
  EXPECT_FALSE(RaySegment(Vec3(0.0, 1.5, 0.0), Vec3::UnitX()).enters(box, 10.0, t));
  EXPECT_TRUE(RaySegment(Vec3(1.5, 0.0, 0.0), Vec3::UnitY()).enters(box, 0.0, t));
  EXPECT_EQ(t, 0.0);
  EXPECT_TRUE(
      RaySegment(Vec3(0.0, -2.0, 0.0), Vec3(1.0, 1.0, 0.0).normalized()).enters(box, 10.0, t));
}

TEST(DynamicTree, RayCastStopsOnZeroAndQueryStopsOnFalse) {
  Random random(13);
  Scene scene = randomScene(random, 500);
  scene.create(Aabb{Vec3::Constant(-0.5), Vec3::Constant(0.5)});
  int calls = 0;
  scene.tree.query(Aabb{Vec3::Constant(-100.0), Vec3::Constant(100.0)},
                   [&](std::int32_t) { return ++calls < 3; });
  EXPECT_EQ(calls, 3);
  calls = 0;
  scene.tree.rayCast(Vec3(-50.0, 0.0, 0.0), Vec3::UnitX(), 100.0, [&](std::int32_t, Real) {
    ++calls;
    return 0.0;
  });
  EXPECT_EQ(calls, 1);
}

TEST(DynamicTree, HeightStaysLogarithmic) {
  Random random(14);
  const int n = 4096;
  const Real bound = 2.5 * std::log2(static_cast<Real>(n));
  const Scene scattered = randomScene(random, n);
  EXPECT_LE(scattered.tree.height(), bound);
  // Boxes added in order along a line: a tree without rotations would become a list.
  DynamicTree line(kMargin);
  for (int i = 0; i < n; ++i) {
    const Vec3 c(static_cast<Real>(i), 0.0, 0.0);
    line.createProxy(Aabb{c - Vec3::Constant(0.4), c + Vec3::Constant(0.4)}, 0);
  }
  EXPECT_TRUE(line.validate());
  EXPECT_LE(line.height(), bound);
  // And after many moves.
  Scene moving = randomScene(random, n);
  for (int batch = 0; batch < 4; ++batch) moving.churn(random, 4000);
  EXPECT_LE(moving.tree.height(), 2.5 * std::log2(static_cast<Real>(moving.live_ids.size())));
}

TEST(DynamicTree, SmallMoveInsideTheFatBoxChangesNothing) {
  DynamicTree tree(kMargin);
  const Aabb box{Vec3::Zero(), Vec3::Ones()};
  const std::int32_t a = tree.createProxy(box, 7);
  const std::int32_t b = tree.createProxy(shifted(box, Vec3(3.0, 0.0, 0.0)), 8);
  // Created moving: the box reaches where it goes in the first step.
  const std::int32_t c =
      tree.createProxy(shifted(box, Vec3(6.0, 0.0, 0.0)), 9, Vec3(0.0, 0.0, 2.0));
  EXPECT_EQ(tree.fatAabb(c).lower, Vec3(6.0 - kMargin, -kMargin, -kMargin));
  EXPECT_EQ(tree.fatAabb(c).upper, Vec3(7.0 + kMargin, 1.0 + kMargin, 3.0 + kMargin));
  EXPECT_EQ(tree.userData(a), 7u);
  EXPECT_EQ(tree.userData(b), 8u);
  const Aabb fat = tree.fatAabb(a);
  EXPECT_EQ(fat.lower, Vec3::Constant(-kMargin));
  EXPECT_FALSE(tree.moveProxy(a, shifted(box, Vec3(0.04, -0.05, 0.0)), Vec3(0.04, -0.05, 0.0)));
  EXPECT_EQ(tree.fatAabb(a).lower, fat.lower);
  EXPECT_EQ(tree.fatAabb(a).upper, fat.upper);
  // Inside it now, but the next step's sweep would leave it: moved, so a body speeding up is met
  // where it is going.
  EXPECT_TRUE(tree.moveProxy(a, shifted(box, Vec3(0.04, -0.05, 0.0)), Vec3(0.0, -0.2, 0.0)));
  EXPECT_EQ(tree.fatAabb(a).lower, Vec3(0.04 - kMargin, (-0.05 - 0.2) - kMargin, -kMargin));
  // Out of it: predicted along the displacement.
  EXPECT_TRUE(tree.moveProxy(a, shifted(box, Vec3(0.5, 0.0, 0.0)), Vec3(0.5, 0.0, -0.2)));
  EXPECT_EQ(tree.fatAabb(a).lower, Vec3(0.5 - kMargin, -kMargin, -0.2 - kMargin));
  EXPECT_EQ(tree.fatAabb(a).upper, Vec3(2.0 + kMargin, 1.0 + kMargin, 1.0 + kMargin));
  EXPECT_TRUE(tree.validate());
}

TEST(DynamicTree, CopyIsIndependentAndBehavesIdentically) {
  Random random(15);
  Scene original = randomScene(random, 2000);
  original.churn(random, 1000);
  Scene copy = original;
  const std::vector<std::int32_t> before = original.queryTree(random.box(kRegion).grown(5.0));
  // The same calls on both give the same trees, visited in the same order.
  Random random_a(16);
  Random random_b(16);
  original.churn(random_a, 2000);
  copy.churn(random_b, 2000);
  copy.check(random_b);
  for (int q = 0; q < 20; ++q) {
    const Aabb box = random.box(kRegion).grown(2.0);
    ASSERT_EQ(original.queryTree(box), copy.queryTree(box));
  }
  EXPECT_EQ(original.tree.height(), copy.tree.height());
  EXPECT_EQ(original.tree.areaRatio(), copy.tree.areaRatio());
  // Changing the copy leaves the original alone.
  Scene reference = original;
  while (!copy.live_ids.empty()) copy.destroy(copy.pick(random));
  const Aabb all{Vec3::Constant(-100.0), Vec3::Constant(100.0)};
  EXPECT_EQ(original.queryTree(all), reference.queryTree(all));
  EXPECT_FALSE(before.empty());
}

TEST(DynamicTree, SameCallsGiveSameVisitOrder) {
  const auto run = [](std::vector<std::int32_t>& order) {
    Random random(17);
    Scene scene = randomScene(random, 1500);
    scene.churn(random, 1500);
    for (int q = 0; q < 10; ++q) {
      for (const std::int32_t id : scene.queryTree(random.box(kRegion).grown(4.0)))
        order.push_back(id);
      scene.tree.rayCast(random.point(kRegion), random.direction(), 30.0,
                         [&](const std::int32_t id, const Real t) {
                           order.push_back(id);
                           return t;
                         });
    }
  };
  std::vector<std::int32_t> first;
  std::vector<std::int32_t> second;
  run(first);
  run(second);
  EXPECT_GT(first.size(), 100u);
  EXPECT_EQ(first, second);
}

TEST(DynamicTree, RebuildKeepsProxiesAndLowersTheCost) {
  Random random(18);
  Scene scene = randomScene(random, 3000);
  scene.churn(random, 3000);
  const Real incremental_ratio = scene.tree.areaRatio();
  const std::int32_t bound = scene.tree.idBound();
  std::map<std::int32_t, std::uint64_t> user;
  for (const std::int32_t id : scene.ids()) user[id] = scene.tree.userData(id);
  scene.tree.rebuild();
  scene.check(random);
  EXPECT_EQ(scene.tree.idBound(), bound);
  for (const auto& entry : user) EXPECT_EQ(scene.tree.userData(entry.first), entry.second);
  EXPECT_LT(scene.tree.areaRatio(), incremental_ratio);
  EXPECT_LE(scene.tree.height(), 2.5 * std::log2(static_cast<Real>(scene.live_ids.size())));
  // It stays a working dynamic tree.
  scene.churn(random, 2000);
  scene.check(random);
}

// Pairs of proxies of one "body" (same user data / 4) are rejected, as a filter would.
bool acceptPair(const std::uint64_t user_a, const std::uint64_t user_b) {
  return user_a / 4 != user_b / 4;
}

std::vector<ProxyPair> brutePairs(const Scene& scene, const std::vector<std::int32_t>& moved) {
  std::vector<ProxyPair> pairs;
  std::vector<char> was_moved(scene.live.size(), 0);
  for (const std::int32_t id : moved) was_moved[static_cast<std::size_t>(id)] = 1;
  const std::vector<std::int32_t> ids = scene.ids();
  for (std::size_t i = 0; i < ids.size(); ++i) {
    for (std::size_t j = i + 1; j < ids.size(); ++j) {
      const std::int32_t a = ids[i];
      const std::int32_t b = ids[j];
      if (!was_moved[static_cast<std::size_t>(a)] && !was_moved[static_cast<std::size_t>(b)])
        continue;
      if (!scene.tree.fatAabb(a).overlaps(scene.tree.fatAabb(b))) continue;
      if (acceptPair(scene.tree.userData(a), scene.tree.userData(b))) pairs.push_back({a, b});
    }
  }
  return pairs;
}

TEST(BodyPairs, FinderMatchesBruteForce) {
  Random random(21);
  Scene scene = randomScene(random, 1500);
  PairFinder finder;
  std::vector<ProxyPair> pairs;
  for (int round = 0; round < 5; ++round) {
    std::vector<std::int32_t> moved;
    scene.churn(random, 300, &moved);
    // Repeats are allowed; proxies destroyed since they moved are not.
    moved.erase(std::remove_if(moved.begin(), moved.end(),
                               [&](const std::int32_t id) { return !scene.tree.isProxy(id); }),
                moved.end());
    for (int extra = 0; extra < 50; ++extra) moved.push_back(scene.pick(random));
    for (int extra = 0; extra < 10; ++extra) moved.push_back(moved[random.index(moved.size())]);
    finder.findPairs(scene.tree, moved, acceptPair, pairs);
    ASSERT_TRUE(std::is_sorted(pairs.begin(), pairs.end()));
    ASSERT_EQ(std::adjacent_find(pairs.begin(), pairs.end()), pairs.end());
    const std::vector<ProxyPair> expected = brutePairs(scene, moved);
    EXPECT_GT(expected.size(), 10u);
    ASSERT_EQ(pairs, expected);
  }
  // Everything moved: every overlapping accepted pair.
  const std::vector<std::int32_t> all = scene.ids();
  finder.findPairs(scene.tree, all, acceptPair, pairs);
  EXPECT_EQ(pairs, brutePairs(scene, all));
}

TEST(BodyPairs, PersistentPairsEqualAllOverlappingPairs) {
  Random random(22);
  Scene scene;
  PairFinder finder;
  PersistentPairs persistent;
  std::vector<ProxyPair> found;
  std::vector<ProxyPair> ended;
  std::vector<std::int32_t> moved;
  for (int i = 0; i < 1200; ++i) moved.push_back(scene.create(random.box(0.5 * kRegion)));
  for (int step = 0; step < 30; ++step) {
    finder.findPairs(scene.tree, moved, acceptPair, found);
    const std::size_t ended_before = ended.size();
    persistent.update(scene.tree, found, moved, &ended);
    for (std::size_t e = ended_before; e < ended.size(); ++e) {
      EXPECT_FALSE(scene.tree.fatAabb(ended[e].a).overlaps(scene.tree.fatAabb(ended[e].b)));
    }
    ASSERT_EQ(persistent.pairs(), brutePairs(scene, scene.ids())) << "step " << step;

    moved.clear();
    for (int k = 0; k < 200; ++k) {
      const std::int32_t id = scene.pick(random);
      if (scene.move(id, random)) moved.push_back(id);
    }
    for (int k = 0; k < 5; ++k) {
      const std::int32_t id = scene.pick(random);
      persistent.removeProxy(id);
      scene.destroy(id);
      moved.erase(std::remove(moved.begin(), moved.end(), id), moved.end());
      moved.push_back(scene.create(random.box(0.5 * kRegion)));
    }
  }
  EXPECT_GT(ended.size(), 50u);
}

TEST(BodyPairs, CopiedTreeGivesTheSamePairs) {
  Random random(23);
  const Scene scene = randomScene(random, 1000);
  const Scene copy = scene;
  std::vector<std::int32_t> moved;
  for (int k = 0; k < 300; ++k) moved.push_back(scene.pick(random));
  PairFinder finder;
  std::vector<ProxyPair> a;
  std::vector<ProxyPair> b;
  std::vector<std::pair<std::uint64_t, std::uint64_t>> calls_a;
  std::vector<std::pair<std::uint64_t, std::uint64_t>> calls_b;
  finder.findPairs(
      scene.tree, moved,
      [&](std::uint64_t x, std::uint64_t y) {
        calls_a.emplace_back(x, y);
        return true;
      },
      a);
  PairFinder other;
  other.findPairs(
      copy.tree, moved,
      [&](std::uint64_t x, std::uint64_t y) {
        calls_b.emplace_back(x, y);
        return true;
      },
      b);
  EXPECT_FALSE(a.empty());
  EXPECT_EQ(a, b);
  EXPECT_EQ(calls_a, calls_b);
}

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
