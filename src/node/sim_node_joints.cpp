// The joint and body-spring service handlers of SimNode.
#include "mass_aggregate_sim/node/body_conversions.h"
#include "mass_aggregate_sim/node/input_limits.h"
#include "mass_aggregate_sim/node/sim_node.h"
#include "service_helpers.h"

namespace mass_aggregate_sim {
namespace node {

bool SimNode::onAddJoint(AddJoint::Request& req, AddJoint::Response& res) {
  auto request = toJointRequest(req);
  if (!request) return answer(res, false, request.message());
  JointRequest joint = *request;
  return runOnWorldThread(res, [&] {
    const auto frame = referenceFrame(req.frame_id);
    if (!frame) {
      answer(res, false, "frame_id: " + frame.message());
      return;
    }
    AddJoint::Request resolved = req;
    placeJointRequest(*frame, joint, resolved);
    const auto id = sim_.addJoint(joint);
    if (!id) {
      answer(res, false, id.message());
      return;
    }
    res.joint_id = *id;
    recordCommand("add_joint", resolved);
    answer(res, true,
           "added " + req.type + " joint " + std::to_string(*id) + " (" +
               jointName(sim_.jointNames(), *id) + ") at " + describeTime(sim_.world()));
  });
}

bool SimNode::onAddBodySpring(AddBodySpring::Request& req, AddBodySpring::Response& res) {
  auto request = toBodySpringRequest(req);
  if (!request) return answer(res, false, request.message());
  BodySpringRequest spring = *request;
  return runOnWorldThread(res, [&] {
    const auto frame = referenceFrame(req.frame_id);
    if (!frame) {
      answer(res, false, "frame_id: " + frame.message());
      return;
    }
    AddBodySpring::Request resolved = req;
    placeBodySpringRequest(*frame, spring, resolved);
    const auto id = sim_.addBodySpring(spring);
    if (!id) {
      answer(res, false, id.message());
      return;
    }
    res.link_id = *id;
    recordCommand("add_body_spring", resolved);
    answer(
        res, true,
        "added body " + req.type + " " + std::to_string(*id) + " at " + describeTime(sim_.world()));
  });
}

bool SimNode::onRemoveJoint(RemoveJoint::Request& req, RemoveJoint::Response& res) {
  return runOnWorldThread(res, [&] {
    const engine::Status removed = sim_.removeJoint(req.joint_id);
    if (!removed) {
      answer(res, false, removed.message());
      return;
    }
    recordCommand("remove_joint", req);
    answer(res, true, "removed joint " + std::to_string(req.joint_id));
  });
}

bool SimNode::onSetHingeMotor(SetHingeMotor::Request& req, SetHingeMotor::Response& res) {
  return runOnWorldThread(res, [&] {
    SetHingeMotor::Request resolved = req;
    if (!req.name.empty()) {
      const auto id = findJoint(sim_.world(), sim_.jointNames(), req.name);
      if (!id) {
        answer(res, false, "no joint named " + quoteInput(req.name));
        return;
      }
      resolved.joint_id = *id;
      resolved.name.clear();
    }
    const engine::Status set =
        sim_.setHingeMotor(resolved.joint_id, req.enabled, req.speed, req.max_torque);
    if (!set) {
      answer(res, false, set.message());
      return;
    }
    recordCommand("set_hinge_motor", resolved);
    answer(res, true,
           std::string(req.enabled ? "motor on" : "motor off") + " for hinge " +
               std::to_string(resolved.joint_id) + " at " + describeTime(sim_.world()));
  });
}

}  // namespace node
}  // namespace mass_aggregate_sim
