// Ctrl-C (SIGINT) and SIGTERM during `tem run`: instead of dying mid-write, the run notes the
// request, finishes the step it is in, writes a checkpoint and exits with every file whole.
// A second Ctrl-C, for a run that does not stop soon enough, kills the process as usual.
#pragma once

#include <csignal>

namespace tem::cli {

class StopOnSignal {
 public:
  StopOnSignal();   // installs the handlers
  ~StopOnSignal();  // puts the previous ones back
  StopOnSignal(const StopOnSignal&) = delete;
  StopOnSignal& operator=(const StopOnSignal&) = delete;

  bool requested() const;

 private:
  using Handler = void (*)(int);
  Handler previous_int_, previous_term_;
};

}  // namespace tem::cli
