#pragma once
// The floors under scenarios A and B. A's is the fastest loop we could write that moves the bytes
// A's step must move per particle (read x, v, inverse mass and damping factor, 64 bytes; write x
// and v, 48 bytes), with the least arithmetic that still makes each value depend on what it read:
// v' = (v + [w > 0] g h) d, x' = x + v' h. A reported as a ratio to it says how far A is from what
// the machine can do with those bytes.

#include <cstddef>
#include <memory>

namespace mass_aggregate_sim {
namespace engine {
namespace bench {

// Frees what std::aligned_alloc gave the floors' arrays.
struct FreeAligned {
  void operator()(double* p) const;
};

// The floor's own arrays (the layout of the engine's: xyz of particle i at 3i, scalars at i),
// each aligned to a cache line.
class FloorArrays {
 public:
  explicit FloorArrays(std::size_t particles);
  std::size_t size() const { return particles_; }
  // One pass over every particle.
  void step();
  const double* positions() const { return x_; }

 private:
  std::size_t particles_;
  std::unique_ptr<double, FreeAligned> storage_;
  double* x_;
  double* v_;
  double* inverse_mass_;
  double* damping_;
};

// The floor under scenario B: chains of springs (k, L per spring) along consecutive particles,
// in one pass that does the least B must do: per spring one square root and one division (the
// exact length and its inverse), per particle the force of its two springs and A's update,
// reading x, v, inverse mass, damping factor, k and L (80 bytes) and writing x and v (48). Its
// one chain runs through all the particles; B's breaks every 100 (here a spring of k = 0, whose
// root and division are taken all the same). No elastic energy is summed (B's guard sums it).
class SpringChainFloor {
 public:
  SpringChainFloor(std::size_t particles, std::size_t chain_length);  // particles >= 1
  std::size_t size() const { return particles_; }
  void step();
  const double* positions() const { return x_.get(); }

 private:
  std::size_t particles_;
  std::unique_ptr<double, FreeAligned> x_;  // 3 (n + 1): the last particle's next, a copy of it
  std::unique_ptr<double, FreeAligned> v_;
  std::unique_ptr<double, FreeAligned> inverse_mass_;
  std::unique_ptr<double, FreeAligned> damping_;
  std::unique_ptr<double, FreeAligned> stiffness_;  // spring i joins particles i and i + 1
  std::unique_ptr<double, FreeAligned> rest_length_;
};

}  // namespace bench
}  // namespace engine
}  // namespace mass_aggregate_sim
