#include "uwgrasp/io/config.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include "uwgrasp/core/error.hpp"
#include "uwgrasp/grasp/metrics.hpp"
#include "uwgrasp/io/config_schema.hpp"
#include "uwgrasp/vehicle/thrusters.hpp"

namespace uwgrasp::io {

namespace {
std::string show(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

// Reads the keys present in a YAML tree into a Config, validating each against the schema.
class Reader final : public Visitor {
 public:
  Reader(YAML::Node root, std::string source) : source_(std::move(source)) {
    if (root.IsNull()) root = YAML::Node(YAML::NodeType::Map);
    if (!root.IsMap()) fail("", "the top level must be a mapping of sections");
    stack_.push_back({root, "", {}});
  }
  void finish() { check_unknown(stack_.back()); }

  void section(const char* name, const std::function<void()>& body) override {
    const YAML::Node n = lookup(name);
    if (!n) return;
    if (!n.IsMap()) fail(key(name), "expected a section (mapping)");
    stack_.push_back({n, key(name), {}});
    body();
    check_unknown(stack_.back());
    stack_.pop_back();
  }
  void field(const char* name, double& v, double lo, double hi) override {
    if (const YAML::Node n = lookup(name)) v = number(n, name, lo, hi);
  }
  void field(const char* name, float& v, double lo, double hi) override {
    if (const YAML::Node n = lookup(name)) v = static_cast<float>(number(n, name, lo, hi));
  }
  void field(const char* name, std::uint32_t& v, double lo, double hi) override {
    if (const YAML::Node n = lookup(name)) v = static_cast<std::uint32_t>(integer(n, name, lo, hi));
  }
  void field(const char* name, std::uint64_t& v) override {
    if (const YAML::Node n = lookup(name)) {
      const std::string s = scalar(n, name);
      if (s.empty() || s.find_first_not_of("0123456789") != std::string::npos)
        fail(key(name), "expected a non-negative integer, got '" + s + "'");
      try {
        v = std::stoull(s);
      } catch (const std::exception&) {
        fail(key(name), "integer '" + s + "' is too large");
      }
    }
  }
  void field(const char* name, bool& v) override {
    if (const YAML::Node n = lookup(name)) {
      const std::string s = scalar(n, name);
      if (s == "true") v = true;
      else if (s == "false") v = false;
      else fail(key(name), "expected true or false, got '" + s + "'");
    }
  }
  void field(const char* name, Eigen::Vector3d& v, double lo, double hi) override {
    if (const YAML::Node n = lookup(name)) {
      if (!n.IsSequence() || n.size() != 3) fail(key(name), "expected three numbers [a, b, c]");
      for (int i = 0; i < 3; ++i) v[i] = number(n[i], name, lo, hi);
    }
  }
  void choice(const char* name, std::string& v, const std::vector<std::string>& allowed) override {
    if (const YAML::Node n = lookup(name)) {
      const std::string s = scalar(n, name);
      if (std::find(allowed.begin(), allowed.end(), s) == allowed.end()) {
        std::string list;
        for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
        fail(key(name), "'" + s + "' is not one of " + list);
      }
      v = s;
    }
  }

 private:
  struct Frame {
    YAML::Node node;
    std::string path;
    std::set<std::string> seen;
  };
  [[noreturn]] void fail(const std::string& k, const std::string& what) const {
    throw Error("config " + source_ + ": " + (k.empty() ? "" : k + ": ") + what);
  }
  std::string key(const char* name) const {
    const std::string& p = stack_.back().path;
    return p.empty() ? name : p + "." + name;
  }
  YAML::Node lookup(const char* name) {
    stack_.back().seen.insert(name);
    const YAML::Node& parent = stack_.back().node;
    return parent[name];
  }
  void check_unknown(const Frame& f) const {
    for (const auto& kv : f.node) {
      const std::string k = kv.first.as<std::string>();
      if (!f.seen.count(k))
        fail("", "unknown key '" + (f.path.empty() ? k : f.path + "." + k) + "'");
    }
  }
  std::string scalar(const YAML::Node& n, const char* name) const {
    if (!n.IsScalar()) fail(key(name), "expected a single value");
    return n.Scalar();
  }
  double number(const YAML::Node& n, const char* name, double lo, double hi) const {
    const std::string s = scalar(n, name);
    double v = 0;
    std::size_t used = 0;
    try {
      v = std::stod(s, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != s.size() || s.empty() || !std::isfinite(v))
      fail(key(name), "expected a number, got '" + s + "'");
    if (v < lo || v > hi)
      fail(key(name), show(v) + " is out of range [" + show(lo) + ", " + show(hi) + "]");
    return v;
  }
  long long integer(const YAML::Node& n, const char* name, double lo, double hi) const {
    const std::string s = scalar(n, name);
    const bool digits = !s.empty() && s.find_first_not_of("-0123456789") == std::string::npos &&
                        s.find('-', 1) == std::string::npos;
    if (!digits) fail(key(name), "expected an integer, got '" + s + "'");
    long long v = 0;
    try {
      v = std::stoll(s);
    } catch (const std::exception&) {
      fail(key(name), "integer '" + s + "' is out of range");
    }
    if (v < lo || v > hi)
      fail(key(name), s + " is out of range [" + show(lo) + ", " + show(hi) + "]");
    return v;
  }

  std::string source_;
  std::vector<Frame> stack_;
};

YAML::Node parse_yaml(const std::string& text, const std::string& source) {
  try {
    return YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw Error("config " + source + ": not valid YAML (line " + std::to_string(e.mark.line + 1) +
                ": " + e.msg + ")");
  }
}

void read_into(Config& cfg, const YAML::Node& root, const std::string& source) {
  Reader r(root, source);
  visit(r, cfg);
  r.finish();
}
}  // namespace

void apply_overrides(Config& cfg, const std::vector<std::string>& overrides) {
  for (const std::string& o : overrides) {
    const auto eq = o.find('=');
    if (eq == std::string::npos || eq == 0)
      throw Error("--set '" + o + "': expected section.key=value");
    const std::string path = o.substr(0, eq), value = o.substr(eq + 1);
    YAML::Node root(YAML::NodeType::Map);
    YAML::Node node = root;
    std::stringstream parts(path);
    std::string part, next;
    std::getline(parts, part, '.');
    while (std::getline(parts, next, '.')) {
      node[part] = YAML::Node(YAML::NodeType::Map);
      node.reset(node[part]);
      part = next;
    }
    try {
      node[part] = parse_yaml(value, "--set " + path);
      read_into(cfg, root, "--set");
    } catch (const YAML::Exception& e) {
      throw Error("--set '" + o + "': " + e.what());
    }
  }
  // Weights that sum to 0 rank nothing: refused with the config, before any cloud is read.
  grasp::check_weights(cfg.grasp.score.weights);
  // The vehicle prices each grasp's attitude (q_v, cannot_hold); rebuilt whenever it may change.
  cfg.grasp.score.hold_cost = vehicle::hold_cost_function(cfg.vehicle.params, cfg.vehicle.current);
}

Config parse_config(const std::string& yaml, const std::string& source,
                    const std::vector<std::string>& overrides) {
  Config cfg;
  try {
    read_into(cfg, parse_yaml(yaml, source), source);
  } catch (const YAML::Exception& e) {  // a shape the reader does not expect, e.g. a complex key
    throw Error(source + ": malformed config (" + e.what() + ")");
  }
  apply_overrides(cfg, overrides);
  return cfg;
}

Config load_config(const std::string& path, const std::vector<std::string>& overrides) {
  if (path.empty()) {
    Config cfg;
    apply_overrides(cfg, overrides);
    return cfg;
  }
  std::ifstream f(path, std::ios::binary);
  if (!f) throw Error("config " + path + ": cannot open");
  std::stringstream text;
  text << f.rdbuf();
  return parse_config(text.str(), path, overrides);
}

}  // namespace uwgrasp::io
