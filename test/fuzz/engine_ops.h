#pragma once
// Interprets arbitrary bytes as a sequence of World calls with arbitrary fields (raw 64-bit
// patterns, so NaN, Inf, denormals and huge values all occur) and checks the engine's promises:
// a refused call changes nothing, and a non-finite state never goes unreported. Shared by the
// libFuzzer target (engine_fuzz.cpp) and the gtest that replays saved inputs.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "mass_aggregate_sim/engine/world/world.h"

namespace mass_aggregate_sim {
namespace fuzz {

class ByteReader {
 public:
  ByteReader(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
  bool empty() const { return offset_ >= size_; }
  std::uint8_t byte() { return offset_ < size_ ? data_[offset_++] : 0; }
  std::uint32_t u32() {
    std::uint32_t v = 0;
    for (int i = 0; i < 4; ++i) v = (v << 8) | byte();
    return v;
  }
  // Half the time a raw bit pattern (anything, NaN and Inf included), half a modest value.
  double real() {
    if (byte() & 1u) {
      std::uint64_t bits = 0;
      for (int i = 0; i < 8; ++i) bits = (bits << 8) | byte();
      double v;
      std::memcpy(&v, &bits, sizeof v);
      return v;
    }
    return (static_cast<double>(static_cast<std::int8_t>(byte())) / 8.0);
  }
  engine::Vec3 vec3() {
    const double x = real();
    const double y = real();
    const double z = real();
    return engine::Vec3(x, y, z);
  }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t offset_ = 0;
};

struct Snapshot {
  std::uint64_t hash;
  std::size_t particles;
  std::size_t generators;
  explicit Snapshot(const engine::World& w)
      : hash(w.stateHash()), particles(w.particles().size()), generators(w.generators().size()) {}
  bool operator==(const Snapshot& o) const {
    return hash == o.hash && particles == o.particles && generators == o.generators;
  }
};

[[noreturn]] inline void fail(const std::string& what) {
  std::fprintf(stderr, "engine promise broken: %s\n", what.c_str());
  std::abort();
}

inline void runEngineOps(const std::uint8_t* data, const std::size_t size) {
  using namespace engine;
  ByteReader in(data, size);
  World world;
  std::vector<ParticleId> known;
  int steps_left = 64;
  for (int op = 0; op < 96 && !in.empty(); ++op) {
    const std::uint8_t code = in.byte();
    // An id from the ones handed out (live or stale), or an arbitrary one.
    const auto pickId = [&]() {
      const std::uint32_t pick = in.u32();
      if (!known.empty() && (pick & 1u)) return known[(pick >> 1) % known.size()];
      return ParticleId{in.u32() % 64, in.u32() % 4};
    };
    const Snapshot before(world);
    bool accepted = true;
    switch (code % 16) {
      case 0:
      case 1: {
        ParticleSpec spec;
        spec.position = in.vec3();
        spec.velocity = in.vec3();
        spec.acceleration = in.vec3();
        spec.inverse_mass = in.real();
        spec.damping = in.real();
        spec.radius = in.real();
        const auto id = world.addParticle(spec);
        accepted = id.isOk();
        if (accepted) known.push_back(*id);
        break;
      }
      case 2:
        accepted = world.removeParticle(pickId()).isOk();
        break;
      case 3:
        accepted =
            world.addGenerator(Spring::between(pickId(), pickId(), in.real(), in.real(), in.real()))
                .isOk();
        break;
      case 4:
        accepted =
            world
                .addGenerator(Spring::between(pickId(), pickId(), in.real(), in.real(), in.real())
                                  .pullingOnly())
                .isOk();
        break;
      case 5:
        accepted = world
                       .addGenerator(
                           Spring::anchoredAt(pickId(), in.vec3(), in.real(), in.real(), in.real()))
                       .isOk();
        break;
      case 6:
        accepted = world.addGenerator(Drag{pickId(), in.real(), in.real()}).isOk();
        break;
      case 7:
        accepted = world
                       .addGenerator(Buoyancy{pickId(), in.real(), in.real(), in.real(), in.real(),
                                              in.vec3()})
                       .isOk();
        break;
      case 8:
        accepted =
            world.addGenerator(StiffSpring{pickId(), in.vec3(), in.real(), in.real()}).isOk();
        break;
      case 9:
        accepted = world.setPosition(pickId(), in.vec3()).isOk();
        break;
      case 10:
        accepted = world.setVelocity(pickId(), in.vec3()).isOk();
        break;
      case 11:
        accepted = world.applyImpulse(pickId(), in.vec3()).isOk();
        break;
      case 12:
        accepted = world.addForce(pickId(), in.vec3()).isOk();
        break;
      case 13:
        accepted = world.removeGenerator(in.u32() % 64).isOk();
        break;
      case 14: {
        WorldConfig config = world.config();
        config.dt = in.real();
        config.substeps = static_cast<int>(in.byte() % 8);
        config.integrator = static_cast<Integrator>(in.byte() % 6);
        config.gravity = in.vec3();
        accepted = world.setConfig(config).isOk();
        break;
      }
      default: {
        if (steps_left-- <= 0) break;
        const std::uint64_t divergences = world.divergenceCount();
        world.step();
        const bool finite =
            world.particles().positions().allFinite() && world.particles().velocities().allFinite();
        if (!finite && world.divergenceCount() == divergences) {
          fail("non-finite state after a step without a divergence report");
        }
        break;
      }
    }
    if (!accepted && !(Snapshot(world) == before)) {
      fail("a refused call (op " + std::to_string(code % 16) + ") changed the world");
    }
  }
}

}  // namespace fuzz
}  // namespace mass_aggregate_sim
