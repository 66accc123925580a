#pragma once
// One description of every config field (name, type, allowed range), walked by the YAML reader
// and the YAML / JSON writers so the three can never disagree.
#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "uwgrasp/io/config.hpp"

namespace uwgrasp::io {

class Visitor {
 public:
  virtual ~Visitor() = default;
  virtual void section(const char* name, const std::function<void()>& body) = 0;
  virtual void field(const char* name, double& v, double lo, double hi) = 0;
  virtual void field(const char* name, float& v, double lo, double hi) = 0;
  virtual void field(const char* name, std::uint32_t& v, double lo, double hi) = 0;
  virtual void field(const char* name, std::uint64_t& v) = 0;
  virtual void field(const char* name, bool& v) = 0;
  // Three numbers, each in [lo, hi]; a YAML sequence [a, b, c].
  virtual void field(const char* name, Eigen::Vector3d& v, double lo, double hi) = 0;
  virtual void choice(const char* name, std::string& v, const std::vector<std::string>& allowed) = 0;
};

// An enum as a named choice: table lists (name, value) pairs, the first is the fallback.
template <class E>
void enum_choice(Visitor& v, const char* name, E& e,
                 const std::vector<std::pair<std::string, E>>& table) {
  std::string s = table.front().first;
  std::vector<std::string> names;
  for (const auto& [n, val] : table) {
    names.push_back(n);
    if (val == e) s = n;
  }
  v.choice(name, s, names);
  for (const auto& [n, val] : table)
    if (n == s) e = val;
}

// The shortest decimal that reads back as the same double (0.01 stays 0.01, pi/4 keeps 16
// digits), so written YAML reloads bit-exactly.
std::string shortest(double v);

void visit_grasp(Visitor& v, grasp::GraspConfig& c);
void visit_sim(Visitor& v, SimConfig& c);
void visit_stereo(Visitor& v, camera::DenseConfig& c);
void visit_vehicle(Visitor& v, VehicleConfig& c);

void visit(Visitor& v, Config& c);

}  // namespace uwgrasp::io
