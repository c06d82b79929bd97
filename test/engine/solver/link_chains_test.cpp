#include "engine/solver/link_chains.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
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

struct Found {
  std::vector<std::vector<std::uint32_t>> chains;  // rows, in chain order
};

Found build(LinkChains& chains, std::vector<ParticleRow>& rows, const std::vector<Real>& w) {
  chains.build(rows.data(), rows.size(), w.data(), w.size());
  Found found;
  for (std::size_t c = 0; c < chains.size(); ++c) {
    found.chains.emplace_back();
    for (std::size_t e = chains.begin(c); e < chains.end(c); ++e) {
      found.chains.back().push_back(chains.row(e));
    }
  }
  return found;
}

TEST(LinkChains, AnAnchoredRopeIsOneChainFromTheAnchorOut) {
  // Rows listed out of order, as the solver's height buckets leave them.
  std::vector<ParticleRow> rows = {linkRow(1, 2), linkRow(0, kAnchor), linkRow(2, 3),
                                   linkRow(0, 1)};
  const std::vector<Real> w(4, 1.0);
  LinkChains chains;
  const Found found = build(chains, rows, w);
  ASSERT_EQ(found.chains.size(), 1u);
  EXPECT_EQ(found.chains[0], (std::vector<std::uint32_t>{1, 3, 0, 2}));
  for (const ParticleRow& row : rows) {
    EXPECT_TRUE(row.flags & RowFlags::kChained);
    EXPECT_FALSE(row.flags & RowFlags::kSwept);  // the velocity sweep leaves it to the chain
  }
  // Knot 0 is side a of both its rows (+1 +1); knot 1 is side b of (0, 1), side a of (1, 2).
  const std::size_t e = chains.begin(0);
  EXPECT_EQ(chains.sharedKnot(e), 0u);
  EXPECT_EQ(chains.sharedSign(e), 1.0);
  EXPECT_EQ(chains.sharedKnot(e + 1), 1u);
  EXPECT_EQ(chains.sharedSign(e + 1), -1.0);
  EXPECT_FALSE(chains.heldAtBothEnds(0));  // knot 3 is a free end
}

TEST(LinkChains, AChainTiedAtBothEndsIsHeldAtBothEnds) {
  LinkChains chains;
  {
    // Anchored at both ends (a rope tied between two points).
    std::vector<ParticleRow> rows = {linkRow(0, kAnchor), linkRow(0, 1), linkRow(1, 2),
                                     linkRow(2, kAnchor)};
    ASSERT_EQ(build(chains, rows, std::vector<Real>(3, 1.0)).chains.size(), 1u);
    EXPECT_TRUE(chains.heldAtBothEnds(0));
  }
  {
    // From an anchor to a fixed knot, and from that knot to a free end.
    std::vector<ParticleRow> rows = {linkRow(0, kAnchor), linkRow(0, 1), linkRow(1, 2),
                                     linkRow(2, 3), linkRow(3, 4)};
    std::vector<Real> w(5, 1.0);
    w[2] = 0.0;
    const Found found = build(chains, rows, w);
    ASSERT_EQ(found.chains.size(), 2u);
    for (std::size_t c = 0; c < 2; ++c) {
      const bool to_the_free_end =
          std::find(found.chains[c].begin(), found.chains[c].end(), 4u) != found.chains[c].end();
      EXPECT_EQ(chains.heldAtBothEnds(c), !to_the_free_end) << c;
    }
  }
  {
    // Between two junctions: its ends move.
    std::vector<ParticleRow> rows = {linkRow(0, 1),       linkRow(1, 2),       linkRow(2, 3),
                                     linkRow(0, kAnchor), linkRow(0, kAnchor), linkRow(3, kAnchor),
                                     linkRow(3, kAnchor)};
    ASSERT_EQ(build(chains, rows, std::vector<Real>(4, 1.0)).chains.size(), 1u);
    EXPECT_FALSE(chains.heldAtBothEnds(0));
  }
}

