#pragma once
// Stage timer: the pipeline records wall time per named stage, in the order they ran.
#include <chrono>
#include <string>
#include <vector>

namespace uwgrasp {

struct StageTime {
  std::string name;
  double ms = 0.0;
};

class StageTimer {
 public:
  // Starts timing `name`; the previous stage (if any) ends now. Starting a stage that already
  // ran adds to its time.
  void start(std::string name);
  // Ends the running stage.
  void stop();
  // Forgets every stage, keeping the list's capacity (a timer reused over a stream of frames).
  void clear();
  const std::vector<StageTime>& stages() const { return stages_; }
  double total_ms() const;
  // Time of a stage by name, 0 if it did not run.
  double ms(const std::string& name) const;

 private:
  using Clock = std::chrono::steady_clock;
  std::vector<StageTime> stages_;
  Clock::time_point begin_{};
  std::size_t current_ = 0;
  bool running_ = false;
};

}  // namespace uwgrasp
