// The contact response decides whether a contact with one moving side rests (restingOneSide) from
// squares where they are clearly apart, to skip a square root. It must answer what the square
// root answers, in the scalar instance and in every lane of the four-wide one, on random values
// and on the awkward ones: on the boundary to the last bit, zero, tiny, huge, inf, NaN.
#include "engine/solver/contact_response.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace mass_aggregate_sim {
namespace engine {
namespace {

using simd::Real4;

TEST(ContactResponse, RestingByItsSquaresAnswersAsTheRoot) {
  const Real inf = std::numeric_limits<Real>::infinity();
  const Real nan = std::numeric_limits<Real>::quiet_NaN();
  const Real h = 1.0 / 240.0;
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<Real> unit(0.0, 1.0);
  std::vector<std::pair<Real, Real>> cases;  // closing less built, s = |a|^2
  for (int round = 0; round < 2000; ++round) {
    const Real s = std::pow(10.0, -280.0 + 560.0 * unit(rng));
    const Real boundary = -2.0 * std::sqrt(s) * h;
    for (const Real nudge : {0.0, 1e-16, -1e-16, 1e-9, -1e-9, 3e-9, -3e-9, 0.5, -0.5}) {
      const Real closing = boundary * (1.0 + nudge);
      cases.emplace_back(closing, s);
      cases.emplace_back(std::nextafter(closing, inf), s);
      cases.emplace_back(std::nextafter(closing, -inf), s);
    }
  }
  for (const Real closing : {0.0, -0.0, 1.0, -1.0, -inf, inf, nan}) {
    for (const Real s : {0.0, 1e-300, 96.0, 1e300, inf, nan}) cases.emplace_back(closing, s);
  }
  for (const auto& [closing, s] : cases) {
    const bool expected = response::resting(closing, std::sqrt(s), h);
    ASSERT_EQ(response::restingOneSide(closing, s, h), expected) << closing << " " << s;
  }
  for (std::size_t first = 0; first + 4 <= cases.size(); first += 3) {
    Real4 closing;
    Real4 s;
    for (int lane = 0; lane < 4; ++lane) {
      closing[lane] = cases[first + static_cast<std::size_t>(lane)].first;
      s[lane] = cases[first + static_cast<std::size_t>(lane)].second;
    }
    const simd::Mask4 lanes = response::restingOneSide(closing, s, h);
    for (int lane = 0; lane < 4; ++lane) {
      const bool expected = response::resting(closing[lane], std::sqrt(s[lane]), h);
      ASSERT_EQ(lanes[lane] != 0, expected) << "case " << first + lane;
    }
  }
}

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
