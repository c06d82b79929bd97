#include "engine/solver/link_blocks.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "engine/solver/contact.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

constexpr std::uint32_t kAnchor = kNoParticle;

// A movable link row between knots a and b (kAnchor: anchored at its other end).
ParticleRow linkRow(const std::uint32_t a, const std::uint32_t b,
                    const ContactKind kind = ContactKind::kRod) {
  ParticleRow row{};
  row.a = BodyRef::particle(a);
  row.b = BodyRef::particle(b == kAnchor ? a : b);
  row.kind = kind;
  row.flags = static_cast<std::uint8_t>(RowFlags::kMovable | RowFlags::kActive | RowFlags::kSwept |
                                        (b == kAnchor ? 0 : RowFlags::kHasB));
  return row;
}

// Each block's rows, sorted.
std::vector<std::vector<std::uint32_t>> build(LinkBlocks& blocks, std::vector<ParticleRow>& rows,
                                              const std::vector<Real>& w) {
  blocks.build(rows.data(), rows.size(), w.data(), w.size());
  std::vector<std::vector<std::uint32_t>> found;
  for (std::size_t c = 0; c < blocks.size(); ++c) {
    found.emplace_back();
    for (std::size_t e = blocks.begin(c); e < blocks.end(c); ++e) {
      found.back().push_back(blocks.row(e));
    }
    std::sort(found.back().begin(), found.back().end());
  }
  return found;
}

TEST(LinkBlocks, AnAnchoredRopeIsOneBandedBlockOfWidthOne) {
  // Rows listed out of order, as the solver's height buckets leave them.
  std::vector<ParticleRow> rows = {linkRow(1, 2), linkRow(0, kAnchor), linkRow(2, 3),
                                   linkRow(0, 1)};
  LinkBlocks blocks;
  const auto found = build(blocks, rows, std::vector<Real>(4, 1.0));
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0], (std::vector<std::uint32_t>{0, 1, 2, 3}));
  EXPECT_EQ(blocks.bandwidth(0), 1u);
  for (const ParticleRow& row : rows) {
    EXPECT_TRUE(row.flags & RowFlags::kInBlock);
    EXPECT_FALSE(row.flags & RowFlags::kSwept);  // the velocity sweep leaves it to the block
  }
  // Three shared knots; knot 0 is side a of both its rows (+1 +1), knot 1 side b of (0, 1) and
  // side a of (1, 2).
  ASSERT_EQ(blocks.couplingsEnd(0) - blocks.couplingsBegin(0), 3);
  for (const LinkBlocks::Coupling* k = blocks.couplingsBegin(0); k != blocks.couplingsEnd(0); ++k) {
    EXPECT_EQ(k->second - k->first, 1u);
    EXPECT_EQ(k->sign, k->knot == 0 ? 1.0 : -1.0) << k->knot;
  }
}

TEST(LinkBlocks, EachBlockListsItsMovingKnotsOnce) {
  // Tied between two anchors: three rows, two moving knots.
  std::vector<ParticleRow> rows = {linkRow(0, kAnchor), linkRow(0, 1), linkRow(1, kAnchor)};
  LinkBlocks blocks;
  ASSERT_EQ(build(blocks, rows, std::vector<Real>(2, 1.0)).size(), 1u);
  std::vector<std::uint32_t> knots(blocks.knotsBegin(0), blocks.knotsEnd(0));
  std::sort(knots.begin(), knots.end());
  EXPECT_EQ(knots, (std::vector<std::uint32_t>{0, 1}));
  // A fixed knot (w = 0) is listed by neither block it splits.
  rows = {linkRow(0, 1), linkRow(1, 2), linkRow(2, 3), linkRow(3, 4)};
  std::vector<Real> w(5, 1.0);
  w[2] = 0.0;
  ASSERT_EQ(build(blocks, rows, w).size(), 2u);
  for (std::size_t c = 0; c < 2; ++c) {
    EXPECT_EQ(blocks.knotsEnd(c) - blocks.knotsBegin(c), 2) << c;
    EXPECT_EQ(std::count(blocks.knotsBegin(c), blocks.knotsEnd(c), 2u), 0) << c;
  }
}

