#include "py_simulation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

namespace tem_python {

void set_threads(int threads) {
  if (threads < 0)
    throw py::value_error("set_threads: threads must be 0 or more, got " + std::to_string(threads));
  tem::Simulation::set_threads(threads);
}

PySimulation::PySimulation(tem::Simulation sim) : sim_(std::move(sim)) {
  const size_t capacity = static_cast<size_t>(std::max(sim_.body_capacity(), 1));
  masses_.reserve(capacity);
  volumes_.reserve(capacity);
  inertia_body_.reserve(9 * capacity);
  fixed_ = std::make_unique<bool[]>(capacity);
  refresh_constants();
}

void PySimulation::refresh_constants() {
  if (population_version_ == sim_.population_version()) return;
  population_version_ = sim_.population_version();
  const int n = sim_.body_count();
  masses_.resize(n);
  volumes_.resize(n);
  inertia_body_.resize(9 * static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) {
    masses_[i] = sim_.mass(i);
    volumes_[i] = sim_.volume(i);
    fixed_[i] = sim_.body_fixed(i);
    const tem::Mat3 j = sim_.inertia_body(i);
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) inertia_body_[9 * i + 3 * r + c] = j(r, c);
  }
}

tem::Simulation& PySimulation::get() {
  if (stepping_)
    throw std::runtime_error(
        "tem.Simulation is stepping in another thread; one Simulation is used from one thread "
        "at a time");
  return sim_;
}

void PySimulation::step(long long n) {
  struct Refresh {  // also when Ctrl-C ends the steps early
    PySimulation& s;
    ~Refresh() { s.refresh_constants(); }
  } refresh{*this};
  step_unrefreshed(n);
}

void PySimulation::step_unrefreshed(long long n) {
  if (n < 0) throw py::value_error("step: n must be 0 or more, got " + std::to_string(n));
  tem::Simulation& sim = get();
  // Past the scene's duration the steps go on (a program may step as long as it needs), but not
  // without a word: `tem run` stops there, and a step(10**12) is a mistake worth a warning
  // before it starts (Ctrl-C stops it).
  if (n > 0 && sim.step_count() + n > sim.total_steps()) {
    std::ostringstream message;
    message << "step(" << n << ") goes past the scene's duration (" << sim.total_steps()
            << " steps; now at step " << sim.step_count() << ", to end at t = "
            << static_cast<double>(sim.step_count() + n) * sim.time_step()
            << " s): tem run stops at the duration; the steps go on here";
    if (PyErr_WarnEx(PyExc_RuntimeWarning, message.str().c_str(), 1) != 0)
      throw py::error_already_set();
  }
  // Declared before the release, so cleared after the GIL is taken back.
  struct Stepping {
    bool& flag;
    explicit Stepping(bool& f) : flag(f) { flag = true; }
    ~Stepping() { flag = false; }
  } stepping(stepping_);
  py::gil_scoped_release release;
  // Chunks of about 0.1 s: between them the GIL is taken for a moment to notice Ctrl-C
  // (KeyboardInterrupt leaves the simulation at the end of a whole step). The results do not
  // depend on the chunks: step(a) then step(b) is step(a + b), bit for bit.
  constexpr double kChunkSeconds = 0.1;
  long long done = 0;
  long long chunk = 1;
  while (done < n) {
    const long long k = std::min(chunk, n - done);
    const auto start = std::chrono::steady_clock::now();
    sim.step(k);
    done += k;
    if (done == n) break;
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double wanted = seconds > 0 ? static_cast<double>(k) * kChunkSeconds / seconds
                                      : static_cast<double>(16 * k);
    chunk =
        std::clamp<long long>(std::llround(std::min(wanted, 16.0 * static_cast<double>(k))), 1, n);
    py::gil_scoped_acquire acquire;
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();
  }
}

py::array make_view(py::handle owner, const py::dtype& dtype, const void* data,
                    std::vector<py::ssize_t> shape, std::vector<py::ssize_t> strides,
                    bool writeable) {
  if (data == nullptr) {  // no bodies: an empty array of its own
    return py::array(dtype, std::move(shape), std::move(strides));
  }
  py::array a(dtype, std::move(shape), std::move(strides), data, owner);
  if (!writeable)
    py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return a;
}

}  // namespace tem_python
