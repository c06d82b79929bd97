#pragma once
// Rigid-body benchmark scenes as plain data, shared by every engine that runs them (the Bullet
// peer in bullet_peer_bench.cpp now, the project's own rigid bodies later), so the engines are
// compared on the same bodies. Nothing here depends on a physics engine; only Eigen.
//
// Conventions of every scene: SI units, z up, gravity (0, 0, -9.81), a ground half-space z <= 0.
// Boxes have density 1 kg/m^3, as in Box2D's benchmarks, so a unit cube weighs 1 kg; the mass of
// a body is stored, its inertia is that of the solid uniform shape. A body of mass 0 is fixed.
// A contact pair's friction is sqrt(f_a * f_b) and its restitution max(r_a, r_b) (Box2D's rules);
// every scene below has restitution 0.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace mass_aggregate_sim {
namespace bench {
namespace rigid {

enum class ShapeType { kBox, kSphere };

struct BodySpec {
  ShapeType shape = ShapeType::kBox;
  Eigen::Vector3d half_extents = Eigen::Vector3d::Constant(0.5);  // boxes only
  double radius = 0.0;                                            // spheres only
  double mass = 1.0;                                              // 0: fixed
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d linear_velocity = Eigen::Vector3d::Zero();
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();
  double friction = 0.5;
  double restitution = 0.0;

  bool isFixed() const { return mass <= 0.0; }
};

struct GroundSpec {
  double height = 0.0;
  double friction = 0.5;
  double restitution = 0.0;
};

struct RigidScene {
  std::string name;
  Eigen::Vector3d gravity = Eigen::Vector3d(0.0, 0.0, -9.81);
  GroundSpec ground;
  std::vector<BodySpec> bodies;
  // The body whose drop says whether a structure stood (its top box); -1 when the scene has none.
  int top_body = -1;
  // Half-width of the square region the walls enclose (|x|, |y| below it); 0 when there are no
  // walls. A dynamic body outside it, or below the ground, has escaped.
  double inner_half_width = 0.0;
  // How high the walls stand: a body dropped from above them may be thrown over, which is physics;
  // one that leaves below their top has gone through.
  double wall_height = 0.0;
};

// Every scene runs at 60 Hz.
constexpr double kFrameSeconds = 1.0 / 60.0;

// A structure stood when its top body ended within this distance of where it started.
constexpr double kStoodTolerance = 0.01;

// A dynamic body at `position` is outside the scene's walls or below its ground.
inline bool hasEscaped(const RigidScene& scene, const Eigen::Vector3d& position) {
  const bool outside =
      scene.inner_half_width > 0.0 && (std::abs(position.x()) > scene.inner_half_width ||
                                       std::abs(position.y()) > scene.inner_half_width);
  return outside || position.z() < scene.ground.height;
}

constexpr double kBoxDensity = 1.0;
constexpr double kRainSphereRadius = 0.03;
constexpr double kRainSphereMass = 0.1;
constexpr int kRainDefaultSpheres = 2000;

// Box2D's pyramid in the x-z plane (y = 0): unit cubes of 1 kg; row i (0 at the bottom) holds
// base - i boxes 1 m apart, centred on x = 0 (so each row is shifted half a box from the one
// below), at z = 0.5 + i. Every box touches its neighbours, none overlaps. base * (base + 1) / 2
// boxes; the top body is the single box of the last row.
RigidScene pyramid(int base);

// pyramid(base) and a ball (radius 0.25 m, 1 kg) rolling without slipping at 2 m/s along x on
// the ground 3 m from it, from x = -(base / 2 + 10) m: with sleeping on, a pile that sleeps and
// one body that keeps moving past it and touches nothing but the ground. Top body: the pyramid's.
RigidScene pyramidAndRoller(int base);

// Box2D's pyramid as a user might lay it out by hand: the boxes of a row 1 cm apart (the rows'
// centres 1.01 m apart along x), each moved along x by a uniform draw in [-2 mm, 2 mm], and each
// row 0.1 mm above the one below (z = 0.5 + 1.0001 i), so that no two boxes touch and the
// pyramid falls into place (its top by 1.9 mm). The top body is the single box of the last row.
RigidScene droppedPyramid(int base, std::uint64_t seed = 1);

// n unit cubes of 1 kg in a column at x = y = 0, z = 0.5 + i, touching. Top body: the last.
RigidScene stack(int n);

// n boxes with half extents each drawn from [0.1, 0.3] m (density 1 kg/m^3, so 8 g to 216 g) at
// random orientations, on a 10 x 10 lattice 1.05 m apart per layer (no two can touch: a box's
// bounding sphere is at most 0.52 m), layers 1.05 m apart from z = 1 m up (z = 10.45 m for the
// tenth layer of 100); they fall into a pile inside four fixed walls (boxes 0.5 m thick and 3 m
// tall whose inner faces are 5.5 m from the centre). The walls come first in `bodies`.
constexpr std::uint64_t kRandomDropDefaultSeed = 1;
RigidScene randomDrop(int n, std::uint64_t seed = kRandomDropDefaultSeed);

// The random drop's and the rain's seed in the benchmarks: MAS_RIGID_SEED if set (a pile's
// at-rest overlap depends on how its boxes happened to wedge, and how many spheres the rain throws
// over its walls on how they happened to land, so their figures are compared over several seeds),
// else `otherwise` (each scene's default seed).
std::uint64_t benchmarkSeed(std::uint64_t otherwise);

// A stack of five unit cubes of 1 kg (as stack(5)) and `spheres` spheres of radius 3 cm and
// 0.1 kg raining onto it: layers of 20 x 20 spheres 0.1 m apart (each moved at random by up to
// 1.5 cm across) covering |x|, |y| < 1 m, layers 0.5 m apart from z = 6 m up. Friction 0.5,
// restitution 0. Four fixed walls (0.2 m thick, 2 m tall, inner faces 1.25 m from the centre)
// keep the spheres that miss the stack from rolling away for ever. The walls come after the
// stack's boxes; the top body is the top box.
constexpr std::uint64_t kRainDefaultSeed = 2;
RigidScene particleRain(int spheres = kRainDefaultSpheres, std::uint64_t seed = kRainDefaultSeed);

// SplitMix64 (Steele, Lea and Flood 2014): the generators draw from it instead of std::
// distributions, whose results differ between standard libraries.
class SplitMix64 {
 public:
  explicit SplitMix64(const std::uint64_t seed) : state_(seed) {}

  std::uint64_t next() {
    state_ += 0x9e3779b97f4a7c15ULL;
    std::uint64_t z = state_;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }

  // Uniform in [lo, hi), from the top 53 bits.
  double uniform(const double lo, const double hi) {
    const double unit = static_cast<double>(next() >> 11) * 0x1.0p-53;
    return lo + (hi - lo) * unit;
  }

 private:
  std::uint64_t state_;
};

}  // namespace rigid
}  // namespace bench
}  // namespace mass_aggregate_sim