TEST(LinkBlocks, JunctionsLoopsAndLaddersAreOneBlockFixedKnotsSplit) {
  LinkBlocks blocks;
  {
    // A Y: three arms of two rows meet at knot 0, three rows sharing it.
    std::vector<ParticleRow> rows = {linkRow(0, 1), linkRow(1, 2), linkRow(0, 3),
                                     linkRow(3, 4), linkRow(0, 5), linkRow(5, 6)};
    const auto found = build(blocks, rows, std::vector<Real>(7, 1.0));
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0].size(), 6u);
    EXPECT_LE(blocks.bandwidth(0), 3u);
  }
  {
    // A closed loop of four.
    std::vector<ParticleRow> rows = {linkRow(0, 1), linkRow(1, 2), linkRow(2, 3), linkRow(3, 0)};
    const auto found = build(blocks, rows, std::vector<Real>(4, 1.0));
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0].size(), 4u);
    EXPECT_EQ(blocks.bandwidth(0), 2u);
  }
  {
    // A ladder of ten rungs: two rails of nine rows, ten rungs; the band stays narrow.
    std::vector<ParticleRow> rows;
    for (std::uint32_t i = 0; i + 1 < 10; ++i) {
      rows.push_back(linkRow(2 * i, 2 * i + 2));
      rows.push_back(linkRow(2 * i + 1, 2 * i + 3));
    }
    for (std::uint32_t i = 0; i < 10; ++i) rows.push_back(linkRow(2 * i, 2 * i + 1));
    const auto found = build(blocks, rows, std::vector<Real>(20, 1.0));
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0].size(), 28u);
    EXPECT_LE(blocks.bandwidth(0), 5u);
  }
  {
    // A fixed knot (w = 0) in the middle: two blocks, nothing coupled through it.
    std::vector<ParticleRow> rows = {linkRow(0, 1), linkRow(1, 2), linkRow(2, 3), linkRow(3, 4)};
    std::vector<Real> w(5, 1.0);
    w[2] = 0.0;
    const auto found = build(blocks, rows, w);
    ASSERT_EQ(found.size(), 2u);
    EXPECT_EQ(found[0], (std::vector<std::uint32_t>{0, 1}));
    EXPECT_EQ(found[1], (std::vector<std::uint32_t>{2, 3}));
  }
  {
    // Two links between the same two knots couple through both; a lone link is no block.
    std::vector<ParticleRow> rows = {linkRow(0, 1), linkRow(1, 0), linkRow(2, 3)};
    const auto found = build(blocks, rows, std::vector<Real>(4, 1.0));
    ASSERT_EQ(found.size(), 1u);
    EXPECT_EQ(found[0], (std::vector<std::uint32_t>{0, 1}));
    EXPECT_EQ(blocks.couplingsEnd(0) - blocks.couplingsBegin(0), 2);
    EXPECT_FALSE(rows[2].flags & RowFlags::kInBlock);
  }
  {
    // Contacts and rows that cannot move are never in a block.
    std::vector<ParticleRow> rows = {linkRow(0, 1), linkRow(1, 2, ContactKind::kContact),
                                     linkRow(1, 2)};
    rows[2].flags &= static_cast<std::uint8_t>(~RowFlags::kMovable);
    EXPECT_TRUE(build(blocks, rows, std::vector<Real>(3, 1.0)).empty());
  }
  {
    // A hub: one knot in 20 links couples them all, wider than the band: left to the passes.
    std::vector<ParticleRow> rows;
    for (std::uint32_t i = 1; i <= 20; ++i) rows.push_back(linkRow(0, i));
    EXPECT_TRUE(build(blocks, rows, std::vector<Real>(21, 1.0)).empty());
    for (const ParticleRow& row : rows) EXPECT_FALSE(row.flags & RowFlags::kInBlock);
  }
}

// Block 0's K as the caller fills it, with random values (diagonally dominant).
Eigen::MatrixXd fillRandom(LinkBlocks& blocks, std::mt19937& rng) {
  std::uniform_real_distribution<Real> unit(-1.0, 1.0);
  const std::size_t s = blocks.begin(0);
  const auto n = static_cast<Eigen::Index>(blocks.end(0) - s);
  Eigen::MatrixXd k = Eigen::MatrixXd::Zero(n, n);
  blocks.clearCouplings(0);
  for (const LinkBlocks::Coupling* c = blocks.couplingsBegin(0); c != blocks.couplingsEnd(0); ++c) {
    const Real value = 0.4 * unit(rng);
    blocks.addCoupling(0, *c, value);
    k(c->first - s, c->second - s) += value;
    k(c->second - s, c->first - s) += value;
  }
  for (Eigen::Index i = 0; i < n; ++i) {
    blocks.diagonal[s + i] = 4.0 + unit(rng);
    blocks.least[s + i] = 1.0;
    k(i, i) = blocks.diagonal[s + i];
    blocks.rhs[s + i] = unit(rng);
    blocks.held[s + i] = 0.0;
    blocks.bounded[s + i] = 0;
  }
  return k;
}

