#include "integrator/capture/progress.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>

namespace camsim {

std::string formatSeconds(double s) {
  char buf[32];
  if (s < 60.0) {
    std::snprintf(buf, sizeof buf, "%.1f s", s);
  } else {
    const long total = std::lround(s);
    std::snprintf(buf, sizeof buf, "%ld:%02ld:%02ld", total / 3600, (total / 60) % 60, total % 60);
  }
  return buf;
}

ProgressBar::ProgressBar(std::string label)
    : label_(std::move(label)),
      enabled_(::isatty(STDERR_FILENO) == 1),
      start_(std::chrono::steady_clock::now()),
      lastDraw_(start_) {}

ProgressBar::~ProgressBar() {
  finish();
}

void ProgressBar::update(int done, int total) {
  if (!enabled_ || finished_ || total <= 0) return;
  const auto now = std::chrono::steady_clock::now();
  if (done < total && now - lastDraw_ < std::chrono::milliseconds(100)) return;
  lastDraw_ = now;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double fraction = static_cast<double>(done) / total;
  constexpr int kWidth = 30;
  const int filled = static_cast<int>(fraction * kWidth);
  std::string bar(static_cast<size_t>(filled), '#');
  bar.append(static_cast<size_t>(kWidth - filled), ' ');
  const std::string eta = done > 0 ? formatSeconds(elapsed * (1.0 - fraction) / fraction) : "?";
  std::fprintf(stderr, "\r%s [%s] %3d%%  elapsed %s  ETA %s   ", label_.c_str(), bar.c_str(),
               static_cast<int>(fraction * 100.0), formatSeconds(elapsed).c_str(), eta.c_str());
  std::fflush(stderr);
}

void ProgressBar::finish() {
  if (!enabled_ || finished_) return;
  finished_ = true;
  std::fprintf(stderr, "\n");
}

}  // namespace camsim
