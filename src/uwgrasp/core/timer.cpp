#include "uwgrasp/core/timer.hpp"

namespace uwgrasp {

void StageTimer::start(std::string name) {
  stop();
  stages_.push_back({std::move(name), 0.0});
  begin_ = Clock::now();
  running_ = true;
}

void StageTimer::stop() {
  if (!running_) return;
  stages_.back().ms += std::chrono::duration<double, std::milli>(Clock::now() - begin_).count();
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
