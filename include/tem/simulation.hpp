// TEM's public C++ API: one simulation of rigid bodies made of convex blocks, loaded from a scene
// (a file, JSON text, or a SceneDef built in code), stepped, read and pushed from outside.
//
//   tem::Simulation sim = tem::Simulation::load("scene.json");
//   sim.set_external_force(0, {0, 0, -0.5});   // held for every step until changed
//   sim.step(100);
//   tem::Vec3 x = sim.position(0);
//
// `tem run` is a client of this class, and so is the Python module (python/); what either writes
// or computes, a C++ program gets the same, bit for bit.
//
// Memory: the state arrays (position_data() ...) point into the simulation's own storage; they
// stay valid, and see each new step without a copy, for the life of the Simulation object
// (moving the object keeps them valid too). Where bodies come and go (inlets, outlets,
// removed_at: docs/processes.md), body_count() changes between steps and the arrays hold the
// live bodies in the order of their ids: new ones are appended, removed ones taken out and the
// others moved up. The pointers still stay valid (room for every body the run can hold is
// reserved at load), but an index names whichever body is at that place now: look bodies up by
// name (body_index) after a step that changed body_count(). One Simulation is used from one thread at a time;
// step() shares its work among the threads set by set_threads().
#pragma once

#include <cstddef>
#include <cstdint>
#include <iosfwd>
#include <memory>
#include <string>
#include <vector>

#include "tem/scene_def.hpp"
#include "tem/types.hpp"

namespace tem {

// A scene that cannot be loaded: what() holds every problem, one per line, as `tem check`
// prints them ("FILE: JSON.path: reason").
class SceneLoadError : public std::runtime_error {
 public:
  explicit SceneLoadError(const std::string& message) : std::runtime_error(message) {}
};

// One contact patch of the last step: where it is at the step's start, its normal (unit, from
// body_a into body_b), its depth (negative: still a gap apart, contact before overlap), and the
// magnitudes of the normal and tangential forces held on body_a over the step.
struct Contact {
  int body_a = -1;
  int body_b = -1;  // -1 when the other side is a wall
  int wall = -1;    // the wall's index (the container's six faces first), or -1
  Vec3 point = Vec3::Zero();
  Vec3 normal = Vec3::UnitZ();
  Real depth = 0;
  Real normal_force = 0;
  Real tangential_force = 0;
};

// Energies of the bodies that move freely (bodies with a prescribed motion are driven from
// outside and not counted), and the work the driven bodies have done on them through contact
// since the start: with no external loads, total() - driven_work never rises.
struct SystemEnergies {
  Real kinetic = 0;
  Real potential = 0;  // of gravity, -M G.x summed
  Real driven_work = 0;
  Real total() const { return kinetic + potential; }
};

// What the steps taken so far cost and how the contact solver fared, summed over the steps
// since the Simulation was made or resumed (`tem run`'s closing summary prints them).
struct RunStatistics {
  long long steps = 0;
  // Seconds in each stage of the step (docs/method.md), summed over the steps.
  double broad_phase = 0;
  double narrow_phase = 0;  // narrow phase and patches
  double forces = 0;        // the contact solve
  double integrate = 0;
  // The contact solver's iterations (Gauss-Seidel sweeps, or Newton iterations with
  // contact.solver "newton": those of the island that took most), summed over the steps, the
  // most one step took, and the median over the steps (the lower one of an even count).
  long long solver_iterations = 0;
  int max_solver_iterations = 0;
  int median_solver_iterations = 0;
  long long unconverged_steps = 0;  // steps whose solve stopped at its iteration limit
  long long scaled_steps = 0;       // steps whose impulses were scaled down to add no energy
  long long corrected_steps = 0;    // steps whose overlap correction moved bodies apart
  // contact.solver "newton": islands not converged within newton_iteration_limit iterations,
  // solved by the row solver instead.
  long long fallback_islands = 0;
  int newton_iteration_limit = 0;
  // contact.solver "newton": islands that kept the regularised answer: moving islands of more
  // than moving_polish_bodies bodies, which are not polished, and islands whose polish to exact
  // friction did not converge (docs/method.md, "SEMM by Newton").
  long long regularised_islands = 0;
  int moving_polish_bodies = 0;
  long long outran_margin = 0;  // bodies that moved farther in a step than their contact margin
  long long substeps = 0;       // summed over the steps, and the most one step took
  int max_substeps = 0;
  long long patches = 0;  // contact patches and their points, summed over the steps
  long long points = 0;
  // Block pairs tested with contact before overlap, those that took last step's features and
  // those kept apart by last step's separating face (contact.pair_cache), summed.
  long long block_pairs = 0, cached_pairs = 0, apart_pairs = 0;
  long long sleeping_bodies = 0;  // asleep now (`sleep`)
};

class Simulation {
 public:
  // Loaders. Bad input throws SceneLoadError with every problem found.
  static Simulation load(const std::string& scene_file);
  // `origin` names the text in messages and scene.json's `source`.
  static Simulation from_json(const std::string& scene_json,
                              const std::string& origin = "<scene>");
  static Simulation from_scene(const SceneDef& scene);
  // The scene at a checkpoint written by write_checkpoint() or `tem run` (only `duration` and
  // `output.checkpoint_interval` may differ from the scene it was taken of).
  static Simulation resume(const std::string& scene_file, const std::string& checkpoint_file);

  Simulation(Simulation&&) noexcept;
  Simulation& operator=(Simulation&&) noexcept;
  ~Simulation();