TEST(LinkBlocks, TheBlockSolvesKExactly) {
  std::mt19937 rng(7);
  LinkBlocks blocks;
  // A rope, a ring and a ladder.
  std::vector<std::vector<ParticleRow>> shapes(3);
  shapes[0].push_back(linkRow(0, kAnchor));
  for (std::uint32_t i = 1; i < 40; ++i) shapes[0].push_back(linkRow(i - 1, i));
  for (std::uint32_t i = 0; i < 12; ++i) shapes[1].push_back(linkRow(i, (i + 1) % 12));
  for (std::uint32_t i = 0; i + 1 < 8; ++i) {
    shapes[2].push_back(linkRow(2 * i, 2 * i + 2));
    shapes[2].push_back(linkRow(2 * i + 1, 2 * i + 3));
    shapes[2].push_back(linkRow(2 * i, 2 * i + 3));
  }
  for (std::uint32_t i = 0; i < 8; ++i) shapes[2].push_back(linkRow(2 * i, 2 * i + 1));
  for (std::vector<ParticleRow>& rows : shapes) {
    blocks.build(rows.data(), rows.size(), std::vector<Real>(40, 1.0).data(), 40);
    ASSERT_EQ(blocks.size(), 1u);
    const Eigen::MatrixXd k = fillRandom(blocks, rng);
    const auto n = k.rows();
    const Eigen::VectorXd b = Eigen::Map<const Eigen::VectorXd>(&blocks.rhs[blocks.begin(0)], n);
    const Eigen::VectorXd expected = k.ldlt().solve(b);
    ASSERT_TRUE(blocks.factorKept(0));
    std::vector<Real> x(b.data(), b.data() + n);
    blocks.solveKept(0, x.data());
    ASSERT_TRUE(blocks.solveBounded(0));
    for (Eigen::Index i = 0; i < n; ++i) {
      EXPECT_NEAR(x[i], expected(i), 1e-12) << n << " " << i;
      EXPECT_NEAR(blocks.rhs[blocks.begin(0) + i], expected(i), 1e-12) << n << " " << i;
    }
  }
}

TEST(LinkBlocks, ABoundedEntryThatWouldCrossIsHeldAtItsBound) {
  // A rod, a cable and a rod from an anchor: K = [[2, -1, 0], [-1, 2, -1], [0, -1, 2]],
  // r = (1, -3, 1). Unbounded, dl = (-0.5, -2, -0.5) takes the cable's total 0.1 below 0; held
  // at 0 (dl = -0.1), its coupling moves to its neighbours: 2 dl = 1 - 0.1 for each.
  LinkBlocks blocks;
  std::vector<ParticleRow> rows = {linkRow(0, kAnchor), linkRow(0, 1, ContactKind::kCable),
                                   linkRow(1, 2)};
  blocks.build(rows.data(), rows.size(), std::vector<Real>(3, 1.0).data(), 3);
  ASSERT_EQ(blocks.size(), 1u);
  std::vector<std::size_t> entry(3);
  for (std::size_t e = blocks.begin(0); e < blocks.end(0); ++e) entry[blocks.row(e)] = e;
  const Real rhs[3] = {1.0, -3.0, 1.0};
  const auto fill = [&](const bool bound) {
    blocks.clearCouplings(0);
    for (const LinkBlocks::Coupling* k = blocks.couplingsBegin(0); k != blocks.couplingsEnd(0);
         ++k) {
      blocks.addCoupling(0, *k, -1.0);
    }
    for (std::size_t r = 0; r < 3; ++r) {
      blocks.diagonal[entry[r]] = 2.0;
      blocks.least[entry[r]] = 1.0;
      blocks.least[entry[r]] = 1.0;
      blocks.rhs[entry[r]] = rhs[r];
      blocks.held[entry[r]] = r == 1 ? 0.1 : 0.0;
      blocks.bounded[entry[r]] = bound && r == 1;
    }
  };
  fill(true);
  ASSERT_TRUE(blocks.solveBounded(0));
  EXPECT_DOUBLE_EQ(blocks.rhs[entry[1]], -0.1);
  EXPECT_DOUBLE_EQ(blocks.rhs[entry[0]], 0.45);
  EXPECT_DOUBLE_EQ(blocks.rhs[entry[2]], 0.45);
  fill(false);
  ASSERT_TRUE(blocks.solveBounded(0));
  EXPECT_NEAR(blocks.rhs[entry[1]], -2.0, 1e-15);
  EXPECT_NEAR(blocks.rhs[entry[0]], -0.5, 1e-15);
}

