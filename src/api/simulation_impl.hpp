// What a tem::Simulation holds (include/tem/simulation.hpp): the Model, the State, the step's
// Workspace, and the recording of `tem run`'s files. Visible to the rest of src/api/ (the MPI
// run, the reports) and to TEM's tests, but not installed.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "io/run_output.hpp"
#include "process/population.hpp"
#include "simulation/step.hpp"
#include "simulation/step_loop.hpp"
#include "tem/simulation.hpp"

namespace tem {

// The Impl is also the step's hooks (simulation/step_loop.hpp): while recording, a checkpoint
// where a step begins, the rows of the state a step starts from, and the bodies that left.
struct Simulation::Impl : StepHooks {
  Model model;
  State state;
  Workspace workspace;
  std::vector<std::string> warnings;
  // Derived per-body arrays the API hands out as views, refreshed after every step.
  std::vector<Real> quaternions;         // 4 per body, [w, x, y, z]
  std::vector<Real> angular_velocities;  // 3 per body, world axes
  bool stepped = false;                  // contacts() has a step to report
  // Granular processes: the bodies at the start (kept where bodies come and go, to rebuild the
  // Model's bodies from a checkpoint), and the bodies that left since the last row of
  // removed.csv.
  std::vector<Body> initial_bodies;
  std::vector<RemovedBody> removed;

  // Recording (record(), resume_recording()).
  std::unique_ptr<RunOutput> output;
  std::string directory;
  long long every = 1;             // steps between output rows
  long long checkpoint_every = 0;  // steps between checkpoints, 0: none
  long long first_step = 0;        // where the recording started or resumed
  long long written_step = -1;     // the step whose row was written last

  explicit Impl(Model m);
  PopulationLinks links() {
    return {&workspace.forces, &workspace.patches, &workspace.loads, &workspace.contact.features};
  }
  // Room for every body the run can hold, so that the state arrays (and the views on them)
  // never move when bodies are added.
  void reserve_capacity();
  void refresh_views();
  void restore(const Checkpoint& checkpoint);  // state and contact memory, then the views
  // Output from the current step on into `dir` through `out` (new, or reopened at a checkpoint).
  void start_recording(const std::string& dir, std::unique_ptr<RunOutput> out);
  void advance_one();
  void write_row();  // the current state's row: its contact forces first
  void write_found_row();  // the same, with the contact forces already found for this state

  // StepHooks
  void step_begins(const Model& model, State& state, Workspace& w) override;
  void forces_found(const Model& model, const State& state, const Workspace& w) override;
  void bodies_left(const std::vector<RemovedBody>& left) override;
};

}  // namespace tem
