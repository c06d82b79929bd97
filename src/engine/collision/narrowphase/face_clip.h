#pragma once
// Sutherland-Hodgman clipping of a box's incident face against the reference face's side planes,
// keeping track of the features each vertex lies on (for stable ids).

#include <array>
#include <cstdint>

#include "mass_aggregate_sim/engine/core/types.h"

namespace mass_aggregate_sim {
namespace engine {

// A vertex of the incident face as it is clipped, in the reference box's frame. Incident edge e
// joins incident vertices e and (e + 1) % 4; side plane p is 0: x_u <= h_u, 1: -x_u <= h_u,
// 2: x_v <= h_v, 3: -x_v <= h_v, with u, v the reference face's in-plane axes.
// code: 0..3 an incident vertex; 4 + 4 e + p: incident edge e cut by plane p; 20 + 4 p' + p: the
// reference face's corner where plane p cuts the stretch of plane p'.
struct ClipVertex {
  Vec3 x = Vec3::Zero();
  std::array<std::int8_t, 2> edges{{-1, -1}};   // incident edges through it
  std::array<std::int8_t, 2> planes{{-1, -1}};  // side planes through it
  std::uint32_t code = 0;
};

// Four vertices clipped by four planes, each adding at most one.
struct ClipPolygon {
  std::array<ClipVertex, 8> vertices;
  int count = 0;
};

// The incident face (vertices in order) clipped to the side planes of the reference face with
// normal along `axis` and half extents h. Vertices less than kClipSlack h outside a side plane
// are first moved onto it, so that faces of equal size keep their four corners.
void clipToFaceSides(const Vec3& h, int axis, ClipPolygon& polygon);

}  // namespace engine
}  // namespace mass_aggregate_sim
