#include "rigid_scenes.h"

#include <cmath>
#include <cstdlib>
#include <string>
#include <utility>

namespace mass_aggregate_sim {
namespace bench {
namespace rigid {
namespace {

constexpr double kPi = 3.14159265358979323846;

BodySpec unitCube(const Eigen::Vector3d& position) {
  BodySpec body;
  body.position = position;
  body.mass = kBoxDensity;
  return body;
}

BodySpec fixedBox(const Eigen::Vector3d& half_extents, const Eigen::Vector3d& position) {
  BodySpec body;
  body.half_extents = half_extents;
  body.position = position;
  body.mass = 0.0;
  return body;
}

// Four fixed walls whose inner faces are `inner` from the centre: the two normal to x span the
// inner width in y, the two normal to y span the full outer width in x, so they meet at the
// corners without overlapping.
void addWalls(RigidScene& scene, const double inner, const double half_thickness,
              const double height) {
  const double centre = inner + half_thickness;
  const double half_height = 0.5 * height;
  const Eigen::Vector3d across_x(half_thickness, inner, half_height);
  const Eigen::Vector3d across_y(inner + 2.0 * half_thickness, half_thickness, half_height);
  scene.bodies.push_back(fixedBox(across_x, Eigen::Vector3d(centre, 0.0, half_height)));
  scene.bodies.push_back(fixedBox(across_x, Eigen::Vector3d(-centre, 0.0, half_height)));
  scene.bodies.push_back(fixedBox(across_y, Eigen::Vector3d(0.0, centre, half_height)));
  scene.bodies.push_back(fixedBox(across_y, Eigen::Vector3d(0.0, -centre, half_height)));
  scene.inner_half_width = inner;
  scene.wall_height = height;
}

// Uniform over the rotations (Shoemake, Graphics Gems III).
Eigen::Quaterniond randomOrientation(SplitMix64& rng) {
  const double u1 = rng.uniform(0.0, 1.0);
  const double u2 = rng.uniform(0.0, 2.0 * kPi);
  const double u3 = rng.uniform(0.0, 2.0 * kPi);
  const double a = std::sqrt(1.0 - u1);
  const double b = std::sqrt(u1);
  return Eigen::Quaterniond(b * std::cos(u3), a * std::sin(u2), a * std::cos(u2), b * std::sin(u3));
}

}  // namespace

namespace {

// Box2D's pyramid laid with the boxes of a row `spacing` m apart centre to centre (1: touching),
// each moved along x by a draw in [-jitter, jitter] (none when 0), each row `row_gap` m above the
// one below. The top body is the single box of the last row.
RigidScene layPyramid(std::string name, const int base, const double spacing, const double jitter,
                      const double row_gap, const std::uint64_t seed) {
  RigidScene scene;
  scene.name = std::move(name);
  scene.bodies.reserve(static_cast<std::size_t>(base) * static_cast<std::size_t>(base + 1) / 2);
  SplitMix64 rng(seed);
  for (int row = 0; row < base; ++row) {
    const double first = spacing * (0.5 * (row + 1) - 0.5 * base);
    for (int k = 0; k < base - row; ++k) {
      const double x = first + spacing * k + rng.uniform(-jitter, jitter);
      scene.bodies.push_back(unitCube(Eigen::Vector3d(x, 0.0, 0.5 + (1.0 + row_gap) * row)));
    }
  }
  scene.top_body = static_cast<int>(scene.bodies.size()) - 1;
  return scene;
}

}  // namespace

RigidScene pyramid(const int base) {
  return layPyramid("pyramid/" + std::to_string(base), base, 1.0, 0.0, 0.0, 1);
}

RigidScene droppedPyramid(const int base, const std::uint64_t seed) {
  std::string name = "dropped_pyramid/" + std::to_string(base);
  if (seed != 1) name += ", seed " + std::to_string(seed);
  return layPyramid(std::move(name), base, 1.01, 0.002, 0.0001, seed);
}

RigidScene pyramidAndRoller(const int base) {
  constexpr double kRadius = 0.25;
  constexpr double kSpeed = 2.0;
  RigidScene scene = pyramid(base);
  scene.name = "pyramid_and_roller/" + std::to_string(base);
  BodySpec ball;
  ball.shape = ShapeType::kSphere;
  ball.radius = kRadius;
  ball.mass = 1.0;
  ball.position = Eigen::Vector3d(-(0.5 * base + 10.0), 3.0, kRadius);
  ball.linear_velocity = Eigen::Vector3d(kSpeed, 0.0, 0.0);
  // Rolling: the contact point still, v + w x (-r z) = 0.
  ball.angular_velocity = Eigen::Vector3d(0.0, kSpeed / kRadius, 0.0);
  scene.bodies.push_back(ball);
  return scene;
}

RigidScene stack(const int n) {
  RigidScene scene;
  scene.name = "stack/" + std::to_string(n);
  for (int i = 0; i < n; ++i) scene.bodies.push_back(unitCube(Eigen::Vector3d(0.0, 0.0, 0.5 + i)));
  scene.top_body = n - 1;
  return scene;
}

RigidScene randomDrop(const int n, const std::uint64_t seed) {
  constexpr int kPerSide = 10;
  constexpr double kSpacing = 1.05;
  constexpr double kLowest = 1.0;
  RigidScene scene;
  scene.name = "random_drop/" + std::to_string(n);
  if (seed != kRandomDropDefaultSeed) scene.name += ", seed " + std::to_string(seed);
  addWalls(scene, 5.5, 0.25, 3.0);
  SplitMix64 rng(seed);
  const double first = -0.5 * kSpacing * (kPerSide - 1);
  for (int i = 0; i < n; ++i) {
    const int layer = i / (kPerSide * kPerSide);
    const int in_layer = i % (kPerSide * kPerSide);
    BodySpec body;
    // One draw per statement: the order in which function arguments are evaluated is unspecified.
    for (int axis = 0; axis < 3; ++axis) body.half_extents[axis] = rng.uniform(0.1, 0.3);
    body.mass = kBoxDensity * 8.0 * body.half_extents.prod();
    body.orientation = randomOrientation(rng);
    body.position =
        Eigen::Vector3d(first + kSpacing * (in_layer % kPerSide),
                        first + kSpacing * (in_layer / kPerSide), kLowest + kSpacing * layer);
    scene.bodies.push_back(body);
  }
  return scene;
}

std::uint64_t benchmarkSeed(const std::uint64_t otherwise) {
  const char* const text = std::getenv("MAS_RIGID_SEED");
  return text != nullptr ? std::strtoull(text, nullptr, 10) : otherwise;
}

RigidScene particleRain(const int spheres, const std::uint64_t seed) {
  constexpr int kStackHeight = 5;
  constexpr int kPerSide = 20;
  constexpr double kSpacing = 0.1;
  constexpr double kJitter = 0.015;
  constexpr double kLowest = 6.0;
  constexpr double kLayerGap = 0.5;
  RigidScene scene = stack(kStackHeight);
  scene.name = "particle_rain/" + std::to_string(spheres);
  if (seed != kRainDefaultSeed) scene.name += ", seed " + std::to_string(seed);
  addWalls(scene, 1.25, 0.1, 2.0);
  SplitMix64 rng(seed);
  const double first = -0.5 * kSpacing * (kPerSide - 1);
  for (int i = 0; i < spheres; ++i) {
    const int layer = i / (kPerSide * kPerSide);
    const int in_layer = i % (kPerSide * kPerSide);
    BodySpec body;
    body.shape = ShapeType::kSphere;
    body.radius = kRainSphereRadius;
    body.mass = kRainSphereMass;
    const double jitter_x = rng.uniform(-kJitter, kJitter);
    const double jitter_y = rng.uniform(-kJitter, kJitter);
    body.position = Eigen::Vector3d(first + kSpacing * (in_layer % kPerSide) + jitter_x,
                                    first + kSpacing * (in_layer / kPerSide) + jitter_y,
                                    kLowest + kLayerGap * layer);
    scene.bodies.push_back(body);
  }
  return scene;
}

}  // namespace rigid
}  // namespace bench
}  // namespace mass_aggregate_sim
