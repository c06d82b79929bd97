#pragma once
// ~add_force_field's message and the node's ForceFieldRequest.

#include "mass_aggregate_sim/AddForceField.h"
#include "mass_aggregate_sim/node/body_requests.h"
#include "mass_aggregate_sim/node/force_fields.h"

namespace mass_aggregate_sim {
namespace node {

// The request with its surface still in the message's frame_id: the type and model checked, the
// targets listed (ids then names, particles then bodies), a zero up taken as +z (the numbers are
// the engine's to check).
engine::Result<ForceFieldRequest> toForceFieldRequest(const AddForceField::Request& msg);
// The surface moved from `frame` into the world (up turned, surface_height measured from the
// world's origin); the message updated to match (frame_id cleared), as it is recorded.
void placeForceFieldRequest(const ReferenceFrame& frame, ForceFieldRequest& request,
                            AddForceField::Request& msg);

}  // namespace node
}  // namespace mass_aggregate_sim
