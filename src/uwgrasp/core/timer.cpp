#include "uwgrasp/core/timer.hpp"

#include <algorithm>

namespace uwgrasp {

void StageTimer::start(std::string name) {
  stop();
  // A stage that runs again (e.g. sample/check rounds) adds to its first entry.
  const auto it = std::find_if(stages_.begin(), stages_.end(),
                               [&](const StageTime& s) { return s.name == name; });
  if (it == stages_.end()) {
    stages_.push_back({std::move(name), 0.0});
    current_ = stages_.size() - 1;
  } else {
    current_ = static_cast<std::size_t>(it - stages_.begin());
  }
  begin_ = Clock::now();
  running_ = true;
}

void StageTimer::clear() {
  stages_.clear();
  current_ = 0;
  running_ = false;
}

void StageTimer::stop() {
  if (!running_) return;
  stages_[current_].ms += std::chrono::duration<double, std::milli>(Clock::now() - begin_).count();
  running_ = false;
}

double StageTimer::total_ms() const {
  double t = 0.0;
  for (const auto& s : stages_) t += s.ms;
  return t;
}

double StageTimer::ms(const std::string& name) const {
  double t = 0.0;
  for (const auto& s : stages_)
    if (s.name == name) t += s.ms;
  return t;
}

}  // namespace uwgrasp
