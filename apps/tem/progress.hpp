// Progress of `tem run` on a terminal: simulated time, steps per second, time left. Quiet when
// standard error is not a terminal (a log file, a pipe, CI), so logs hold only the summary.
#pragma once

#include <chrono>

namespace tem::cli {

class Progress {
 public:
  // `end_time`: the simulated time the run ends at; `first_step`: where it starts (resumed runs
  // count speed from there).
  Progress(double end_time, long long first_step);
  // Cheap enough to call every step: it looks at the clock every 64 steps and redraws the line
  // at most four times a second.
  void update(long long step, double time) {
    if (enabled_ && (step & 63) == 0) redraw(step, time);
  }
  // Clears the line before other messages are printed.
  void finish();

 private:
  void redraw(long long step, double time);

  bool enabled_;
  double end_time_;
  long long first_step_;
  std::chrono::steady_clock::time_point start_, last_draw_;
  double start_time_ = -1;
  bool drawn_ = false;
};

}  // namespace tem::cli