TEST(LinkChains, JunctionsFixedKnotsAndLoopsEndChains) {
  LinkChains chains;
  {
    // A Y: three arms of two rows meet at knot 0.
    std::vector<ParticleRow> rows = {linkRow(0, 1), linkRow(1, 2), linkRow(0, 3),
                                     linkRow(3, 4), linkRow(0, 5), linkRow(5, 6)};
    const Found found = build(chains, rows, std::vector<Real>(7, 1.0));
    ASSERT_EQ(found.chains.size(), 3u);
    for (const auto& chain : found.chains) EXPECT_EQ(chain.size(), 2u);
  }
  {
    // A fixed knot (w = 0) in the middle: two chains, neither through it.
    std::vector<ParticleRow> rows = {linkRow(0, 1), linkRow(1, 2), linkRow(2, 3), linkRow(3, 4)};
    std::vector<Real> w(5, 1.0);
    w[2] = 0.0;
    const Found found = build(chains, rows, w);
    ASSERT_EQ(found.chains.size(), 2u);
    EXPECT_EQ(found.chains[0], (std::vector<std::uint32_t>{0, 1}));
    EXPECT_EQ(found.chains[1], (std::vector<std::uint32_t>{2, 3}));
  }
  {
    // A closed loop of four: a chain of three, the fourth left to the passes.
    std::vector<ParticleRow> rows = {linkRow(0, 1), linkRow(1, 2), linkRow(2, 3), linkRow(3, 0)};
    const Found found = build(chains, rows, std::vector<Real>(4, 1.0));
    ASSERT_EQ(found.chains.size(), 1u);
    EXPECT_EQ(found.chains[0].size(), 3u);
    EXPECT_FALSE(rows[3].flags & RowFlags::kChained);
  }
  {
    // Two links between the same two knots, and a lone link: no chain.
    std::vector<ParticleRow> rows = {linkRow(0, 1), linkRow(1, 0), linkRow(2, 3)};
    const Found found = build(chains, rows, std::vector<Real>(4, 1.0));
    EXPECT_TRUE(found.chains.empty());
    for (const ParticleRow& row : rows) EXPECT_FALSE(row.flags & RowFlags::kChained);
  }
  {
    // Contacts and rows that cannot move are never in a chain.
    std::vector<ParticleRow> rows = {linkRow(0, 1), linkRow(1, 2, ContactKind::kContact),
                                     linkRow(1, 2)};
    rows[2].flags &= static_cast<std::uint8_t>(~RowFlags::kMovable);
    const Found found = build(chains, rows, std::vector<Real>(3, 1.0));
    EXPECT_TRUE(found.chains.empty());
  }
}

// A chain of n rows with random coupling: K as the caller fills it.
void randomChain(LinkChains& chains, std::vector<ParticleRow>& rows, const int n,
                 std::mt19937& rng) {
  rows.clear();
  rows.push_back(linkRow(0, kAnchor));
  for (int i = 1; i < n; ++i) {
    rows.push_back(linkRow(static_cast<std::uint32_t>(i - 1), static_cast<std::uint32_t>(i)));
  }
  chains.build(rows.data(), rows.size(), std::vector<Real>(n, 1.0).data(), n);
  std::uniform_real_distribution<Real> unit(-1.0, 1.0);
  for (std::size_t e = chains.begin(0); e < chains.end(0); ++e) {
    chains.diagonal[e] = 2.0 + 0.5 * unit(rng);
    chains.coupling[e] = e + 1 < chains.end(0) ? 0.9 * unit(rng) : 0.0;
    chains.rhs[e] = unit(rng);
    chains.held[e] = 0.0;
    chains.bounded[e] = 0;
  }
}

Eigen::MatrixXd dense(const LinkChains& chains) {
  const auto n = static_cast<Eigen::Index>(chains.end(0) - chains.begin(0));
  Eigen::MatrixXd k = Eigen::MatrixXd::Zero(n, n);
  for (Eigen::Index i = 0; i < n; ++i) {
    k(i, i) = chains.diagonal[chains.begin(0) + i];
    if (i + 1 < n) k(i, i + 1) = k(i + 1, i) = chains.coupling[chains.begin(0) + i];
  }
  return k;
}

TEST(LinkChains, TheBlockSolvesKExactly) {
  std::mt19937 rng(7);
  LinkChains chains;
  std::vector<ParticleRow> rows;
  for (const int n : {2, 5, 40}) {
    randomChain(chains, rows, n, rng);
    const Eigen::MatrixXd k = dense(chains);
    const Eigen::VectorXd b = Eigen::Map<const Eigen::VectorXd>(&chains.rhs[0], n);
    const Eigen::VectorXd expected = k.ldlt().solve(b);
    ASSERT_TRUE(chains.factorKept(0));
    std::vector<Real> x(chains.rhs.begin(), chains.rhs.begin() + n);
    chains.solveKept(0, x.data());
    ASSERT_TRUE(chains.solveBounded(0));
    for (int i = 0; i < n; ++i) {
      EXPECT_NEAR(x[i], expected(i), 1e-12) << n << " " << i;
      EXPECT_NEAR(chains.rhs[i], expected(i), 1e-12) << n << " " << i;
    }
  }
}