  // --- stepping -------------------------------------------------------------------------
  // n whole steps of time_step(). While recording, the output rows fall due as in `tem run`.
  void step(long long n = 1);
  Real time() const;
  long long step_count() const;
  Real time_step() const;
  // Steps `tem run` takes for the scene's duration: round(duration / time_step).
  long long total_steps() const;
  // Threads for the step's shared work (OpenMP; 0: one per core). The results do not depend on
  // it. Process-wide: every Simulation stepped from any thread uses it from then on (without
  // a call, OpenMP's default, OMP_NUM_THREADS or one per core).
  static void set_threads(int threads);
  // The threads a step shares its work among now.
  static int threads();

  // --- inlets (docs/processes.md) ---------------------------------------------------------
  // Per inlet, in the scene's order: the copies it has placed, those that had fallen due by
  // now (a copy finds no room: it waits, and is late), and its count.
  struct InletDelivery {
    std::string name;
    long long placed = 0, due = 0, count = 0;
  };
  std::vector<InletDelivery> inlet_deliveries() const;

  // --- bodies ---------------------------------------------------------------------------
  int body_count() const;
  // The most bodies this run can hold at once (those at the start and every inlet's count):
  // the arrays below have room for them all, so their pointers never move.
  int body_capacity() const;
  // Changes whenever bodies come or go (inlets, outlets, removed_at): indices and names read
  // before such a change may no longer match.
  long long population_version() const;
  // Whether bodies can come and go in this scene (inlets, outlets, removed_at): then
  // body_count() may change between steps, and recording writes removed.csv.
  bool bodies_come_and_go() const;
  const std::string& body_name(int body) const;
  int body_index(const std::string& name) const;  // -1 when there is none
  bool body_fixed(int body) const;
  Real mass(int body) const;
  Mat3 inertia_body(int body) const;   // about the centre of mass, body axes
  Mat3 inertia_world(int body) const;  // about the centre of mass, world axes, now
  Real volume(int body) const;

  // State of one body now: centre of mass, attitude [w, x, y, z] (w >= 0), velocity of the
  // centre of mass, angular velocity (world axes).
  Vec3 position(int body) const;
  Quat attitude(int body) const;
  Vec3 velocity(int body) const;
  Vec3 angular_velocity(int body) const;

  // The same for all bodies at once, without a copy. position_data() and velocity_data() point
  // at body 0's x and v inside TEM's own state; body i's are state_stride() bytes further on.
  // quaternion_data() (4 per body, [w, x, y, z]) and angular_velocity_data() (3 per body, world
  // axes) are contiguous arrays that TEM refreshes after every step.
  const Real* position_data() const;
  const Real* velocity_data() const;
  std::ptrdiff_t state_stride() const;
  const Real* quaternion_data() const;
  const Real* angular_velocity_data() const;
  // The first body whose state stopped being finite (a blown-up scene), or -1.
  int first_non_finite_body() const;

  // --- forces from outside --------------------------------------------------------------
  // Per body, world axes, the torque about the centre of mass; held through every step until
  // changed (zero at the start). Fixed bodies ignore them. The data pointers are contiguous,
  // 3 per body, writable between steps.
  void set_external_force(int body, const Vec3& force);
  void set_external_torque(int body, const Vec3& torque);
  Vec3 external_force(int body) const;
  Vec3 external_torque(int body) const;
  Real* external_force_data();
  Real* external_torque_data();
  void clear_external_loads();

  // --- results --------------------------------------------------------------------------
  // The patches of the last step taken (empty before the first).
  std::vector<Contact> contacts() const;
  // Finds the contact patches of the current state without stepping and writes them as
  // contacts.csv's header and rows (docs/interface.md; forces zero); returns how many.
  std::size_t write_contacts_csv(std::ostream& out) const;
  RunStatistics run_statistics() const;
  SystemEnergies energies() const;
  // A 64-bit hash of the state's exact bits, as `tem run --hash` prints it (hex: state_hash_hex).
  std::uint64_t state_hash() const;
  std::string state_hash_hex() const;

  // --- files ----------------------------------------------------------------------------
  // Writes `tem run`'s files into `directory` (bodies.csv, energy.csv, scene.json; with
  // `contacts` contacts.csv; ParaView files when the scene asks) from the current state on: a
  // row now, then every output interval, and finish_recording() writes the last state's row.
  // An earlier run's files in `directory` that this run would not write again (contacts.csv,
  // removed.csv, sensors.csv, ParaView frames; only files TEM wrote, known by name and header)
  // are removed, and its checkpoint.bin; returns the names of the former, for a message.
  std::vector<std::string> record(const std::string& directory, bool contacts = false);
  // Continues a run that `tem run` or record() left in `directory` from its checkpoint.bin:
  // the files are cut back to that point and appended to. Throws std::runtime_error when the
  // checkpoint belongs to another scene or run.
  static Simulation resume_recording(const std::string& scene_file, const std::string& directory,
                                     bool contacts);
  bool recording() const;
  void finish_recording();
  // State and the contact solver's memory (warm start, friction, penalty springs): resuming
  // from it continues bit for bit. While recording, also the files' sizes.
  void write_checkpoint(const std::string& path);

  // The scene as loaded, defaults filled in.
  const SceneDef& scene() const;
  // Warnings about accepted defects of the scene (a non-convex block allowed, a penalty
  // contact's time step above its stable limit, inlets that cannot deliver; and, when the
  // simulation starts at the scene's start rather than at a checkpoint, bodies overlapping
  // deeply at the start), one line each.
  const std::vector<std::string>& warnings() const;

  // For TEM's own tests and the MPI driver, built on its internals: the implementation object.
  struct Impl;
  Impl& impl() { return *impl_; }
  const Impl& impl() const { return *impl_; }

 private:
  explicit Simulation(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace tem
