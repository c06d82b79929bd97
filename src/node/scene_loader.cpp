#include "mass_aggregate_sim/node/scene_loader.h"

#include <xmlrpcpp/XmlRpcException.h>

#include <cmath>
#include <optional>
#include <random>
#include <utility>
#include <vector>

#include "mass_aggregate_sim/engine/integrators/integrator.h"
#include "mass_aggregate_sim/node/force_fields.h"
#include "mass_aggregate_sim/node/input_limits.h"
#include "mass_aggregate_sim/node/links.h"
#include "mass_aggregate_sim/node/scene_bodies.h"
#include "mass_aggregate_sim/node/scene_contacts.h"
#include "mass_aggregate_sim/node/xmlrpc_reader.h"

namespace mass_aggregate_sim {
namespace node {
namespace {

using engine::ParticleSpec;
using engine::Real;
using engine::Vec3;
using XmlRpc::XmlRpcValue;

constexpr Real kDefaultRate = 60.0;
const Vec3 kDefaultGravity(0.0, 0.0, -9.81);

std::string indexed(const std::string& key, const int i) {
  return key + "[" + std::to_string(i) + "]";
}

// The properties every particle source shares: mass (or fixed), radius, damping, velocity,
// acceleration.
ParticleSpec readParticleProperties(XmlRpcValue& s, const std::string& key) {
  ParticleSpec spec;
  const bool fixed = boolOr(s, key, "fixed", false);
  const Real mass = realOr(s, key, "mass", 1.0);
  if (!fixed && mass <= 0.0) throw ParamError(key + ".mass", "must be > 0 (or set fixed: true)");
  spec.inverse_mass = fixed ? 0.0 : 1.0 / mass;
  // Radius and damping are checked by the engine when the particle is added.
  spec.radius = realOr(s, key, "radius", 0.1);
  spec.damping = realOr(s, key, "damping", 1.0);
  spec.velocity = fixed ? Vec3::Zero() : vec3Or(s, key, "velocity", Vec3::Zero());
  spec.acceleration = vec3Or(s, key, "acceleration", Vec3::Zero());
  return spec;
}

class SceneBuilder {
 public:
  explicit SceneBuilder(const SceneOverrides& overrides) : overrides_(overrides) {}

  LoadedScene build(XmlRpcValue& scene) {
    LoadedScene loaded;
    const std::string key = "scene";
    if (scene.getType() == XmlRpcValue::TypeInvalid) {
      loaded.world = makeWorld(config(scene, key, loaded), key);
      return loaded;
    }
    checkKeys(scene, key,
              {"name", "description", "rate", "dt", "substeps", "integrator", "gravity",
               "particles", "lines", "blocks", "links", "forces", "colliders", "collisions",
               "body_solver", "bodies", "joints"});
    loaded.name = stringOr(scene, key, "name", "");
    loaded.description = stringOr(scene, key, "description", "");
    world_ = makeWorld(config(scene, key, loaded), key);
    if (has(scene, "collisions"))
      readCollisionSettings(scene["collisions"], key + ".collisions", world_);
    if (has(scene, "colliders")) readColliders(scene["colliders"], key + ".colliders", world_);
    if (has(scene, "particles")) readParticles(scene["particles"], key + ".particles");
    if (has(scene, "lines")) readLines(scene["lines"], key + ".lines");
    if (has(scene, "blocks")) readBlocks(scene["blocks"], key + ".blocks");
    if (has(scene, "links")) readLinks(scene["links"], key + ".links");
    const BodyLimits body_limits{overrides_.max_bodies, overrides_.max_joints,
                                 overrides_.world_frame};
    if (has(scene, "body_solver"))
      readBodySolver(scene["body_solver"], key + ".body_solver", world_);
    if (has(scene, "bodies")) readBodies(scene["bodies"], key + ".bodies", world_, body_limits);
    if (has(scene, "joints")) {
      readJoints(scene["joints"], key + ".joints", world_, body_limits, loaded.joint_names);
    }
    // After the bodies: a force may act on them.
    if (has(scene, "forces")) readForces(scene["forces"], key + ".forces");
    loaded.world = world_;
    return loaded;
  }

 private:
  // The engine checks the config as a whole (e.g. dt <= 1 s, so a rate below 1 Hz): a refusal
  // stops the load with its reason instead of running on other settings.
  static engine::World makeWorld(const engine::WorldConfig& config, const std::string& key) {
    engine::Result<engine::World> world = engine::World::create(config);
    if (!world) throw ParamError(key, world.message());
    return std::move(world).take();
  }

