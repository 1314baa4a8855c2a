#include "progress.hpp"

#include <unistd.h>

#include <cstdio>

namespace tem::cli {
namespace {

// "1h02m", "3m05s", "12.3s".
void format_duration(double seconds, char* out, std::size_t size) {
  if (seconds >= 3600) {
    const long s = static_cast<long>(seconds);
    std::snprintf(out, size, "%ldh%02ldm", s / 3600, (s / 60) % 60);
  } else if (seconds >= 60) {
    const long s = static_cast<long>(seconds);
    std::snprintf(out, size, "%ldm%02lds", s / 60, s % 60);
  } else {
    std::snprintf(out, size, "%.1fs", seconds);
  }
}

}  // namespace

Progress::Progress(double end_time, long long first_step)
    : enabled_(isatty(STDERR_FILENO) != 0),
      end_time_(end_time),
      first_step_(first_step),
      start_(std::chrono::steady_clock::now()),
      last_draw_(start_) {}

void Progress::redraw(long long step, double time) {
  const auto now = std::chrono::steady_clock::now();
  if (start_time_ < 0) start_time_ = time;
  if (now - last_draw_ < std::chrono::milliseconds(250)) return;
  last_draw_ = now;
  const double wall = std::chrono::duration<double>(now - start_).count();
  const double steps_per_second = static_cast<double>(step - first_step_) / wall;
  const double simulated_per_second = (time - start_time_) / wall;
  char eta[32] = "?";
  if (simulated_per_second > 0)
    format_duration((end_time_ - time) / simulated_per_second, eta, sizeof eta);
  std::fprintf(stderr, "\r  t = %.6g / %.6g s (%3.0f%%)  %.0f steps/s  left %s    ", time,
               end_time_, 100 * time / end_time_, steps_per_second, eta);
  std::fflush(stderr);
  drawn_ = true;
}

void Progress::finish() {
  if (!drawn_) return;
  std::fprintf(stderr, "\r%*s\r", 79, "");
  std::fflush(stderr);
  drawn_ = false;
}

}  // namespace tem::cli
