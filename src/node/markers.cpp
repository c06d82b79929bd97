#include "mass_aggregate_sim/node/markers.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <map>
#include <vector>

#include "mass_aggregate_sim/node/conversions.h"

namespace mass_aggregate_sim {
namespace node {
namespace {

using engine::Real;
using engine::Vec3;
using visualization_msgs::Marker;

}  // namespace

std_msgs::ColorRGBA rgba(const float r, const float g, const float b, const float a) {
  std_msgs::ColorRGBA c;
  c.r = r;
  c.g = g;
  c.b = b;
  c.a = a;
  return c;
}

std_msgs::ColorRGBA tensionColor(const double tension, const double tension_scale) {
  const float t = static_cast<float>(std::clamp(tension / tension_scale, -1.0, 1.0));
  // White at zero, fading to red when stretched and to blue when compressed.
  if (t >= 0.0f) return rgba(1.0f, 1.0f - t, 1.0f - t);
  return rgba(1.0f + t, 1.0f + t, 1.0f);
}

MarkerBuilder::MarkerBuilder(std::string frame_id, const double tension_scale,
                             const bool contact_markers)
    : frame_id_(std::move(frame_id)),
      tension_scale_(tension_scale > 0.0 ? tension_scale : 1.0),
      contact_markers_(contact_markers) {}

void MarkerBuilder::restart() {
  delete_all_ = true;
  published_.clear();
}

Marker MarkerBuilder::makeMarker(const std::string& ns, const int id, const int type,
                                 const ros::Time& stamp) const {
  Marker marker;
  marker.header.frame_id = frame_id_;
  marker.header.stamp = stamp;
  marker.ns = ns;
  marker.id = id;
  marker.type = type;
  marker.action = Marker::ADD;
  marker.pose.orientation.w = 1.0;
  marker.frame_locked = false;
  return marker;
}

visualization_msgs::MarkerArray MarkerBuilder::build(const engine::World& world,
                                                     const ros::Time& stamp) {
  WorldSnapshot snapshot;
  takeSnapshot(world, snapshot, {}, contact_markers_);
  return build(snapshot, world.colliders(), stamp);
}

visualization_msgs::MarkerArray MarkerBuilder::build(const WorldSnapshot& world,
                                                     const engine::Colliders& colliders,
                                                     const ros::Time& stamp) {
  visualization_msgs::MarkerArray out;
  if (delete_all_) {
    Marker clear;
    clear.header.frame_id = frame_id_;
    clear.header.stamp = stamp;
    clear.action = Marker::DELETEALL;
    out.markers.push_back(clear);
    delete_all_ = false;
  }
  const std::size_t first = out.markers.size();
  addParticles(world, stamp, out);
  addLinks(world, stamp, out);
  addColliders(colliders, stamp, out);
  addBodies(world.bodies, stamp, out);
  addJoints(world.bodies, stamp, out);
  if (contact_markers_) addContacts(world.bodies, stamp, out);

  std::set<std::pair<std::string, int>> now;
  for (std::size_t i = first; i < out.markers.size(); ++i) {
    now.emplace(out.markers[i].ns, out.markers[i].id);
  }
  for (const auto& [ns, id] : published_) {
    if (now.count({ns, id})) continue;
    Marker gone = makeMarker(ns, id, Marker::SPHERE_LIST, stamp);
    gone.action = Marker::DELETE;
    out.markers.push_back(gone);
  }
  published_ = std::move(now);
  return out;
}

void MarkerBuilder::addParticles(const WorldSnapshot& world, const ros::Time& stamp,
                                 visualization_msgs::MarkerArray& out) const {
  const auto& x = world.positions;
  const auto& radius = world.radii;
  const auto& inverse_mass = world.inverse_masses;
  const std::size_t n = world.ids.size();
  // One list per (radius, movable): ordered keys keep the marker ids stable between frames.
  std::map<std::pair<Real, bool>, std::size_t> list_of;
  for (std::size_t i = 0; i < n; ++i)
    list_of.emplace(std::make_pair(radius[i], inverse_mass[i] > 0.0), 0);
  std::size_t index = 0;
  for (auto& entry : list_of) entry.second = index++;
  std::vector<Marker> lists(list_of.size());
  for (const auto& [key, list] : list_of) {
    Marker& m = lists[list];
    m = makeMarker("particles", static_cast<int>(list), Marker::SPHERE_LIST, stamp);
    // A point particle is still drawn, as a dot of 2 cm.
    const double diameter = std::max(2.0 * key.first, 0.02);
    m.scale.x = m.scale.y = m.scale.z = diameter;
    m.color = key.second ? rgba(1.0f, 0.55f, 0.1f) : rgba(0.5f, 0.5f, 0.5f);
  }
  for (std::size_t i = 0; i < n; ++i) {
    lists[list_of[{radius[i], inverse_mass[i] > 0.0}]].points.push_back(toPointMsg(x.col(i)));
  }
  for (auto& m : lists) out.markers.push_back(std::move(m));
}

void MarkerBuilder::addLinks(const WorldSnapshot& world, const ros::Time& stamp,
                             visualization_msgs::MarkerArray& out) const {
  if (world.links.empty()) return;
  Marker lines = makeMarker("links", 0, Marker::LINE_LIST, stamp);
  lines.scale.x = 0.02;
  lines.color = rgba(1.0f, 1.0f, 1.0f);
  lines.points.reserve(2 * world.links.size());
  lines.colors.reserve(2 * world.links.size());
  for (const LinkSegment& link : world.links) {
    const auto c = tensionColor(link.tension, tension_scale_);
    lines.points.push_back(toPointMsg(link.a));
    lines.points.push_back(toPointMsg(link.b));
    lines.colors.push_back(c);
    lines.colors.push_back(c);
  }
  out.markers.push_back(std::move(lines));
}

void MarkerBuilder::addColliders(const engine::Colliders& colliders, const ros::Time& stamp,
                                 visualization_msgs::MarkerArray& out) const {
  const std_msgs::ColorRGBA grey = rgba(0.5f, 0.52f, 0.55f, 1.0f);
  // Lighter for a surface: seen at a grazing angle it would vanish into the background.
  const std_msgs::ColorRGBA light = rgba(0.9f, 0.9f, 0.95f, 1.0f);
  // Each collider is drawn as its kind describes it (ShapeKind::describe), one marker per part:
  // id = 4 * collider id + part.
  colliders.forEach([&](const auto& shapes) {
    using Shape = typename std::decay_t<decltype(shapes)>::value_type;
    for (const Shape& shape : shapes) {
      const engine::ShapeDescription description = engine::ShapeKind<Shape>::describe(shape);
      for (std::size_t part = 0; part < description.parts.size(); ++part) {
        const engine::ShapePrimitive& primitive = description.parts[part];
        int type = Marker::CUBE;
        switch (primitive.type) {
          case engine::ShapePrimitive::Type::kBox:
            type = Marker::CUBE;
            break;
          case engine::ShapePrimitive::Type::kSphere:
            type = Marker::SPHERE;
            break;
          case engine::ShapePrimitive::Type::kCylinder:
            type = Marker::CYLINDER;
            break;
        }
        Marker m = makeMarker("colliders", static_cast<int>(4 * shape.id + part), type, stamp);
        m.pose.position = toPointMsg(primitive.center);
        m.pose.orientation.x = primitive.orientation.x();
        m.pose.orientation.y = primitive.orientation.y();
        m.pose.orientation.z = primitive.orientation.z();
        m.pose.orientation.w = primitive.orientation.w();
        m.scale.x = primitive.size.x();
        m.scale.y = primitive.size.y();
        m.scale.z = primitive.size.z();
        m.color = description.surface ? light : grey;
        out.markers.push_back(m);
      }
    }
  });
}

}  // namespace node
}  // namespace mass_aggregate_sim
