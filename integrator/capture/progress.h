// A progress bar with elapsed time and ETA on stderr, drawn only when stderr is a
// terminal (quiet in pipes, logs and CI).
#pragma once

#include <chrono>
#include <string>

namespace camsim {

class ProgressBar {
 public:
  explicit ProgressBar(std::string label);
  ~ProgressBar();
  void update(int done, int total);
  void finish();

 private:
  std::string label_;
  bool enabled_;
  bool finished_ = false;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point lastDraw_;
};

std::string formatSeconds(double seconds);

}  // namespace camsim