  engine::WorldConfig config(XmlRpcValue& scene, const std::string& key, LoadedScene& loaded) {
    engine::WorldConfig config;
    // The scene gives its step either as a rate (Hz) or as dt (s), not both.
    if (has(scene, "rate") && has(scene, "dt")) throw ParamError(key, "give rate or dt, not both");
    std::string rate_key = key + ".rate";
    loaded.rate = realOr(scene, key, "rate", kDefaultRate);
    std::optional<Real> dt;
    if (has(scene, "dt")) {
      rate_key = key + ".dt";
      dt = readReal(scene["dt"], rate_key);
      if (!(*dt > 0.0)) throw ParamError(rate_key, "must be > 0 s");
      loaded.rate = 1.0 / *dt;
    }
    loaded.own.rate = loaded.rate;
    loaded.own.rate_given = has(scene, "rate") || has(scene, "dt");
    if (overrides_.rate) {
      loaded.rate = *overrides_.rate;
      rate_key = "~rate";
      dt.reset();
    }
    if (!(loaded.rate > 0.0) || loaded.rate > 100000.0) {
      throw ParamError(rate_key, "must be in (0, 100000] steps per second");
    }
    config.dt = dt ? *dt : 1.0 / loaded.rate;
    config.max_frame_time = std::max(config.max_frame_time, config.dt);
    loaded.own.substeps = intOr(scene, key, "substeps", 1);
    loaded.own.substeps_given = has(scene, "substeps");
    config.substeps = overrides_.substeps ? *overrides_.substeps : loaded.own.substeps;
    if (config.substeps < 1 || config.substeps > 1000) {
      throw ParamError(overrides_.substeps ? "~substeps" : key + ".substeps",
                       "must be in [1, 1000]");
    }
    loaded.own.integrator = stringOr(scene, key, "integrator", "semi_implicit_euler");
    loaded.own.integrator_given = has(scene, "integrator");
    const std::string integrator =
        overrides_.integrator ? *overrides_.integrator : loaded.own.integrator;
    const auto parsed = engine::parseIntegrator(integrator);
    if (!parsed) {
      throw ParamError(overrides_.integrator ? "~integrator" : key + ".integrator",
                       "unknown integrator " + quoteInput(integrator) +
                           " (known: " + engine::integratorNames() + ")");
    }
    config.integrator = *parsed;
    loaded.own.gravity = vec3Or(scene, key, "gravity", kDefaultGravity);
    loaded.own.gravity_given = has(scene, "gravity");
    config.gravity = overrides_.gravity ? *overrides_.gravity : loaded.own.gravity;
    const engine::Status gravity =
        checkVector(config.gravity, kMaxAcceleration, "gravity", "m/s^2");
    if (!gravity) {
      throw ParamError(overrides_.gravity ? "~gravity" : key + ".gravity",
                       gravity.message().substr(std::string("gravity: ").size()));
    }
    const engine::Status valid = engine::validateConfig(config);
    if (!valid) throw ParamError(key, valid.message());
    return config;
  }

  void add(const ParticleSpec& spec, const std::string& key) {
    if (world_.particles().size() >= overrides_.max_particles) {
      throw ParamError(key, "the scene has more than ~max_particles (" +
                                std::to_string(overrides_.max_particles) + ") particles");
    }
    if (!spec.name.empty() && world_.particles().findByName(spec.name)) {
      throw ParamError(key, "the particle name " + quoteInput(spec.name) + " is used twice");
    }
    throwIfBad(checkParticleSpec(spec, overrides_.world_frame), key);
    const auto added = world_.addParticle(spec);
    if (!added) throw ParamError(key, added.message());
  }

  void readParticles(XmlRpcValue& list, const std::string& key) {
    requireArray(list, key);
    for (int i = 0; i < list.size(); ++i) {
      const std::string k = indexed(key, i);
      XmlRpcValue& p = list[i];
      checkKeys(
          p, k,
          {"name", "position", "velocity", "acceleration", "mass", "fixed", "radius", "damping"});
      ParticleSpec spec = readParticleProperties(p, k);
      spec.name = stringOr(p, k, "name", "");
      if (!has(p, "position")) throw ParamError(k + ".position", "is required");
      spec.position = readVec3(p["position"], k + ".position");
      add(spec, k);
    }
  }

