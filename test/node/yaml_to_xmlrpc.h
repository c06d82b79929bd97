#pragma once

#include <xmlrpcpp/XmlRpcValue.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <string>

namespace mass_aggregate_sim {
namespace test {

// A YAML document as the parameter server would hold it after `rosparam load`: so tests can
// write scenes as YAML text and build the XmlRpc tree in memory, with no master.
inline XmlRpc::XmlRpcValue toXmlRpc(const YAML::Node& node) {
  XmlRpc::XmlRpcValue value;
  if (node.IsMap()) {
    for (const auto& entry : node) value[entry.first.as<std::string>()] = toXmlRpc(entry.second);
  } else if (node.IsSequence()) {
    value.setSize(static_cast<int>(node.size()));
    for (std::size_t i = 0; i < node.size(); ++i) value[static_cast<int>(i)] = toXmlRpc(node[i]);
  } else if (node.IsScalar()) {
    const std::string text = node.Scalar();
    if (node.Tag() == "!") return XmlRpc::XmlRpcValue(text);  // quoted: always a string
    if (text == "true" || text == "false") return XmlRpc::XmlRpcValue(text == "true");
    try {
      std::size_t used = 0;
      const long long integer = std::stoll(text, &used);
      if (used == text.size()) return XmlRpc::XmlRpcValue(static_cast<int>(integer));
    } catch (const std::exception&) {
    }
    if (text == ".nan" || text == ".NaN") return XmlRpc::XmlRpcValue(std::nan(""));
    if (text == ".inf" || text == ".Inf") return XmlRpc::XmlRpcValue(HUGE_VAL);
    try {
      std::size_t used = 0;
      const double real = std::stod(text, &used);
      if (used == text.size()) return XmlRpc::XmlRpcValue(real);
    } catch (const std::exception&) {
    }
    return XmlRpc::XmlRpcValue(text);
  }
  return value;
}

inline XmlRpc::XmlRpcValue yamlToXmlRpc(const std::string& text) {
  return toXmlRpc(YAML::Load(text));
}

}  // namespace test
}  // namespace mass_aggregate_sim
