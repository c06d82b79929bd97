#pragma once

#include <xmlrpcpp/XmlRpcValue.h>

#include <initializer_list>
#include <stdexcept>
#include <string>
#include <vector>

#include "mass_aggregate_sim/engine/core/status.h"
#include "mass_aggregate_sim/engine/core/types.h"

namespace mass_aggregate_sim {
namespace node {

// A bad value in a parameter tree: `key` is its full path (e.g. scene.particles[2].mass).
class ParamError : public std::runtime_error {
 public:
  ParamError(const std::string& key, const std::string& reason)
      : std::runtime_error(key + ": " + reason), key_(key), reason_(reason) {}
  const std::string& key() const { return key_; }
  const std::string& reason() const { return reason_; }

 private:
  std::string key_;
  std::string reason_;
};

// Throws a refusal of the form "field: reason" as ParamError(key + "." + field, reason); a message
// without a field stays under key. Does nothing for an ok status.
void throwIfBad(const engine::Status& status, const std::string& key);

// Typed, checked reads of XmlRpc values (what the parameter server holds). Each throws ParamError
// naming the key and the reason.
std::string typeName(const XmlRpc::XmlRpcValue& value);
bool isStruct(const XmlRpc::XmlRpcValue& value);
bool has(XmlRpc::XmlRpcValue& s, const std::string& member);
// Refuses members other than `allowed` (catches misspelt keys).
void checkKeys(XmlRpc::XmlRpcValue& s, const std::string& key,
               std::initializer_list<const char*> allowed);
void checkKeys(XmlRpc::XmlRpcValue& s, const std::string& key,
               const std::vector<std::string>& allowed);
void requireStruct(const XmlRpc::XmlRpcValue& value, const std::string& key);
void requireArray(const XmlRpc::XmlRpcValue& value, const std::string& key);

// Finite; ints are accepted as reals.
engine::Real readReal(XmlRpc::XmlRpcValue& value, const std::string& key);
int readInt(XmlRpc::XmlRpcValue& value, const std::string& key);
bool readBool(XmlRpc::XmlRpcValue& value, const std::string& key);
std::string readString(XmlRpc::XmlRpcValue& value, const std::string& key);
// [x, y, z]
engine::Vec3 readVec3(XmlRpc::XmlRpcValue& value, const std::string& key);

// The member if present, else the fallback.
engine::Real realOr(XmlRpc::XmlRpcValue& s, const std::string& key, const std::string& member,
                    engine::Real fallback);
int intOr(XmlRpc::XmlRpcValue& s, const std::string& key, const std::string& member, int fallback);
bool boolOr(XmlRpc::XmlRpcValue& s, const std::string& key, const std::string& member,
            bool fallback);
std::string stringOr(XmlRpc::XmlRpcValue& s, const std::string& key, const std::string& member,
                     const std::string& fallback);
engine::Vec3 vec3Or(XmlRpc::XmlRpcValue& s, const std::string& key, const std::string& member,
                    const engine::Vec3& fallback);

}  // namespace node
}  // namespace mass_aggregate_sim