  // Evenly spaced particles from start to end, named <name>_0 ... <name>_<count-1>, optionally
  // linked one to the next.
  void readLines(XmlRpcValue& list, const std::string& key) {
    requireArray(list, key);
    for (int i = 0; i < list.size(); ++i) {
      const std::string k = indexed(key, i);
      XmlRpcValue& line = list[i];
      checkKeys(line, k,
                {"name", "start", "end", "count", "velocity", "acceleration", "mass", "fixed",
                 "radius", "damping", "fixed_indices", "link"});
      const std::string name = stringOr(line, k, "name", "");
      if (name.empty()) throw ParamError(k + ".name", "is required (particles are <name>_<i>)");
      if (!has(line, "start") || !has(line, "end")) {
        throw ParamError(k, "start and end are required");
      }
      const Vec3 start = readVec3(line["start"], k + ".start");
      const Vec3 end = readVec3(line["end"], k + ".end");
      const int count = intOr(line, k, "count", 2);
      if (count < 2) throw ParamError(k + ".count", "must be at least 2");
      if (static_cast<std::size_t>(count) > overrides_.max_particles) {
        throw ParamError(k + ".count", "more than ~max_particles (" +
                                           std::to_string(overrides_.max_particles) + ")");
      }
      ParticleSpec spec = readParticleProperties(line, k);
      std::vector<bool> fixed(static_cast<std::size_t>(count), spec.inverse_mass == 0.0);
      if (has(line, "fixed_indices")) {
        XmlRpcValue& indices = line["fixed_indices"];
        const std::string ik = k + ".fixed_indices";
        requireArray(indices, ik);
        for (int j = 0; j < indices.size(); ++j) {
          int index = readInt(indices[j], indexed(ik, j));
          if (index < 0) index += count;  // -1 is the last particle
          if (index < 0 || index >= count) throw ParamError(indexed(ik, j), "out of range");
          fixed[static_cast<std::size_t>(index)] = true;
        }
      }
      const Real inverse_mass = spec.inverse_mass;
      const Vec3 velocity = spec.velocity;
      for (int j = 0; j < count; ++j) {
        spec.name = name + "_" + std::to_string(j);
        spec.position = start + (end - start) * (static_cast<Real>(j) / (count - 1));
        const bool is_fixed = fixed[static_cast<std::size_t>(j)];
        spec.inverse_mass = is_fixed ? 0.0 : inverse_mass;
        spec.velocity = is_fixed ? Vec3::Zero() : velocity;
        add(spec, k);
      }
      if (has(line, "link")) {
        XmlRpcValue& link = line["link"];
        for (int j = 0; j + 1 < count; ++j) {
          LinkRequest request = readLinkProperties(link, k + ".link");
          request.a.name = name + "_" + std::to_string(j);
          request.b = ParticleRef{0, name + "_" + std::to_string(j + 1)};
          addLinkOrThrow(request, k + ".link");
        }
      }
    }
  }

  // A block of count[0] x count[1] x count[2] particles from origin, spacing apart, each moved
  // by a reproducible random offset of up to jitter per axis.
  void readBlocks(XmlRpcValue& list, const std::string& key) {
    requireArray(list, key);
    for (int i = 0; i < list.size(); ++i) {
      const std::string k = indexed(key, i);
      XmlRpcValue& block = list[i];
      checkKeys(block, k,
                {"name", "origin", "count", "spacing", "jitter", "seed", "velocity", "acceleration",
                 "mass", "fixed", "radius", "damping"});
      const std::string name = stringOr(block, k, "name", "");
      const Vec3 origin = vec3Or(block, k, "origin", Vec3::Zero());
      if (!has(block, "count")) throw ParamError(k + ".count", "is required ([nx, ny, nz])");
      XmlRpcValue& count_value = block["count"];
      requireArray(count_value, k + ".count");
      if (count_value.size() != 3) throw ParamError(k + ".count", "expected [nx, ny, nz]");
      int count[3];
      long total = 1;
      for (int axis = 0; axis < 3; ++axis) {
        count[axis] = readInt(count_value[axis], indexed(k + ".count", axis));
        if (count[axis] < 1) throw ParamError(indexed(k + ".count", axis), "must be >= 1");
        total *= count[axis];
        if (total > static_cast<long>(overrides_.max_particles)) {
          throw ParamError(k + ".count", "more than ~max_particles (" +
                                             std::to_string(overrides_.max_particles) + ")");
        }
      }
      Vec3 spacing;
      if (has(block, "spacing") && block["spacing"].getType() == XmlRpcValue::TypeArray) {
        spacing = readVec3(block["spacing"], k + ".spacing");
      } else {
        spacing.setConstant(realOr(block, k, "spacing", 0.25));
      }
      if ((spacing.array() <= 0.0).any()) throw ParamError(k + ".spacing", "must be > 0");
      const Real jitter = realOr(block, k, "jitter", 0.0);
      if (jitter < 0.0) throw ParamError(k + ".jitter", "must be >= 0");
      std::mt19937_64 random(static_cast<std::uint64_t>(intOr(block, k, "seed", 1)));
      // A uniform number in [-1, 1) from the top 53 bits: the same on every platform.
      const auto uniform = [&random]() {
        return static_cast<Real>(random() >> 11) * 0x1.0p-52 - 1.0;
      };
      ParticleSpec spec = readParticleProperties(block, k);
      int index = 0;
      for (int z = 0; z < count[2]; ++z) {
        for (int y = 0; y < count[1]; ++y) {
          for (int x = 0; x < count[0]; ++x) {
            spec.position = origin + Vec3(x, y, z).cwiseProduct(spacing);
            if (jitter > 0.0) {
              const Real dx = uniform();
              const Real dy = uniform();
              const Real dz = uniform();
              spec.position += jitter * Vec3(dx, dy, dz);
            }
            spec.name = name.empty() ? "" : name + "_" + std::to_string(index);
            add(spec, k);
            ++index;
          }
        }
      }
    }
  }

