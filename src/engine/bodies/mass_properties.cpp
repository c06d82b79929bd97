#include "mass_aggregate_sim/engine/bodies/mass_properties.h"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <string>
#include <type_traits>

namespace mass_aggregate_sim {
namespace engine {
namespace {

Status validateShape(const BodyShapeSpec& shape) {
  const Status geometry = std::visit(
      [](const auto& g) { return BodyShapeKind<std::decay_t<decltype(g)>>::validate(g); },
      shape.geometry);
  if (!geometry) return geometry;
  if (!shape.local.position.allFinite()) return Status::error("shape position is not finite");
  if (!shape.local.rotation.coeffs().allFinite() ||
      std::abs(shape.local.rotation.norm() - 1.0) > 1e-6) {
    return Status::error("shape orientation must be a unit quaternion (|q| within 1e-6 of 1)");
  }
  if (!std::isfinite(shape.density) || shape.density <= 0.0) {
    return Status::error("shape density must be finite and > 0");
  }
  const Material& m = shape.material;
  if (!std::isfinite(m.restitution) || m.restitution < 0.0 || m.restitution > 1.0) {
    return Status::error("shape restitution must be in [0, 1]");
  }
  if (!std::isfinite(m.friction) || m.friction < 0.0) {
    return Status::error("shape friction must be finite and >= 0");
  }
  return Status::ok();
}

bool diagonal(const Mat3& m) {
  return m(0, 1) == 0.0 && m(0, 2) == 0.0 && m(1, 2) == 0.0 && m(1, 0) == 0.0 && m(2, 0) == 0.0 &&
         m(2, 1) == 0.0;
}

}  // namespace

Result<MassProperties> computeMassProperties(const std::vector<BodyShapeSpec>& shapes,
                                             const Real mass) {
  if (shapes.empty()) return Status::error("a body needs at least one shape");
  if (!std::isfinite(mass) || mass < 0.0) {
    return Status::error("mass must be finite and > 0 (or 0: from the densities)");
  }
  for (std::size_t k = 0; k < shapes.size(); ++k) {
    const Status valid = validateShape(shapes[k]);
    if (!valid) return Status::error("shapes[" + std::to_string(k) + "]: " + valid.message());
  }
  struct Part {
    Real mass;
    Vec3 center;
    Mat3 inertia;  // about its own centre, in the body frame
  };
  std::vector<Part> parts;
  parts.reserve(shapes.size());
  Real total = 0.0;
  Real volume = 0.0;
  for (const BodyShapeSpec& shape : shapes) {
    std::visit(
        [&](const auto& g) {
          using Kind = BodyShapeKind<std::decay_t<decltype(g)>>;
          const Real v = Kind::volume(g);
          const Mat3 r = shape.local.rotation.toRotationMatrix();
          const Mat3 unit = r * Kind::unitInertia(g).asDiagonal() * r.transpose();
          parts.push_back(Part{shape.density * v, shape.local.position, shape.density * unit});
          total += shape.density * v;
          volume += v;
        },
        shape.geometry);
  }
  if (!(std::isfinite(total) && total > 0.0)) {
    return Status::error("the shapes' mass must be finite and > 0");
  }
  // A given mass scales every part alike: the same centre, the inertia in proportion.
  const Real scale = mass > 0.0 ? mass / total : 1.0;
  Vec3 center = Vec3::Zero();
  for (const Part& p : parts) center += p.mass * p.center;
  center /= total;
  Mat3 inertia = Mat3::Zero();
  for (const Part& p : parts) {
    const Vec3 d = p.center - center;
    inertia += p.inertia + p.mass * (d.squaredNorm() * Mat3::Identity() - d * d.transpose());
  }
  inertia *= scale;
  MassProperties props;
  props.mass = total * scale;
  props.volume = volume;
  props.frame.position = center;
  if (diagonal(inertia)) {
    props.principal_inertia = inertia.diagonal();
  } else {
    const Mat3 symmetric = 0.5 * (inertia + inertia.transpose());
    const Eigen::SelfAdjointEigenSolver<Mat3> solver(symmetric);
    Mat3 axes = solver.eigenvectors();
    if (axes.determinant() < 0.0) axes.col(2) = -axes.col(2);  // a rotation, not a reflection
    props.principal_inertia = solver.eigenvalues();
    props.frame.rotation = Quat(axes).normalized();
  }
  if (!props.principal_inertia.allFinite() || !(props.principal_inertia.array() > 0.0).all()) {
    return Status::error("the inertia tensor is not positive definite");
  }
  return props;
}

}  // namespace engine
}  // namespace mass_aggregate_sim