TEST(LinkBlocks, AHeldEntryIsLetGoWhenItsConstraintIsViolated) {
  // Two cables, K = [[2, -1], [-1, 2]], r = (-3, 1), nothing held: unbounded both would push
  // (dl = (-5/3, -1/3)), so both are held at 0; then the second's constraint is violated with no
  // impulse ((K dl - r)_1 = -1 < 0) and it is let go: 2 dl_1 = 1, dl = (0, 0.5), and the first
  // stays held ((K dl - r)_0 = 2.5 >= 0).
  LinkBlocks blocks;
  std::vector<ParticleRow> rows = {linkRow(0, 1, ContactKind::kCable),
                                   linkRow(1, 2, ContactKind::kCable)};
  blocks.build(rows.data(), rows.size(), std::vector<Real>(3, 1.0).data(), 3);
  ASSERT_EQ(blocks.size(), 1u);
  std::vector<std::size_t> entry(2);
  for (std::size_t e = blocks.begin(0); e < blocks.end(0); ++e) entry[blocks.row(e)] = e;
  blocks.clearCouplings(0);
  blocks.addCoupling(0, *blocks.couplingsBegin(0), -1.0);
  const Real rhs[2] = {-3.0, 1.0};
  for (std::size_t r = 0; r < 2; ++r) {
    blocks.diagonal[entry[r]] = 2.0;
    blocks.least[entry[r]] = 1.0;
    blocks.rhs[entry[r]] = rhs[r];
    blocks.held[entry[r]] = 0.0;
    blocks.bounded[entry[r]] = 1;
  }
  ASSERT_TRUE(blocks.solveBounded(0));
  EXPECT_EQ(blocks.rhs[entry[0]], 0.0);
  EXPECT_DOUBLE_EQ(blocks.rhs[entry[1]], 0.5);
}

TEST(LinkBlocks, ASingularBlockIsRefused) {
  LinkBlocks blocks;
  std::vector<ParticleRow> rows = {linkRow(0, 1), linkRow(1, 2)};
  blocks.build(rows.data(), rows.size(), std::vector<Real>(3, 1.0).data(), 3);
  ASSERT_EQ(blocks.size(), 1u);
  // [[1, 1], [1, 1]]: two links folded onto one line through a knot that cannot take both.
  blocks.clearCouplings(0);
  blocks.addCoupling(0, *blocks.couplingsBegin(0), 1.0);
  for (std::size_t e = 0; e < 2; ++e) {
    blocks.diagonal[e] = 1.0;
    blocks.least[e] = 1.0;
    blocks.rhs[e] = 1.0;
    blocks.held[e] = 0.0;
    blocks.bounded[e] = 0;
  }
  EXPECT_FALSE(blocks.factorKept(0));
  EXPECT_FALSE(blocks.solveBounded(0));
}

// Pivots are measured against the least mobility of their entry's ends: two links nearly in line
// between ends that cannot give (a taut rail) leave a pivot of 1e-4 of it and go row by row; a
// heavy knot hung from a light one (w 1e-6 and 1) leaves 1e-6 of the diagonal, its own scale.
TEST(LinkBlocks, ANearlySingularBlockIsRefusedAHeavyEndIsNot) {
  LinkBlocks blocks;
  std::vector<ParticleRow> rows = {linkRow(0, 1), linkRow(1, 2)};
  blocks.build(rows.data(), rows.size(), std::vector<Real>(3, 1.0).data(), 3);
  ASSERT_EQ(blocks.size(), 1u);
  const auto fill = [&](const Real coupling, const Real second_diagonal, const Real second_least) {
    blocks.clearCouplings(0);
    blocks.addCoupling(0, *blocks.couplingsBegin(0), coupling);
    for (std::size_t e = 0; e < 2; ++e) {
      blocks.diagonal[e] = e == 0 ? 1.0 : second_diagonal;
      blocks.least[e] = e == 0 ? 1.0 : second_least;
      blocks.rhs[e] = 1.0;
      blocks.held[e] = 0.0;
      blocks.bounded[e] = 0;
    }
  };
  fill(std::sqrt(1.0 - 1e-4), 1.0, 1.0);
  EXPECT_FALSE(blocks.factorKept(0));
  fill(1.0, 1.0 + 1e-6, 1e-6);
  EXPECT_TRUE(blocks.factorKept(0));
  EXPECT_TRUE(blocks.solveBounded(0));
}

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
