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

std_msgs::ColorRGBA color(const float r, const float g, const float b, const float a = 1.0f) {
  std_msgs::ColorRGBA c;
  c.r = r;
  c.g = g;
  c.b = b;
  c.a = a;
  return c;
}

// Tension of a spring from a to b: k (l - L), zero for a slack bungee.
Real springTension(const Vec3& a, const Vec3& b, const Real stiffness, const Real rest_length,
                   const bool pull_only) {
  const Real extension = (a - b).norm() - rest_length;
  if (pull_only && extension <= 0.0) return 0.0;
  return stiffness * extension;
}

}  // namespace

std_msgs::ColorRGBA tensionColor(const double tension, const double tension_scale) {
  const float t = static_cast<float>(std::clamp(tension / tension_scale, -1.0, 1.0));
  // White at zero, fading to red when stretched and to blue when compressed.
  if (t >= 0.0f) return color(1.0f, 1.0f - t, 1.0f - t);
  return color(1.0f + t, 1.0f + t, 1.0f);
}

MarkerBuilder::MarkerBuilder(std::string frame_id, const double tension_scale)
    : frame_id_(std::move(frame_id)), tension_scale_(tension_scale > 0.0 ? tension_scale : 1.0) {}

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
  addColliders(world, stamp, out);

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

void MarkerBuilder::addParticles(const engine::World& world, const ros::Time& stamp,
                                 visualization_msgs::MarkerArray& out) const {
  const engine::ParticleStore& particles = world.particles();
  const auto x = particles.positions();
  const auto radius = particles.radii();
  const auto inverse_mass = particles.inverseMasses();
  // One list per (radius, movable): ordered keys keep the marker ids stable between frames.
  std::map<std::pair<Real, bool>, std::size_t> list_of;
  for (std::size_t i = 0; i < particles.size(); ++i) {
    const std::pair<Real, bool> key(radius[i], inverse_mass[i] > 0.0);
    auto it = list_of.find(key);
    if (it == list_of.end()) {
      it = list_of.emplace(key, 0).first;
    }
  }
  std::size_t index = 0;
  for (auto& entry : list_of) entry.second = index++;
  std::vector<Marker> lists(list_of.size());
  for (const auto& [key, list] : list_of) {
    Marker& m = lists[list];
    m = makeMarker("particles", static_cast<int>(list), Marker::SPHERE_LIST, stamp);
    // A point particle is still drawn, as a dot of 2 cm.
    const double diameter = std::max(2.0 * key.first, 0.02);
    m.scale.x = m.scale.y = m.scale.z = diameter;
    m.color = key.second ? color(1.0f, 0.55f, 0.1f) : color(0.5f, 0.5f, 0.5f);
  }
  for (std::size_t i = 0; i < particles.size(); ++i) {
    lists[list_of[{radius[i], inverse_mass[i] > 0.0}]].points.push_back(toPointMsg(x.col(i)));
  }
  for (auto& m : lists) out.markers.push_back(std::move(m));
}