TEST(LinkChains, ABoundedEntryThatWouldCrossIsHeldAtItsBound) {
  // K dl = r for a rod, a cable and a rod: the cable would be pushed (its total 0.1 + dl < 0);
  // held at 0, its coupling moves to its neighbours' right-hand sides and they are solved again.
  LinkChains chains;
  std::vector<ParticleRow> rows = {linkRow(0, kAnchor), linkRow(0, 1), linkRow(1, 2)};
  chains.build(rows.data(), rows.size(), std::vector<Real>(3, 1.0).data(), 3);
  ASSERT_EQ(chains.size(), 1u);
  const Real diagonal[3] = {2.0, 2.0, 2.0};
  const Real coupling[3] = {-1.0, -1.0, 0.0};
  const Real rhs[3] = {1.0, -3.0, 1.0};
  for (int i = 0; i < 3; ++i) {
    chains.diagonal[i] = diagonal[i];
    chains.coupling[i] = coupling[i];
    chains.rhs[i] = rhs[i];
    chains.held[i] = i == 1 ? 0.1 : 0.0;
    chains.bounded[i] = i == 1;
  }
  ASSERT_TRUE(chains.solveBounded(0));
  // dl_1 = -0.1; 2 dl_0 = 1 - (-1)(-0.1) = 0.9; 2 dl_2 = 1 - 0.1 = 0.9.
  EXPECT_DOUBLE_EQ(chains.rhs[1], -0.1);
  EXPECT_DOUBLE_EQ(chains.rhs[0], 0.45);
  EXPECT_DOUBLE_EQ(chains.rhs[2], 0.45);
  // Unbounded, the cable's total would go below 0: dl = (-0.5, -2, -0.5).
  for (int i = 0; i < 3; ++i) {
    chains.rhs[i] = rhs[i];
    chains.bounded[i] = 0;
  }
  ASSERT_TRUE(chains.solveBounded(0));
  EXPECT_NEAR(chains.rhs[1], -2.0, 1e-15);
  EXPECT_NEAR(chains.rhs[0], -0.5, 1e-15);
}

TEST(LinkChains, AHeldEntryIsLetGoWhenItsConstraintIsViolated) {
  // Two cables, K = [[2, -1], [-1, 2]], r = (-3, 1), nothing held: unbounded both would push
  // (dl = (-5/3, -1/3)), so both are held at 0; then the second's constraint is violated with no
  // impulse ((K dl - r)_1 = -1 < 0) and it is let go: 2 dl_1 = 1, dl = (0, 0.5), while the first
  // stays held ((K dl - r)_0 = 2.5 >= 0).
  LinkChains chains;
  std::vector<ParticleRow> rows = {linkRow(0, 1, ContactKind::kCable),
                                   linkRow(1, 2, ContactKind::kCable)};
  chains.build(rows.data(), rows.size(), std::vector<Real>(3, 1.0).data(), 3);
  ASSERT_EQ(chains.size(), 1u);
  const std::size_t first = chains.row(0) == 0 ? 0 : 1;
  const std::size_t second = 1 - first;
  chains.diagonal[0] = chains.diagonal[1] = 2.0;
  chains.coupling[0] = -1.0;
  chains.rhs[first] = -3.0;
  chains.rhs[second] = 1.0;
  chains.held[0] = chains.held[1] = 0.0;
  chains.bounded[0] = chains.bounded[1] = 1;
  ASSERT_TRUE(chains.solveBounded(0));
  EXPECT_EQ(chains.rhs[first], 0.0);
  EXPECT_DOUBLE_EQ(chains.rhs[second], 0.5);
}

TEST(LinkChains, ASingularBlockIsRefused) {
  LinkChains chains;
  std::vector<ParticleRow> rows = {linkRow(0, 1), linkRow(1, 2)};
  chains.build(rows.data(), rows.size(), std::vector<Real>(3, 1.0).data(), 3);
  ASSERT_EQ(chains.size(), 1u);
  // [[1, 1], [1, 1]]: two links folded onto one line through a knot that cannot take both.
  chains.diagonal[0] = chains.diagonal[1] = 1.0;
  chains.coupling[0] = 1.0;
  chains.rhs[0] = chains.rhs[1] = 1.0;
  chains.held[0] = chains.held[1] = 0.0;
  chains.bounded[0] = chains.bounded[1] = 0;
  EXPECT_FALSE(chains.factorKept(0));
  EXPECT_FALSE(chains.solveBounded(0));
}

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
