#include "mass_aggregate_sim/node/xmlrpc_reader.h"

#include <cmath>
#include <cstdlib>

#include "mass_aggregate_sim/node/input_limits.h"

namespace mass_aggregate_sim {
namespace node {

using XmlRpc::XmlRpcValue;

void throwIfBad(const engine::Status& status, const std::string& key) {
  if (status) return;
  const std::string& message = status.message();
  const std::size_t colon = message.find(": ");
  if (colon == std::string::npos) throw ParamError(key, message);
  throw ParamError(key + "." + message.substr(0, colon), message.substr(colon + 2));
}

std::string typeName(const XmlRpcValue& value) {
  switch (value.getType()) {
    case XmlRpcValue::TypeInvalid:
      return "nothing";
    case XmlRpcValue::TypeBoolean:
      return "a boolean";
    case XmlRpcValue::TypeInt:
      return "an integer";
    case XmlRpcValue::TypeDouble:
      return "a number";
    case XmlRpcValue::TypeString:
      return "a string";
    case XmlRpcValue::TypeDateTime:
      return "a date";
    case XmlRpcValue::TypeBase64:
      return "binary data";
    case XmlRpcValue::TypeArray:
      return "a list";
    case XmlRpcValue::TypeStruct:
      return "a map";
  }
  return "an unknown type";
}

bool isStruct(const XmlRpcValue& value) { return value.getType() == XmlRpcValue::TypeStruct; }

bool has(XmlRpcValue& s, const std::string& member) { return isStruct(s) && s.hasMember(member); }

void requireStruct(const XmlRpcValue& value, const std::string& key) {
  if (!isStruct(value)) throw ParamError(key, "expected a map, got " + typeName(value));
}

void requireArray(const XmlRpcValue& value, const std::string& key) {
  if (value.getType() != XmlRpcValue::TypeArray) {
    throw ParamError(key, "expected a list, got " + typeName(value));
  }
}

void checkKeys(XmlRpcValue& s, const std::string& key, const std::vector<std::string>& allowed) {
  requireStruct(s, key);
  for (auto it = s.begin(); it != s.end(); ++it) {
    bool known = false;
    for (const std::string& name : allowed) known = known || it->first == name;
    if (known) continue;
    std::string list;
    for (const std::string& name : allowed) list += (list.empty() ? "" : ", ") + name;
    throw ParamError(key + "." + it->first, "unknown key (known here: " + list + ")");
  }
}

void checkKeys(XmlRpcValue& s, const std::string& key,
               const std::initializer_list<const char*> allowed) {
  checkKeys(s, key, std::vector<std::string>(allowed.begin(), allowed.end()));
}

engine::Real readReal(XmlRpcValue& value, const std::string& key) {
  engine::Real result;
  if (value.getType() == XmlRpcValue::TypeDouble) {
    result = static_cast<double>(value);
  } else if (value.getType() == XmlRpcValue::TypeInt) {
    result = static_cast<int>(value);
  } else if (value.getType() == XmlRpcValue::TypeString) {
    // rosparam reads YAML 1.1, where 1.0e6 and 1e+6 are strings: only 1.0e+6 is a number.
    const std::string text = static_cast<std::string>(value);
    char* end = nullptr;
    std::strtod(text.c_str(), &end);
    const bool numeric = !text.empty() && end == text.c_str() + text.size();
    throw ParamError(key,
                     "expected a number, got the string " + quoteInput(text) +
                         (numeric ? " (YAML 1.1 exponents need a dot and a sign: 1.0e+6)" : ""));
  } else {
    throw ParamError(key, "expected a number, got " + typeName(value));
  }
  if (!std::isfinite(result)) throw ParamError(key, "must be finite");
  return result;
}

int readInt(XmlRpcValue& value, const std::string& key) {
  if (value.getType() != XmlRpcValue::TypeInt) {
    throw ParamError(key, "expected an integer, got " + typeName(value));
  }
  return static_cast<int>(value);
}

bool readBool(XmlRpcValue& value, const std::string& key) {
  if (value.getType() != XmlRpcValue::TypeBoolean) {
    throw ParamError(key, "expected true or false, got " + typeName(value));
  }
  return static_cast<bool>(value);
}

std::string readString(XmlRpcValue& value, const std::string& key) {
  if (value.getType() != XmlRpcValue::TypeString) {
    throw ParamError(key, "expected a string, got " + typeName(value));
  }
  return static_cast<std::string>(value);
}

engine::Vec3 readVec3(XmlRpcValue& value, const std::string& key) {
  if (value.getType() != XmlRpcValue::TypeArray || value.size() != 3) {
    throw ParamError(
        key, "expected [x, y, z], got " + typeName(value) +
                 (value.getType() == XmlRpcValue::TypeArray ? " of " + std::to_string(value.size())
                                                            : std::string()));
  }
  engine::Vec3 v;
  for (int i = 0; i < 3; ++i) v[i] = readReal(value[i], key + "[" + std::to_string(i) + "]");
  return v;
}

engine::Real realOr(XmlRpcValue& s, const std::string& key, const std::string& member,
                    const engine::Real fallback) {
  return has(s, member) ? readReal(s[member], key + "." + member) : fallback;
}

int intOr(XmlRpcValue& s, const std::string& key, const std::string& member, const int fallback) {
  return has(s, member) ? readInt(s[member], key + "." + member) : fallback;
}

bool boolOr(XmlRpcValue& s, const std::string& key, const std::string& member,
            const bool fallback) {
  return has(s, member) ? readBool(s[member], key + "." + member) : fallback;
}

std::string stringOr(XmlRpcValue& s, const std::string& key, const std::string& member,
                     const std::string& fallback) {
  return has(s, member) ? readString(s[member], key + "." + member) : fallback;
}

engine::Vec3 vec3Or(XmlRpcValue& s, const std::string& key, const std::string& member,
                    const engine::Vec3& fallback) {
  return has(s, member) ? readVec3(s[member], key + "." + member) : fallback;
}

}  // namespace node
}  // namespace mass_aggregate_sim
