#include "bandwidth_floor.h"

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <new>

// The Double4 helpers never cross a library boundary: the note that their calling convention
// depends on AVX does not apply.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wpsabi"
#endif

namespace mass_aggregate_sim {
namespace engine {
namespace bench {
namespace {

// Four doubles as one value (GCC and Clang vector extensions); four particles' xyz are three of
// them: (x0 y0 z0 x1) (y1 z1 x2 y2) (z2 x3 y3 z3), and spreadN lines up the per-particle scalars
// with the Nth.
typedef double Double4 __attribute__((vector_size(32)));
typedef std::int64_t Mask4 __attribute__((vector_size(32)));

inline Double4 load(const double* p) {
  Double4 r;
  std::memcpy(&r, p, sizeof r);
  return r;
}
inline void store(double* p, const Double4 value) { std::memcpy(p, &value, sizeof value); }
inline Double4 spread0(const Double4 s) { return __builtin_shufflevector(s, s, 0, 0, 0, 1); }
inline Double4 spread1(const Double4 s) { return __builtin_shufflevector(s, s, 1, 1, 2, 2); }
inline Double4 spread2(const Double4 s) { return __builtin_shufflevector(s, s, 2, 3, 3, 3); }

constexpr double kH = 1.0 / 60.0;
constexpr double kGravityStep[3] = {0.0, -9.81 * kH, 0.0};  // g h
constexpr std::size_t kLine = 64;
// Each array starts this far past a page boundary plus its own multiple of it, so the streams do
// not alias in the 4 KiB-page address bits the load/store unit compares (5 to 8 % faster at
// 100,000 particles than arrays all at the same page offset, in a scratch comparison).
constexpr std::size_t kStagger = 17 * kLine;

// Eight particles per iteration (4 was up to 7 % slower at 100,000 particles in a scratch
// comparison, 16 no faster), the rest one at a time.
__attribute__((target_clones("avx2", "default"))) void floorPass(
    const std::size_t n, double* __restrict x, double* __restrict v,
    const double* __restrict inverse_mass, const double* __restrict damping) {
  const Double4 h = {kH, kH, kH, kH};
  const Double4 zero = {0.0, 0.0, 0.0, 0.0};
  const Double4 one = {1.0, 1.0, 1.0, 1.0};
  const double* g = kGravityStep;
  const Double4 gravity[3] = {
      {g[0], g[1], g[2], g[0]}, {g[1], g[2], g[0], g[1]}, {g[2], g[0], g[1], g[2]}};
  std::size_t i = 0;
  for (; i + 8 <= n; i += 8) {
    for (std::size_t group = i; group < i + 8; group += 4) {
      const Double4 movable = (Double4)((Mask4)(load(inverse_mass + group) > zero) & (Mask4)one);
      const Double4 d = load(damping + group);
      const Double4 m[3] = {spread0(movable), spread1(movable), spread2(movable)};
      const Double4 s[3] = {spread0(d), spread1(d), spread2(d)};
      for (int b = 0; b < 3; ++b) {
        const std::size_t k = 3 * group + 4 * static_cast<std::size_t>(b);
        const Double4 velocity = (load(v + k) + m[b] * gravity[b]) * s[b];
        store(v + k, velocity);
        store(x + k, load(x + k) + velocity * h);
      }
    }
  }
  for (; i < n; ++i) {
    const double movable = inverse_mass[i] > 0.0 ? 1.0 : 0.0;
    for (std::size_t c = 0; c < 3; ++c) {
      const std::size_t k = 3 * i + c;
      const double velocity = (v[k] + movable * g[c]) * damping[i];
      v[k] = velocity;
      x[k] += velocity * kH;
    }
  }
}

std::size_t roundUp(const std::size_t bytes) { return (bytes + kLine - 1) / kLine * kLine; }

}  // namespace

void FloorArrays::Free::operator()(double* p) const { std::free(p); }

FloorArrays::FloorArrays(const std::size_t particles) : particles_(particles) {
  const std::size_t sizes[4] = {3 * particles * sizeof(double), 3 * particles * sizeof(double),
                                particles * sizeof(double), particles * sizeof(double)};
  std::size_t total = 0;
  for (const std::size_t bytes : sizes) total += roundUp(bytes) + 4 * kStagger + 4096;
  void* block = std::aligned_alloc(4096, (total + 4095) / 4096 * 4096);
  if (block == nullptr) throw std::bad_alloc();
  storage_.reset(static_cast<double*>(block));
  // Array k starts (k + 1) kStagger bytes past a page boundary.
  std::size_t offset = 0;
  double* arrays[4];
  for (std::size_t k = 0; k < 4; ++k) {
    const std::size_t start = offset + (k + 1) * kStagger;
    arrays[k] = reinterpret_cast<double*>(static_cast<char*>(block) + start);
    offset = (start + sizes[k] + 4095) / 4096 * 4096;
  }
  x_ = arrays[0];
  v_ = arrays[1];
  inverse_mass_ = arrays[2];
  damping_ = arrays[3];
  const double damping = std::pow(0.99, kH);
  for (std::size_t i = 0; i < 3 * particles; ++i) {
    x_[i] = 100.0;
    v_[i] = 0.0;
  }
  for (std::size_t i = 0; i < particles; ++i) {
    inverse_mass_[i] = 1.0;
    damping_[i] = damping;
  }
}

void FloorArrays::step() { floorPass(particles_, x_, v_, inverse_mass_, damping_); }

}  // namespace bench
}  // namespace engine
}  // namespace mass_aggregate_sim
