// What a tem::Simulation holds (include/tem/simulation.hpp): the Model, the State, the step's
// Workspace, and the recording of `tem run`'s files. Visible to TEM's own programs (the CLI's
// summary reads the stage times) but not installed.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "io/run_output.hpp"
#include "simulation/step.hpp"
#include "tem/simulation.hpp"

namespace tem {

struct Simulation::Impl {
  Model model;
  State state;
  Workspace workspace;
  std::vector<std::string> warnings;
  // Derived per-body arrays the API hands out as views, refreshed after every step.
  std::vector<Real> quaternions;         // 4 per body, [w, x, y, z]
  std::vector<Real> angular_velocities;  // 3 per body, world axes
  bool stepped = false;                  // contacts() has a step to report

  // Recording (record(), resume_recording()).
  std::unique_ptr<RunOutput> output;
  std::string directory;
  long long every = 1;             // steps between output rows
  long long checkpoint_every = 0;  // steps between checkpoints, 0: none
  long long first_step = 0;        // where the recording started or resumed
  long long written_step = -1;     // the step whose row was written last

  explicit Impl(Model m);
  void refresh_views();
  void restore(const Checkpoint& checkpoint);  // state and contact memory, then the views
  // Output from the current step on into `dir` through `out` (new, or reopened at a checkpoint).
  void start_recording(const std::string& dir, std::unique_ptr<RunOutput> out);
  void advance_one();
  void write_row();  // the current state's row: its contact forces first
};

}  // namespace tem
