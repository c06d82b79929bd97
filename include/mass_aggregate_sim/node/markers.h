#pragma once

#include <ros/time.h>
#include <visualization_msgs/MarkerArray.h>

#include <set>
#include <string>
#include <utility>

#include "mass_aggregate_sim/engine/world/world.h"
#include "mass_aggregate_sim/node/snapshot.h"

namespace mass_aggregate_sim {
namespace node {

// Builds the RViz view of a world: particles as one SPHERE_LIST per radius (so 10,000 particles
// stay a handful of markers), links as one LINE_LIST coloured by tension (blue compressed, white
// slack, red stretched, saturating at tension_scale), colliders as their shapes (grey,
// translucent); bodies as their shapes' parts (BodyShapeKind::describe: boxes, spheres, a capsule
// as a cylinder and two spheres) coloured by type and dimmed while sleeping, joints as one
// LINE_LIST, and with `contact_markers` each body contact point as a line along its normal.
// Remembers what it published so a marker that disappears gets a DELETE, and starts with
// DELETEALL after restart().
class MarkerBuilder {
 public:
  MarkerBuilder(std::string frame_id, double tension_scale, bool contact_markers = false);

  // From a snapshot (the publishing thread) and the world's colliders.
  visualization_msgs::MarkerArray build(const WorldSnapshot& world,
                                        const engine::Colliders& colliders, const ros::Time& stamp);
  visualization_msgs::MarkerArray build(const engine::World& world, const ros::Time& stamp);
  // The next array starts with DELETEALL (after a reset or a new scene).
  void restart();

 private:
  void addParticles(const WorldSnapshot& world, const ros::Time& stamp,
                    visualization_msgs::MarkerArray& out) const;
  void addLinks(const WorldSnapshot& world, const ros::Time& stamp,
                visualization_msgs::MarkerArray& out) const;
  void addColliders(const engine::Colliders& colliders, const ros::Time& stamp,
                    visualization_msgs::MarkerArray& out) const;
  // body_markers.cpp
  void addBodies(const BodySnapshot& bodies, const ros::Time& stamp,
                 visualization_msgs::MarkerArray& out) const;
  void addJoints(const BodySnapshot& bodies, const ros::Time& stamp,
                 visualization_msgs::MarkerArray& out) const;
  void addContacts(const BodySnapshot& bodies, const ros::Time& stamp,
                   visualization_msgs::MarkerArray& out) const;
  visualization_msgs::Marker makeMarker(const std::string& ns, int id, int type,
                                        const ros::Time& stamp) const;

  std::string frame_id_;
  double tension_scale_;
  bool contact_markers_;
  bool delete_all_ = true;
  std::set<std::pair<std::string, int>> published_;
};

// An RGBA colour, each component in [0, 1].
std_msgs::ColorRGBA rgba(float r, float g, float b, float a = 1.0f);
// The colour of a link carrying `tension` (N, negative when compressed).
std_msgs::ColorRGBA tensionColor(double tension, double tension_scale);
// The colour of a body: by type, dimmed while it sleeps.
std_msgs::ColorRGBA bodyColor(engine::BodyType type, bool sleeping);

}  // namespace node
}  // namespace mass_aggregate_sim
