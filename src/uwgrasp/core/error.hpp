#pragma once
// uwgrasp::Error: bad input (missing or malformed file, empty cloud, degenerate geometry,
// out-of-range config). The message names the file, field or value; the CLI prints it on one
// line and exits 2.
#include <stdexcept>
#include <string>

namespace uwgrasp {

class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& what) : std::runtime_error(what) {}
};

}  // namespace uwgrasp
