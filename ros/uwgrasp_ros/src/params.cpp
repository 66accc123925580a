#include "params.hpp"

#include <set>
#include <sstream>

#include "uwgrasp/core/error.hpp"

namespace uwgrasp_ros {

namespace {
// A parameter's value as the YAML that --set takes.
std::string yaml_of(XmlRpc::XmlRpcValue& v, const std::string& name) {
  std::ostringstream o;
  switch (v.getType()) {
    case XmlRpc::XmlRpcValue::TypeBoolean: return bool(v) ? "true" : "false";
    case XmlRpc::XmlRpcValue::TypeInt: return std::to_string(int(v));
    case XmlRpc::XmlRpcValue::TypeDouble: o.precision(17), o << double(v); return o.str();
    case XmlRpc::XmlRpcValue::TypeString: return std::string(v);
    case XmlRpc::XmlRpcValue::TypeArray: {
      o << "[";
      for (int i = 0; i < v.size(); ++i) o << (i ? "," : "") << yaml_of(v[i], name);
      o << "]";
      return o.str();
    }
    default: throw uwgrasp::Error("parameter " + name + ": unsupported type");
  }
}
}  // namespace

NodeParams read_params(const ros::NodeHandle& nh) {
  NodeParams p;
  nh.param<std::string>("config", p.config_path, "");
  nh.param<std::string>("base_frame", p.base_frame, p.base_frame);
  nh.param<std::string>("fixed_frame", p.fixed_frame, "");
  nh.param("tf_timeout", p.tf_timeout, p.tf_timeout);
  nh.param("enabled", p.enabled, true);
  const std::set<std::string> own = {"config", "base_frame", "fixed_frame", "tf_timeout", "enabled"};
  std::vector<std::string> names;
  nh.getParamNames(names);
  const std::string prefix = nh.getNamespace() + "/";
  for (const auto& full : names) {
    if (full.compare(0, prefix.size(), prefix) != 0) continue;
    std::string key = full.substr(prefix.size());
    if (own.count(key)) continue;
    XmlRpc::XmlRpcValue v;
    if (!nh.getParam(key, v)) continue;
    if (v.getType() == XmlRpc::XmlRpcValue::TypeStruct) continue;  // its leaves are listed too
    for (auto& c : key) c = c == '/' ? '.' : c;
    p.sets.push_back(key + "=" + yaml_of(v, full));
  }
  return p;
}

}  // namespace uwgrasp_ros
