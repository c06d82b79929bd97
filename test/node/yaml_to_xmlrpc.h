#pragma once

#include <xmlrpcpp/XmlRpcValue.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <regex>
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
    // The YAML 1.1 number forms that rosparam's loader (PyYAML) accepts: "1.0e6" and "1e+6"
    // are strings there, only "1.0e+6" is a float.
    static const std::regex integer("[-+]?(0|[1-9][0-9]*)");
    static const std::regex real("[-+]?([0-9]+\\.[0-9]*|\\.[0-9]+)([eE][-+][0-9]+)?");
    if (std::regex_match(text, integer)) {
      // XML-RPC integers are 32-bit (rosparam refuses larger ones); keep a larger one as a
      // double, so the loader sees a number outside every integer field's range.
      const double number = std::stod(text);
      if (std::abs(number) <= 2147483647.0) return XmlRpc::XmlRpcValue(static_cast<int>(number));
      return XmlRpc::XmlRpcValue(number);
    }
    if (std::regex_match(text, real)) return XmlRpc::XmlRpcValue(std::stod(text));
    if (text == ".nan" || text == ".NaN") return XmlRpc::XmlRpcValue(std::nan(""));
    if (text == ".inf" || text == ".Inf") return XmlRpc::XmlRpcValue(HUGE_VAL);
    return XmlRpc::XmlRpcValue(text);
  }
  return value;
}

inline XmlRpc::XmlRpcValue yamlToXmlRpc(const std::string& text) {
  return toXmlRpc(YAML::Load(text));
}

}  // namespace test
}  // namespace mass_aggregate_sim
