// The bodies' broadphase (engine/collision/dynamic_tree.h, body_pairs.h) on a field of boxes, each
// swaying about its own place (so the scene neither drifts nor settles): building the tree, one
// step of moving a tenth of the bodies and updating the pair set, the same step by brute force
// (every pair of boxes tested), and closest-hit ray casts.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "engine/collision/body_pairs.h"
#include "engine/collision/dynamic_tree.h"
#include "engine/collision/ray_segment.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

constexpr Real kMargin = 0.1;
constexpr Real kTimeStep = 1.0 / 60.0;
// Each step moves the bodies with index % kMovedShare == step % kMovedShare.
constexpr int kMovedShare = 10;

struct Body {
  Vec3 base;
  Vec3 half_extents;
  Vec3 amplitude;
  Real phase;
};

// Boxes 0.2 to 1 m across, about one per 4 m^3, swaying up to 1 m at up to 1 m/s.
class Field {
 public:
  explicit Field(const std::int64_t n) : engine_(5) {
    half_side_ = 0.8 * std::cbrt(static_cast<Real>(n));
    for (std::int64_t i = 0; i < n; ++i) {
      const Vec3 base(uniform(-half_side_, half_side_), uniform(-half_side_, half_side_),
                      uniform(-half_side_, half_side_));
      const Vec3 half(uniform(0.1, 0.5), uniform(0.1, 0.5), uniform(0.1, 0.5));
      const Vec3 amplitude(uniform(-1.0, 1.0), uniform(-1.0, 1.0), uniform(-1.0, 1.0));
      bodies_.push_back({base, half, amplitude, uniform(0.0, 6.0)});
    }
  }

  std::size_t size() const { return bodies_.size(); }
  Real halfSide() const { return half_side_; }
  Vec3 center(const std::size_t i, const Real time) const {
    const Body& b = bodies_[i];
    return b.base + b.amplitude * std::sin(time + b.phase);
  }
  Aabb box(const std::size_t i, const Real time) const {
    const Vec3 c = center(i, time);
    return Aabb{c - bodies_[i].half_extents, c + bodies_[i].half_extents};
  }
  Real uniform(const Real lo, const Real hi) {
    return lo + (hi - lo) * (static_cast<Real>(engine_()) / 4294967296.0);
  }

 private:
  std::mt19937 engine_;
  Real half_side_;
  std::vector<Body> bodies_;
};

bool acceptAll(std::uint64_t, std::uint64_t) { return true; }

DynamicTree buildTree(const Field& field, std::vector<std::int32_t>& proxies) {
  DynamicTree tree(kMargin);
  proxies.clear();
  for (std::size_t i = 0; i < field.size(); ++i) {
    proxies.push_back(tree.createProxy(field.box(i, 0.0), i));
  }
  return tree;
}

// Arguments: proxy count, 1 to rebuild after the inserts.
void BM_DynamicTreeBuild(benchmark::State& state) {
  const Field field(state.range(0));
  std::vector<std::int32_t> proxies;
  int height = 0;
  Real area_ratio = 0.0;
  for (auto _ : state) {
    DynamicTree tree = buildTree(field, proxies);
    if (state.range(1) != 0) tree.rebuild();
    height = tree.height();
    area_ratio = tree.areaRatio();
    benchmark::DoNotOptimize(tree);
  }
  state.SetItemsProcessed(state.iterations() * state.range(0));
  state.counters["height"] = height;
  state.counters["area_ratio"] = area_ratio;
}

