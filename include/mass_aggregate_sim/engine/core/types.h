#pragma once

#include <Eigen/Core>

namespace mass_aggregate_sim {
namespace engine {

using Real = double;
using Vec3 = Eigen::Vector3d;
// One column per particle: each attribute is its own contiguous array (structure of arrays).
using Vec3Array = Eigen::Matrix<Real, 3, Eigen::Dynamic>;
using ScalarArray = Eigen::Matrix<Real, Eigen::Dynamic, 1>;
// Views of the particle store's growable buffers.
using Vec3Map = Eigen::Map<Vec3Array>;
using ConstVec3Map = Eigen::Map<const Vec3Array>;
using ScalarMap = Eigen::Map<ScalarArray>;
using ConstScalarMap = Eigen::Map<const ScalarArray>;

}  // namespace engine
}  // namespace mass_aggregate_sim