  LinkRequest readLinkProperties(XmlRpcValue& s, const std::string& k) {
    checkKeys(s, k,
              {"type", "a", "b", "anchor", "stiffness", "damping", "rest_length", "max_length",
               "length", "restitution"});
    LinkRequest request;
    const std::string type = stringOr(s, k, "type", "");
    const auto parsed = parseLinkType(type);
    if (!parsed) {
      throw ParamError(k + ".type", "unknown link type " + quoteInput(type) +
                                        " (known: " + linkTypeNames() + ")");
    }
    request.type = *parsed;
    request.stiffness = realOr(s, k, "stiffness", 0.0);
    request.damping = realOr(s, k, "damping", 0.0);
    request.rest_length = realOr(s, k, "rest_length", -1.0);
    request.max_length = realOr(s, k, "max_length", -1.0);
    request.length = realOr(s, k, "length", -1.0);
    request.restitution = realOr(s, k, "restitution", 0.0);
    return request;
  }

  void checkLinkCount(const std::string& key) const {
    if (world_.generators().size() + world_.links().size() + world_.bodyGenerators().size() >=
        overrides_.max_links) {
      throw ParamError(key, "more than ~max_links (" + std::to_string(overrides_.max_links) +
                                ") links and force generators");
    }
  }

  void addLinkOrThrow(const LinkRequest& request, const std::string& key) {
    checkLinkCount(key);
    const auto added = addLink(world_, request);
    if (!added) throw ParamError(key, added.message());
  }

  void readLinks(XmlRpcValue& list, const std::string& key) {
    requireArray(list, key);
    for (int i = 0; i < list.size(); ++i) {
      const std::string k = indexed(key, i);
      XmlRpcValue& link = list[i];
      LinkRequest request = readLinkProperties(link, k);
      request.a.name = stringOr(link, k, "a", "");
      if (request.a.name.empty()) throw ParamError(k + ".a", "is required (a particle name)");
      const bool to_b = has(link, "b");
      if (to_b == has(link, "anchor")) throw ParamError(k, "give exactly one of b and anchor");
      if (to_b) {
        request.b = ParticleRef{0, readString(link["b"], k + ".b")};
      } else {
        request.anchor = readVec3(link["anchor"], k + ".anchor");
      }
      addLinkOrThrow(request, k);
    }
  }

  // The particles a force applies to: `all: true`, or `particles: [names]`.
  std::vector<engine::ParticleId> readTargets(XmlRpcValue& s, const std::string& k) {
    std::vector<engine::ParticleId> ids;
    const bool all = boolOr(s, k, "all", false);
    if (all == has(s, "particles")) throw ParamError(k, "give exactly one of all and particles");
    if (all) {
      for (std::size_t i = 0; i < world_.particles().size(); ++i) {
        if (world_.particles().inverseMasses()[i] > 0.0) ids.push_back(world_.particles().idAt(i));
      }
      return ids;
    }
    XmlRpcValue& names = s["particles"];
    requireArray(names, k + ".particles");
    for (int j = 0; j < names.size(); ++j) {
      const std::string name = readString(names[j], indexed(k + ".particles", j));
      const auto id = world_.particles().findByName(name);
      if (!id)
        throw ParamError(indexed(k + ".particles", j), "no particle named " + quoteInput(name));
      ids.push_back(*id);
    }
    return ids;
  }

