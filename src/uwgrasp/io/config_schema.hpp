#pragma once
// One description of every config field (name, type, allowed range), walked by the YAML reader
// and the YAML / JSON writers so the three can never disagree.
#include <cstdint>
#include <functional>
#include <string>
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
  virtual void choice(const char* name, std::string& v, const std::vector<std::string>& allowed) = 0;
};

void visit(Visitor& v, Config& c);

}  // namespace uwgrasp::io
