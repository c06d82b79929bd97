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

// Per spring (d_x^2 + d_y^2) + d_z^2 of four springs whose differences d are in the layout above.
inline Double4 squaredLengths(const Double4* d) {
  const Double4 sq[3] = {d[0] * d[0], d[1] * d[1], d[2] * d[2]};
  const Double4 x =
      __builtin_shufflevector(__builtin_shufflevector(sq[0], sq[1], 0, 3, 6, 1), sq[2], 0, 1, 2, 5);
  const Double4 y =
      __builtin_shufflevector(__builtin_shufflevector(sq[0], sq[1], 1, 4, 7, 0), sq[2], 0, 1, 2, 6);
  const Double4 z =
      __builtin_shufflevector(__builtin_shufflevector(sq[0], sq[1], 2, 5, 0, 0), sq[2], 0, 1, 4, 7);
  return (x + y) + z;
}

// Spring i pulls particle i by f_i = -k (l - L) d / l, d = x_i - x_(i+1), and particle i + 1 by
// -f_i: particle i feels f_i - f_(i-1). Four particles a group, each group's springs from the
// positions before the group moves (the next group's first particle has not moved yet), f_(i-1)
// carried over from the group before.
__attribute__((target_clones("avx2", "default"))) void springChainPass(
    const std::size_t n, double* __restrict x, double* __restrict v,
    const double* __restrict inverse_mass, const double* __restrict damping,
    const double* __restrict stiffness, const double* __restrict rest_length) {
  const Double4 h = {kH, kH, kH, kH};
  const double* g = kGravityStep;
  const Double4 gravity[3] = {
      {g[0], g[1], g[2], g[0]}, {g[1], g[2], g[0], g[1]}, {g[2], g[0], g[1], g[2]}};
  const Double4 zero = {0.0, 0.0, 0.0, 0.0};
  Double4 before = zero;  // the last group's f[2]: its lanes 1 to 3 are f_(i-1)
  std::size_t i = 0;
  // Two groups an iteration: 2.59 to 2.61 ns at 1,000 and 10,000 particles against 2.65 to 2.77
  // one at a time, in one scratch comparison.
#pragma GCC unroll 2
  for (; i + 4 <= n; i += 4) {
    Double4 d[3];
    for (int b = 0; b < 3; ++b) {
      const std::size_t k = 3 * i + 4 * static_cast<std::size_t>(b);
      d[b] = load(x + k) - load(x + k + 3);
    }
    const Double4 squared = squaredLengths(d);
    const Double4 length = {std::sqrt(squared[0]), std::sqrt(squared[1]), std::sqrt(squared[2]),
                            std::sqrt(squared[3])};
    const Double4 magnitude =
        -(load(stiffness + i) * (length - load(rest_length + i))) * (1.0 / length);
    const Double4 f[3] = {spread0(magnitude) * d[0], spread1(magnitude) * d[1],
                          spread2(magnitude) * d[2]};
    const Double4 earlier[3] = {__builtin_shufflevector(before, f[0], 1, 2, 3, 4),
                                __builtin_shufflevector(f[0], f[1], 1, 2, 3, 4),
                                __builtin_shufflevector(f[1], f[2], 1, 2, 3, 4)};
    before = f[2];
    const Double4 w = load(inverse_mass + i);
    const Double4 decay = load(damping + i);
    const Double4 m[3] = {spread0(w), spread1(w), spread2(w)};
    const Double4 s[3] = {spread0(decay), spread1(decay), spread2(decay)};
    for (int b = 0; b < 3; ++b) {
      const std::size_t k = 3 * i + 4 * static_cast<std::size_t>(b);
      const Double4 velocity = (load(v + k) + ((f[b] - earlier[b]) * m[b]) * h + gravity[b]) * s[b];
      store(v + k, velocity);
      store(x + k, load(x + k) + velocity * h);
    }
  }
  double f_before[3] = {before[1], before[2], before[3]};
  for (; i < n; ++i) {
    double d[3];
    for (int c = 0; c < 3; ++c) d[c] = x[3 * i + c] - x[3 * i + 3 + c];
    const double length = std::sqrt((d[0] * d[0] + d[1] * d[1]) + d[2] * d[2]);
    const double magnitude = -(stiffness[i] * (length - rest_length[i])) * (1.0 / length);
    for (int c = 0; c < 3; ++c) {
      const double f = magnitude * d[c];
      const std::size_t k = 3 * i + static_cast<std::size_t>(c);
      const double velocity =
          (v[k] + ((f - f_before[c]) * inverse_mass[i]) * kH + g[c]) * damping[i];
      v[k] = velocity;
      x[k] += velocity * kH;
      f_before[c] = f;
    }
  }
}

std::size_t roundUp(const std::size_t bytes) { return (bytes + kLine - 1) / kLine * kLine; }

}  // namespace

void FreeAligned::operator()(double* p) const { std::free(p); }

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

SpringChainFloor::SpringChainFloor(const std::size_t particles, const std::size_t chain_length)
    : particles_(particles) {
  const auto allocate = [](const std::size_t count) {
    void* block = std::aligned_alloc(kLine, roundUp(count * sizeof(double)));
    if (block == nullptr) throw std::bad_alloc();
    return std::unique_ptr<double, FreeAligned>(static_cast<double*>(block));
  };
  x_ = allocate(3 * (particles + 1));
  v_ = allocate(3 * particles);
  inverse_mass_ = allocate(particles);
  damping_ = allocate(particles);
  stiffness_ = allocate(particles);
  rest_length_ = allocate(particles);
  const double damping = std::pow(0.99, kH);
  // B's chains: 1 m apart along x, every other particle 0.1 m up, chains 2 m apart in z.
  for (std::size_t i = 0; i < particles; ++i) {
    const std::size_t j = i % chain_length;
    x_.get()[3 * i] = static_cast<double>(j);
    x_.get()[3 * i + 1] = 0.1 * static_cast<double>(j % 2);
    x_.get()[3 * i + 2] = 2.0 * static_cast<double>(i / chain_length);
    for (int c = 0; c < 3; ++c) v_.get()[3 * i + static_cast<std::size_t>(c)] = 0.0;
    inverse_mass_.get()[i] = 1.0;
    damping_.get()[i] = damping;
    const bool ends_chain = j + 1 == chain_length || i + 1 == particles;
    stiffness_.get()[i] = ends_chain ? 0.0 : 10.0;
    rest_length_.get()[i] = 1.0;
  }
  // The last particle's spring (k = 0) ends 1 m along x from where that particle starts.
  for (int c = 0; c < 3; ++c) {
    x_.get()[3 * particles + static_cast<std::size_t>(c)] =
        x_.get()[3 * (particles - 1) + static_cast<std::size_t>(c)] + (c == 0 ? 1.0 : 0.0);
  }
}

void SpringChainFloor::step() {
  springChainPass(particles_, x_.get(), v_.get(), inverse_mass_.get(), damping_.get(),
                  stiffness_.get(), rest_length_.get());
}

}  // namespace bench
}  // namespace engine
}  // namespace mass_aggregate_sim
