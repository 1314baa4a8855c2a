// What the Python module holds for one tem.Simulation: the C++ object, the per-body constants
// the module hands out as read-only arrays, and whether a step is running (the GIL is released
// then, so another Python thread could call in).
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <memory>
#include <vector>

#include "tem/simulation.hpp"

namespace tem_python {

namespace py = pybind11;

class PySimulation {
 public:
  explicit PySimulation(tem::Simulation sim);

  // The simulation, for every call that reads or changes more than the state arrays; raises
  // RuntimeError while another thread is inside step().
  tem::Simulation& get();
  // The simulation without the check: for handing out views, whose pointers never change.
  tem::Simulation& raw() { return sim_; }

  // step(n) with the GIL released, in chunks of about 0.1 s between which Ctrl-C is noticed.
  void step(long long n);

  // Constants per body, kept here so that the arrays on them are views too; refreshed after a
  // step where bodies came or went (room for the run's capacity keeps the pointers still).
  const std::vector<double>& masses() const { return masses_; }
  const std::vector<double>& volumes() const { return volumes_; }
  const std::vector<double>& inertia_body() const { return inertia_body_; }  // 9 per body
  const bool* fixed() const { return fixed_.get(); }                         // one bool per body

 private:
  void refresh_constants();
  void step_unrefreshed(long long n);

  tem::Simulation sim_;
  bool stepping_ = false;  // read and written with the GIL held only
  long long population_version_ = -1;  // of the constants held
  std::vector<double> masses_, volumes_, inertia_body_;
  std::unique_ptr<bool[]> fixed_;
};

// tem.set_threads(n): tem::Simulation::set_threads, which holds for every thread that steps.
// 0: one per core; a negative count is a ValueError.
void set_threads(int threads);

// An (N, ...) float64 or bool array on memory owned by `owner` (the Python Simulation), which
// the array keeps alive through its base object; read-only unless `writeable`.
py::array make_view(py::handle owner, const py::dtype& dtype, const void* data,
                    std::vector<py::ssize_t> shape, std::vector<py::ssize_t> strides,
                    bool writeable);

// Adds the class tem.Bodies (sim.bodies) to the module.
void bind_bodies(py::module_& m);
// The object sim.bodies returns for the Python Simulation `owner`.
py::object make_bodies(py::object owner);

}  // namespace tem_python
