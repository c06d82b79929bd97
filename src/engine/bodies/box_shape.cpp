// The box body shape kind (box_shape.h).
#include "mass_aggregate_sim/engine/bodies/box_shape.h"

#include "engine/collision/geometry.h"

namespace mass_aggregate_sim {
namespace engine {

Status BodyShapeKind<BoxShape>::validate(const BoxShape& box) {
  if (!(box.half_extents.allFinite() && (box.half_extents.array() > 0.0).all())) {
    return Status::error("box half_extents must be finite and > 0");
  }
  return Status::ok();
}

Real BodyShapeKind<BoxShape>::volume(const BoxShape& box) { return 8.0 * box.half_extents.prod(); }

// With full extents 2h: I_x = m (4 h_y^2 + 4 h_z^2) / 12 = m (h_y^2 + h_z^2) / 3, and so on.
Vec3 BodyShapeKind<BoxShape>::unitInertia(const BoxShape& box) {
  const Vec3 h2 = box.half_extents.cwiseProduct(box.half_extents);
  return volume(box) / 3.0 * Vec3(h2.y() + h2.z(), h2.z() + h2.x(), h2.x() + h2.y());
}

// The world half extents along axis i: sum over the box axes j of |R_ij| h_j.
Aabb BodyShapeKind<BoxShape>::aabb(const BoxShape& box, const Frame& frame) {
  const Vec3 extent = frame.rotation.cwiseAbs() * box.half_extents;
  return Aabb{frame.position - extent, frame.position + extent};
}

std::optional<RayShapeHit> BodyShapeKind<BoxShape>::raycast(const BoxShape& box, const Frame& frame,
                                                            const Vec3& origin,
                                                            const Vec3& direction,
                                                            const Real max_t) {
  const std::optional<RayShapeHit> hit = rayIntoCentredBox(
      frame.applyInverse(origin), frame.rotation.transpose() * direction, max_t, box.half_extents);
  if (!hit) return std::nullopt;
  return RayShapeHit{hit->t, frame.rotation * hit->normal};
}

std::vector<ShapePrimitive> BodyShapeKind<BoxShape>::describe(const BoxShape& box) {
  ShapePrimitive cube;
  cube.type = ShapePrimitive::Type::kBox;
  cube.size = 2.0 * box.half_extents;
  return {cube};
}

// The submerged part is a convex polyhedron bounded by the box's faces clipped to the liquid and
// by a cap in the surface. Its volume is the sum of the signed tetrahedra (p, a, b, c) over its
// faces' triangles (abc counter-clockwise seen from outside), V = (a - p).((b - p) x (c - p)) / 6,
// for any p; taking p in the surface, the cap adds nothing and only the clipped faces are
// needed. Each tetrahedron's centroid is (p + a + b + c) / 4.
SubmergedVolume BodyShapeKind<BoxShape>::submerged(const BoxShape& box, const Frame& frame,
                                                   const LiquidSurface& surface) {
  const Vec3 extent = frame.rotation.transpose() * surface.up;
  const Real reach = extent.cwiseAbs().dot(box.half_extents);
  const Real centre = surface.above(frame.position);
  if (centre >= reach) return SubmergedVolume{};
  if (centre <= -reach) return SubmergedVolume::whole(volume(box), frame.position);
  const Vec3 p = frame.position - centre * surface.up;
  SubmergedVolume part;
  // Face k, side s: outward normal s e_k; its corners counter-clockwise seen from outside run
  // through (-,-), (+,-), (+,+), (-,+) along (e_i, e_j), (i, j, k) cyclic, reversed for s < 0.
  constexpr Real kCorner[4][2] = {{-1.0, -1.0}, {1.0, -1.0}, {1.0, 1.0}, {-1.0, 1.0}};
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3;
    const int j = (k + 2) % 3;
    for (const Real side : {-1.0, 1.0}) {
      Vec3 corners[4];
      for (int c = 0; c < 4; ++c) {
        const int at = side > 0.0 ? c : 3 - c;
        Vec3 local;
        local[k] = side * box.half_extents[k];
        local[i] = kCorner[at][0] * box.half_extents[i];
        local[j] = kCorner[at][1] * box.half_extents[j];
        corners[c] = frame.apply(local);
      }
      // The face clipped to the liquid (Sutherland-Hodgman against one plane): at most 5 corners.
      Vec3 kept[5];
      int count = 0;
      for (int c = 0; c < 4; ++c) {
        const Vec3& from = corners[c];
        const Vec3& to = corners[(c + 1) % 4];
        const Real h_from = surface.above(from);
        const Real h_to = surface.above(to);
        if (h_from < 0.0) kept[count++] = from;
        if ((h_from < 0.0) != (h_to < 0.0)) {
          kept[count++] = from + (h_from / (h_from - h_to)) * (to - from);
        }
      }
      for (int c = 1; c + 1 < count; ++c) {
        const Vec3 a = kept[0] - p;
        const Vec3 b = kept[c] - p;
        const Vec3 d = kept[c + 1] - p;
        const Real v = a.dot(b.cross(d)) / 6.0;
        part.volume += v;
        part.moment += v * (p + 0.25 * (a + b + d));
      }
    }
  }
  return part;
}

}  // namespace engine
}  // namespace mass_aggregate_sim
