#pragma once
// The floor under scenario A: the fastest loop we could write that moves the bytes A's step must
// move per particle (read x, v, inverse mass and damping factor, 64 bytes; write x and v, 48
// bytes), with the least arithmetic that still makes each value depend on what it read:
// v' = (v + [w > 0] g h) d, x' = x + v' h. A reported as a ratio to it says how far A is from what
// the machine can do with those bytes.

#include <cstddef>
#include <memory>

namespace mass_aggregate_sim {
namespace engine {
namespace bench {

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
  struct Free {
    void operator()(double* p) const;
  };
  std::size_t particles_;
  std::unique_ptr<double, Free> storage_;
  double* x_;
  double* v_;
  double* inverse_mass_;
  double* damping_;
};

}  // namespace bench
}  // namespace engine
}  // namespace mass_aggregate_sim
