// The drag and buoyancy service handlers of SimNode (~add_force_field, ~remove_force_field).
#include "mass_aggregate_sim/node/force_field_conversions.h"
#include "mass_aggregate_sim/node/sim_node.h"
#include "service_helpers.h"

namespace mass_aggregate_sim {
namespace node {

bool SimNode::onAddForceField(AddForceField::Request& req, AddForceField::Response& res) {
  auto request = toForceFieldRequest(req);
  if (!request) return answer(res, false, request.message());
  ForceFieldRequest field = *request;
  return runOnWorldThread(res, [&] {
    const auto frame = referenceFrame(req.frame_id);
    if (!frame) {
      answer(res, false, "frame_id: " + frame.message());
      return;
    }
    AddForceField::Request resolved = req;
    placeForceFieldRequest(*frame, field, resolved);  // recorded in the world, whatever the type
    const auto ids = sim_.addForceFields(field);
    if (!ids) {
      answer(res, false, ids.message());
      return;
    }
    res.force_ids.assign((*ids).begin(), (*ids).end());
    recordCommand("add_force_field", resolved);
    answer(res, true,
           "added " + std::to_string((*ids).size()) + " " + req.type + " at " +
               describeTime(sim_.world()));
  });
}

bool SimNode::onRemoveForceField(RemoveForceField::Request& req, RemoveForceField::Response& res) {
  return runOnWorldThread(res, [&] {
    const engine::Status removed = sim_.removeForceField(req.force_id);
    if (!removed) {
      answer(res, false, removed.message());
      return;
    }
    recordCommand("remove_force_field", req);
    answer(res, true, "removed force field " + std::to_string(req.force_id));
  });
}

}  // namespace node
}  // namespace mass_aggregate_sim