  // The liquid and depth of a buoyancy on particles or on bodies (the kinds' defaults where left
  // out).
  template <typename Kind>
  static void readBuoyancy(XmlRpcValue& force, const std::string& k, Kind& buoyancy) {
    buoyancy.max_depth = realOr(force, k, "max_depth", buoyancy.max_depth);
    buoyancy.volume = realOr(force, k, "volume", buoyancy.volume);
    buoyancy.liquid_density = realOr(force, k, "liquid_density", buoyancy.liquid_density);
    buoyancy.surface_height = realOr(force, k, "surface_height", buoyancy.surface_height);
    buoyancy.up = vec3Or(force, k, "up", buoyancy.up);
  }

  // One generator of the kind on each body of `bodies: [names]`.
  template <typename Kind>
  void addOnBodies(Kind generator, XmlRpcValue& force, const std::string& k) {
    for (const auto id : readBodyTargets(force, k, world_)) {
      checkLinkCount(k);
      generator.body = id;
      const auto added = world_.addBodyGenerator(generator);
      if (!added) throw ParamError(k, added.message());
    }
  }

  void readForces(XmlRpcValue& list, const std::string& key) {
    requireArray(list, key);
    for (int i = 0; i < list.size(); ++i) {
      const std::string k = indexed(key, i);
      XmlRpcValue& force = list[i];
      const std::string type = stringOr(force, k, "type", "");
      if (type == "spring" || type == "bungee") {
        checkLinkCount(k);
        readPointSpring(force, k, world_);
      } else if (type == "drag" && has(force, "bodies")) {
        checkKeys(force, k, {"type", "bodies", "k1", "k2", "angular"});
        engine::BodyDrag drag;
        drag.k1 = realOr(force, k, "k1", 0.0);
        drag.k2 = realOr(force, k, "k2", 0.0);
        drag.angular = realOr(force, k, "angular", 0.0);
        addOnBodies(drag, force, k);
      } else if (type == "buoyancy" && has(force, "bodies")) {
        checkKeys(force, k,
                  {"type", "bodies", "model", "max_depth", "volume", "liquid_density",
                   "surface_height", "up"});
        engine::BodyBuoyancy buoyancy;
        const auto model = parseBuoyancyModel(stringOr(force, k, "model", "shapes"));
        if (!model) throw ParamError(k + ".model", model.message());
        buoyancy.model = *model;
        readBuoyancy(force, k, buoyancy);
        addOnBodies(buoyancy, force, k);
      } else if (type == "drag") {
        checkKeys(force, k, {"type", "all", "particles", "k1", "k2"});
        const Real k1 = realOr(force, k, "k1", 0.0);
        const Real k2 = realOr(force, k, "k2", 0.0);
        for (const auto id : readTargets(force, k)) {
          checkLinkCount(k);
          const auto added = world_.addGenerator(engine::Drag{id, k1, k2});
          if (!added) throw ParamError(k, added.message());
        }
      } else if (type == "buoyancy") {
        checkKeys(force, k,
                  {"type", "all", "particles", "max_depth", "volume", "liquid_density",
                   "surface_height", "up"});
        engine::Buoyancy buoyancy;
        readBuoyancy(force, k, buoyancy);
        for (const auto id : readTargets(force, k)) {
          buoyancy.particle = id;
          checkLinkCount(k);
          const auto added = world_.addGenerator(buoyancy);
          if (!added) throw ParamError(k, added.message());
        }
      } else {
        throw ParamError(k + ".type", "unknown force " + quoteInput(type) +
                                          " (known: drag, buoyancy, spring, bungee)");
      }
    }
  }

  SceneOverrides overrides_;
  engine::World world_;
};

}  // namespace

engine::Result<LoadedScene> loadScene(const XmlRpcValue& scene, const SceneOverrides& overrides) {
  XmlRpcValue copy = scene;
  try {
    return SceneBuilder(overrides).build(copy);
  } catch (const ParamError& error) {
    return engine::Status::error(error.what());
  } catch (const XmlRpc::XmlRpcException& error) {
    return engine::Status::error("scene: " + error.getMessage());
  }
}

}  // namespace node
}  // namespace mass_aggregate_sim
