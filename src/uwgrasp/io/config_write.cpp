// Config written out: YAML (the config command, simulate's config.yaml) and JSON (grasps.json's "config").
#include <yaml-cpp/yaml.h>

#include <charconv>
#include <sstream>

#include "uwgrasp/io/config.hpp"
#include "uwgrasp/io/config_schema.hpp"

namespace uwgrasp::io {

std::string shortest(double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

namespace {
class YamlWriter final : public Visitor {
 public:
  explicit YamlWriter(YAML::Emitter& e) : e_(e) {}
  void section(const char* name, const std::function<void()>& body) override {
    e_ << YAML::Key << name << YAML::Value << YAML::BeginMap;
    body();
    e_ << YAML::EndMap;
  }
  void field(const char* n, double& v, double, double) override {
    e_ << YAML::Key << n << YAML::Value << shortest(v);
  }
  void field(const char* n, float& v, double, double) override { e_ << YAML::Key << n << YAML::Value << v; }
  void field(const char* n, std::uint32_t& v, double, double) override { e_ << YAML::Key << n << YAML::Value << v; }
  void field(const char* n, std::uint64_t& v) override { e_ << YAML::Key << n << YAML::Value << v; }
  void field(const char* n, bool& v) override { e_ << YAML::Key << n << YAML::Value << v; }
  void field(const char* n, Eigen::Vector3d& v, double, double) override {
    e_ << YAML::Key << n << YAML::Value << YAML::Flow << YAML::BeginSeq << shortest(v.x())
       << shortest(v.y()) << shortest(v.z()) << YAML::EndSeq;
  }
  void choice(const char* n, std::string& v, const std::vector<std::string>&) override {
    e_ << YAML::Key << n << YAML::Value << v;
  }

 private:
  YAML::Emitter& e_;
};

class JsonWriter final : public Visitor {
 public:
  explicit JsonWriter(nlohmann::json& root) { stack_.push_back(&root); }
  void section(const char* name, const std::function<void()>& body) override {
    nlohmann::json& child = (*stack_.back())[name] = nlohmann::json::object();
    stack_.push_back(&child);
    body();
    stack_.pop_back();
  }
  // Floats go through their shortest decimal form so 0.0025f is written as 0.0025.
  void field(const char* n, float& v, double, double) override {
    std::ostringstream s;
    s.precision(7);
    s << v;
    (*stack_.back())[n] = std::stod(s.str());
  }
  void field(const char* n, double& v, double, double) override { (*stack_.back())[n] = v; }
  void field(const char* n, std::uint32_t& v, double, double) override { (*stack_.back())[n] = v; }
  void field(const char* n, std::uint64_t& v) override { (*stack_.back())[n] = v; }
  void field(const char* n, bool& v) override { (*stack_.back())[n] = v; }
  void field(const char* n, Eigen::Vector3d& v, double, double) override {
    (*stack_.back())[n] = {v.x(), v.y(), v.z()};
  }
  void choice(const char* n, std::string& v, const std::vector<std::string>&) override {
    (*stack_.back())[n] = v;
  }

 private:
  std::vector<nlohmann::json*> stack_;
};
}  // namespace

std::string to_yaml(const Config& cfg) {
  Config c = cfg;
  YAML::Emitter e;
  e.SetFloatPrecision(7);
  e.SetDoublePrecision(15);
  e << YAML::BeginMap;
  YamlWriter w(e);
  visit(w, c);
  e << YAML::EndMap;
  return std::string(e.c_str()) + "\n";
}

nlohmann::json to_json(const Config& cfg) {
  Config c = cfg;
  nlohmann::json j = nlohmann::json::object();
  JsonWriter w(j);
  visit(w, c);
  return j;
}

}  // namespace uwgrasp::io