// One step: a tenth of the bodies move to where the clock says; those that left their fat boxes
// are reinserted, their new pairs found and the persistent pair set updated (all pairs, as the
// brute force below finds them).
void BM_DynamicTreePairStep(benchmark::State& state) {
  const Field field(state.range(0));
  std::vector<std::int32_t> proxies;
  DynamicTree tree = buildTree(field, proxies);
  PairFinder finder;
  PersistentPairs persistent;
  std::vector<ProxyPair> found;
  finder.findPairs(tree, proxies, acceptAll, found);
  persistent.update(tree, found, proxies);
  std::vector<std::int32_t> moved;
  std::int64_t step = 0;
  std::int64_t reinserted = 0;
  for (auto _ : state) {
    ++step;
    const Real time = kTimeStep * static_cast<Real>(step);
    const Real previous = time - kTimeStep * kMovedShare;
    moved.clear();
    for (std::size_t i = step % kMovedShare; i < field.size(); i += kMovedShare) {
      const Vec3 displacement = field.center(i, time) - field.center(i, previous);
      if (tree.moveProxy(proxies[i], field.box(i, time), displacement)) moved.push_back(proxies[i]);
    }
    reinserted += static_cast<std::int64_t>(moved.size());
    finder.findPairs(tree, moved, acceptAll, found);
    persistent.update(tree, found, moved);
    benchmark::DoNotOptimize(persistent.pairs().data());
  }
  state.counters["pairs"] = static_cast<double>(persistent.pairs().size());
  state.counters["reinserted"] =
      static_cast<double>(reinserted) / static_cast<double>(state.iterations());
}

// The same motion; every pair of fat boxes tested.
void BM_BruteForcePairStep(benchmark::State& state) {
  const Field field(state.range(0));
  std::vector<Aabb> boxes;
  for (std::size_t i = 0; i < field.size(); ++i) boxes.push_back(field.box(i, 0.0).grown(kMargin));
  std::vector<ProxyPair> pairs;
  std::int64_t step = 0;
  for (auto _ : state) {
    ++step;
    const Real time = kTimeStep * static_cast<Real>(step);
    for (std::size_t i = step % kMovedShare; i < field.size(); i += kMovedShare) {
      boxes[i] = field.box(i, time).grown(kMargin);
    }
    pairs.clear();
    for (std::size_t i = 0; i < boxes.size(); ++i) {
      for (std::size_t j = i + 1; j < boxes.size(); ++j) {
        if (boxes[i].overlaps(boxes[j])) {
          pairs.push_back({static_cast<std::int32_t>(i), static_cast<std::int32_t>(j)});
        }
      }
    }
    benchmark::DoNotOptimize(pairs.data());
  }
  state.counters["pairs"] = static_cast<double>(pairs.size());
}

// Closest-hit rays across the field, 256 per iteration. Arguments: proxy count, 1 to rebuild the
// tree first.
void BM_DynamicTreeRayCast(benchmark::State& state) {
  Field field(state.range(0));
  std::vector<std::int32_t> proxies;
  DynamicTree tree = buildTree(field, proxies);
  if (state.range(1) != 0) tree.rebuild();
  constexpr int kRays = 256;
  std::vector<Vec3> origins;
  std::vector<Vec3> directions;
  const Real half = field.halfSide();
  for (int r = 0; r < kRays; ++r) {
    origins.emplace_back(field.uniform(-half, half), field.uniform(-half, half),
                         field.uniform(-half, half));
    Vec3 d;
    do {
      d = Vec3(field.uniform(-1.0, 1.0), field.uniform(-1.0, 1.0), field.uniform(-1.0, 1.0));
    } while (d.norm() < 0.1 || d.norm() > 1.0);
    directions.push_back(d.normalized());
  }
  std::int64_t hits = 0;
  for (auto _ : state) {
    for (int r = 0; r < kRays; ++r) {
      const RaySegment ray(origins[r], directions[r]);
      std::int32_t closest = DynamicTree::kNull;
      tree.rayCast(origins[r], directions[r], 4.0 * half,
                   [&](const std::int32_t proxy, const Real max_t) {
                     Real entry = 0.0;
                     ray.enters(tree.fatAabb(proxy), max_t, entry);
                     closest = proxy;
                     return entry > 0.0 ? entry : 0.0;
                   });
      hits += closest != DynamicTree::kNull;
    }
  }
  state.SetItemsProcessed(state.iterations() * kRays);
  state.counters["hit_share"] =
      static_cast<double>(hits) / static_cast<double>(state.iterations() * kRays);
}

BENCHMARK(BM_DynamicTreeBuild)
    ->Args({1000, 0})
    ->Args({1000, 1})
    ->Args({10000, 0})
    ->Args({10000, 1})
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_DynamicTreePairStep)->Arg(1000)->Arg(10000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_BruteForcePairStep)->Arg(1000)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_DynamicTreeRayCast)->Args({10000, 0})->Args({10000, 1})->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
