// MarkerBuilder's bodies, joints and contact lines.
#include <algorithm>
#include <type_traits>
#include <variant>

#include "mass_aggregate_sim/node/conversions.h"
#include "mass_aggregate_sim/node/markers.h"

namespace mass_aggregate_sim {
namespace node {
namespace {

using engine::Vec3;
using visualization_msgs::Marker;

// Marker ids of one body's parts: 256 per body slot (at most kMaxShapesPerBody = 64 shapes of at
// most 4 parts), so a body keeps its ids while it lives.
int bodyPartId(const std::uint64_t body_id, const std::uint32_t shape, const std::size_t part) {
  const std::uint64_t slot = body_id & 0xFFFFFFFFull;
  return static_cast<int>((slot * 256 + shape * 4 + part) & 0x7FFFFFFFull);
}

int markerType(const engine::ShapePrimitive::Type type) {
  switch (type) {
    case engine::ShapePrimitive::Type::kBox:
      return Marker::CUBE;
    case engine::ShapePrimitive::Type::kSphere:
      return Marker::SPHERE;
    case engine::ShapePrimitive::Type::kCylinder:
      return Marker::CYLINDER;
  }
  return Marker::CUBE;
}

}  // namespace

std_msgs::ColorRGBA bodyColor(const engine::BodyType type, const bool sleeping) {
  std_msgs::ColorRGBA c = type == engine::BodyType::kDynamic     ? rgba(0.25f, 0.55f, 0.95f)
                          : type == engine::BodyType::kKinematic ? rgba(0.3f, 0.8f, 0.35f)
                                                                 : rgba(0.5f, 0.52f, 0.55f);
  if (sleeping) {
    c.r *= 0.45f;
    c.g *= 0.45f;
    c.b *= 0.45f;
  }
  return c;
}

void MarkerBuilder::addBodies(const BodySnapshot& bodies, const ros::Time& stamp,
                              visualization_msgs::MarkerArray& out) const {
  for (const ShapeView& shape : bodies.shapes) {
    const std::vector<engine::ShapePrimitive> parts = std::visit(
        [](const auto& g) { return engine::BodyShapeKind<std::decay_t<decltype(g)>>::describe(g); },
        shape.geometry);
    const std_msgs::ColorRGBA c =
        bodyColor(bodies.types[shape.body], bodies.sleeping[shape.body] != 0);
    for (std::size_t part = 0; part < parts.size() && part < 4; ++part) {
      const engine::ShapePrimitive& primitive = parts[part];
      Marker m = makeMarker("bodies", bodyPartId(bodies.ids[shape.body], shape.index, part),
                            markerType(primitive.type), stamp);
      // The part's pose in the shape's frame, then the shape's in the world.
      const engine::Transform pose =
          shape.pose * engine::Transform{primitive.center, primitive.orientation};
      m.pose.position = toPointMsg(pose.position);
      m.pose.orientation.x = pose.rotation.x();
      m.pose.orientation.y = pose.rotation.y();
      m.pose.orientation.z = pose.rotation.z();
      m.pose.orientation.w = pose.rotation.w();
      m.scale.x = primitive.size.x();
      m.scale.y = primitive.size.y();
      m.scale.z = primitive.size.z();
      m.color = c;
      out.markers.push_back(m);
    }
  }
}

void MarkerBuilder::addJoints(const BodySnapshot& bodies, const ros::Time& stamp,
                              visualization_msgs::MarkerArray& out) const {
  if (bodies.joints.empty()) return;
  Marker lines = makeMarker("joints", 0, Marker::LINE_LIST, stamp);
  lines.scale.x = 0.02;
  lines.color = rgba(1.0f, 0.85f, 0.1f);
  const auto segment = [&](const Vec3& a, const Vec3& b) {
    lines.points.push_back(toPointMsg(a));
    lines.points.push_back(toPointMsg(b));
  };
  // Each end's centre of mass to where the joint holds it, and the two anchors (apart only for a
  // distance joint or a joint being pulled apart).
  for (const JointView& joint : bodies.joints) {
    if (joint.body_a) segment(joint.centre_a, joint.anchor_a);
    if (joint.body_b) segment(joint.centre_b, joint.anchor_b);
    segment(joint.anchor_a, joint.anchor_b);
  }
  out.markers.push_back(std::move(lines));
}

void MarkerBuilder::addContacts(const BodySnapshot& bodies, const ros::Time& stamp,
                                visualization_msgs::MarkerArray& out) const {
  if (bodies.contacts.empty() || !(bodies.substep > 0.0)) return;
  Marker lines = makeMarker("contacts", 0, Marker::LINE_LIST, stamp);
  lines.scale.x = 0.01;
  lines.color = rgba(1.0f, 0.2f, 0.2f);
  // Along the normal, 2 cm plus up to 0.5 m for a force of tension_scale or more.
  for (const engine::BodyContactReport& contact : bodies.contacts) {
    for (const auto& point : contact.points) {
      const double force = point.normal_impulse / bodies.substep;
      const double length = 0.02 + 0.5 * std::clamp(force / tension_scale_, 0.0, 1.0);
      lines.points.push_back(toPointMsg(point.position));
      lines.points.push_back(toPointMsg(point.position - length * contact.normal));
    }
  }
  if (!lines.points.empty()) out.markers.push_back(std::move(lines));
}

}  // namespace node
}  // namespace mass_aggregate_sim
