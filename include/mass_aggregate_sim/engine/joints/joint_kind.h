#pragma once

#include <cstdint>
#include <vector>

#include "mass_aggregate_sim/engine/bodies/body_spec.h"
#include "mass_aggregate_sim/engine/core/particle_id.h"
#include "mass_aggregate_sim/engine/core/status.h"
#include "mass_aggregate_sim/engine/core/transform.h"

namespace mass_aggregate_sim {
namespace engine {

// Names one joint; never reused within a world.
using JointId = std::uint32_t;

// One end of a joint: a point on a body (in the body's own frame), a particle, or a fixed point
// in the world (neither set).
struct JointEnd {
  BodyId body;
  ParticleId particle;
  Vec3 point = Vec3::Zero();

  static JointEnd onBody(const BodyId body, const Vec3& local = Vec3::Zero()) {
    JointEnd end;
    end.body = body;
    end.point = local;
    return end;
  }
  static JointEnd atParticle(const ParticleId particle) {
    JointEnd end;
    end.particle = particle;
    return end;
  }
  static JointEnd inWorld(const Vec3& point) {
    JointEnd end;
    end.point = point;
    return end;
  }
  bool isBody() const { return body.valid(); }
  bool isParticle() const { return particle.valid(); }
  bool isWorld() const { return !isBody() && !isParticle(); }
};

// What a joint did in the last substep, as a force and a torque on its end b (world frame, N and
// N m; its end a felt the opposite): the accumulated impulses over the substep's length.
struct JointReaction {
  JointId id = 0;
  Vec3 force = Vec3::Zero();
  Vec3 torque = Vec3::Zero();
};

class BodyStore;
class ParticleStore;
struct JointRow;

// What a joint kind measures when it is added: the bodies' and particles' poses.
struct JointScene {
  const BodyStore& bodies;
  const ParticleStore& particles;
};
struct SolverBody;

// How a joint kind is solved in a substep (body_stages.cpp): h, whether the bias that removes the
// joint's error acts (solve) or not (relax), and the solver bodies.
struct JointPass {
  std::vector<SolverBody>& bodies;
  Real h;
  bool use_bias;
};

// What the engine knows of a joint kind K: JointKind<K>, specialised in K's own header and
// defined in its own source file (joints/<kind>.cpp). Every place that handles joints (adding and
// removing them, bodies and particles removed with their joints, the solver, the state hash,
// scenes, markers) visits JointKinds (joints.h), so a kind that lacks one does not compile:
//   kName                  the kind's name in scenes and messages
//   kTurns                 whether it holds rotation: then its ends are bodies or the world (a
//                          particle has no orientation)
//   fields(K&, visitor)    the fields a scene sets besides the two ends
//   validate(K&, scene)    refuses bad values (Status says why); takes what it measures from the
//                          bodies' poses when it is added (a hinge's axis in each body's frame,
//                          a distance's current length, the relative orientation to keep)
//   warmStart(k, row, bodies), solve(k, row, pass)
//                          the rows of the joint: its impulses of the last substep applied
//                          again, then one pass (soft with use_bias, like the contacts)
//   reaction(k, h)         the force and torque of the last substep
//   addToHash(k, hasher)   its state (the impulses it carries)
template <typename Kind>
struct JointKind;

}  // namespace engine
}  // namespace mass_aggregate_sim
