#include "stop_signal.hpp"

namespace tem::cli {
namespace {

volatile std::sig_atomic_t stop_requested = 0;

extern "C" void on_stop_signal(int signal) {
  stop_requested = 1;
  // The next one is not caught: a stuck run can still be killed with a second Ctrl-C.
  std::signal(signal, SIG_DFL);
}

}  // namespace

StopOnSignal::StopOnSignal() {
  stop_requested = 0;
  previous_int_ = std::signal(SIGINT, on_stop_signal);
  previous_term_ = std::signal(SIGTERM, on_stop_signal);
}

StopOnSignal::~StopOnSignal() {
  std::signal(SIGINT, previous_int_);
  std::signal(SIGTERM, previous_term_);
}

bool StopOnSignal::requested() const { return stop_requested != 0; }

}  // namespace tem::cli