void MarkerBuilder::addLinks(const engine::World& world, const ros::Time& stamp,
                             visualization_msgs::MarkerArray& out) const {
  const engine::ParticleStore& particles = world.particles();
  const engine::ForceGenerators& g = world.generators();
  const auto x = particles.positions();
  const auto at = [&](const engine::ParticleId id) -> Vec3 {
    return x.col(particles.denseIndexUnchecked(id));
  };
  Marker lines = makeMarker("links", 0, Marker::LINE_LIST, stamp);
  lines.scale.x = 0.02;
  lines.color = color(1.0f, 1.0f, 1.0f);
  const auto segment = [&](const Vec3& a, const Vec3& b, const Real tension) {
    const auto c = tensionColor(tension, tension_scale_);
    lines.points.push_back(toPointMsg(a));
    lines.points.push_back(toPointMsg(b));
    lines.colors.push_back(c);
    lines.colors.push_back(c);
  };
  for (const auto& s : g.springs) {
    segment(at(s.a), at(s.b), springTension(at(s.a), at(s.b), s.stiffness, s.rest_length, false));
  }
  for (const auto& s : g.bungees) {
    segment(at(s.a), at(s.b), springTension(at(s.a), at(s.b), s.stiffness, s.rest_length, true));
  }
  for (const auto& s : g.anchored_springs) {
    const Vec3 p = at(s.particle);
    segment(p, s.anchor, springTension(p, s.anchor, s.stiffness, s.rest_length, false));
  }
  for (const auto& s : g.anchored_bungees) {
    const Vec3 p = at(s.particle);
    segment(p, s.anchor, springTension(p, s.anchor, s.stiffness, s.rest_length, true));
  }
  for (const auto& s : g.stiff_springs) {
    const Vec3 p = at(s.particle);
    segment(p, s.anchor, springTension(p, s.anchor, s.stiffness, 0.0, false));
  }
  // Cables and rods are constraints: their tension is the force the resolver applied in the last
  // substep (World::linkTensions, sorted by id), negative for a rod in compression.
  const std::vector<engine::LinkTension> tensions = world.linkTensions();
  const auto tension = [&](const engine::GeneratorId id) -> Real {
    const auto it = std::lower_bound(
        tensions.begin(), tensions.end(), id,
        [](const engine::LinkTension& t, const engine::GeneratorId key) { return t.id < key; });
    return it != tensions.end() && it->id == id ? it->tension : 0.0;
  };
  const engine::Links& links = world.links();
  for (const auto& c : links.cables) segment(at(c.a), at(c.b), tension(c.id));
  for (const auto& c : links.anchored_cables) segment(at(c.particle), c.anchor, tension(c.id));
  for (const auto& r : links.rods) segment(at(r.a), at(r.b), tension(r.id));
  for (const auto& r : links.anchored_rods) segment(at(r.particle), r.anchor, tension(r.id));
  if (!lines.points.empty()) out.markers.push_back(std::move(lines));
}

void MarkerBuilder::addColliders(const engine::World& world, const ros::Time& stamp,
                                 visualization_msgs::MarkerArray& out) const {
  const engine::Colliders& colliders = world.colliders();
  const std_msgs::ColorRGBA grey = color(0.5f, 0.52f, 0.55f, 1.0f);
  // Each collider is its own marker(s): id = 4 * collider id + part.
  const auto shape = [&](const engine::ColliderId id, const int part, const int type,
                         const Vec3& center, const Eigen::Quaterniond& orientation,
                         const Vec3& scale) {
    Marker m = makeMarker("colliders", static_cast<int>(4 * id + part), type, stamp);
    m.pose.position = toPointMsg(center);
    m.pose.orientation.x = orientation.x();
    m.pose.orientation.y = orientation.y();
    m.pose.orientation.z = orientation.z();
    m.pose.orientation.w = orientation.w();
    m.scale.x = scale.x();
    m.scale.y = scale.y();
    m.scale.z = scale.z();
    m.color = grey;
    out.markers.push_back(m);
  };
  for (const auto& plane : colliders.planes) {
    // A 40 m square slab whose top face is the plane, centred on the plane's point nearest the
    // origin (normal.x = offset).
    shape(plane.id, 0, Marker::CUBE, plane.normal * (plane.offset - 0.005),
          Eigen::Quaterniond::FromTwoVectors(Vec3::UnitZ(), plane.normal), Vec3(40, 40, 0.01));
    // Lighter than the other shapes: seen at a grazing angle it would vanish into the background.
    out.markers.back().color = color(0.9f, 0.9f, 0.95f, 1.0f);
  }
  for (const auto& sphere : colliders.spheres) {
    shape(sphere.id, 0, Marker::SPHERE, sphere.center, Eigen::Quaterniond::Identity(),
          Vec3::Constant(2.0 * sphere.radius));
  }
  for (const auto& box : colliders.boxes) {
    shape(box.id, 0, Marker::CUBE, box.center, box.orientation.normalized(),
          2.0 * box.half_extents);
  }
  for (const auto& capsule : colliders.capsules) {
    const Vec3 axis = capsule.b - capsule.a;
    const Real d = 2.0 * capsule.radius;
    shape(capsule.id, 0, Marker::CYLINDER, 0.5 * (capsule.a + capsule.b),
          Eigen::Quaterniond::FromTwoVectors(Vec3::UnitZ(), axis), Vec3(d, d, axis.norm()));
    shape(capsule.id, 1, Marker::SPHERE, capsule.a, Eigen::Quaterniond::Identity(),
          Vec3::Constant(d));
    shape(capsule.id, 2, Marker::SPHERE, capsule.b, Eigen::Quaterniond::Identity(),
          Vec3::Constant(d));
  }
}

}  // namespace node
}  // namespace mass_aggregate_sim
