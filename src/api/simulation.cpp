#include "tem/simulation.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "api/output_steps.hpp"
#include "api/scene_loading.hpp"
#include "api/simulation_impl.hpp"
#include "contact/detect_contacts.hpp"
#include "forces/semm_newton/semm_newton.hpp"
#include "io/checkpoint.hpp"
#include "io/contacts_csv.hpp"
#include "io/scene_reader.hpp"
#include "io/scene_writer.hpp"
#include "simulation/sleep.hpp"
#include "support/parallel.hpp"
#include "world/inlet_delivery.hpp"
#include "world/state_hash.hpp"

namespace tem {
namespace {

// The thread count asked for through the API, for every thread that steps: OpenMP's own
// setting belongs to the thread that made it, so a Simulation stepped from another thread (a
// Python worker thread, say) would otherwise run at OpenMP's default. <= 0: never asked.
std::atomic<int> requested_threads{0};

// The checkpoint of `path`, checked against the scene.
Checkpoint read_matching_checkpoint(const Model& model, const std::string& path,
                                    const std::string& scene_name) {
  Checkpoint c = read_checkpoint(path);
  require_same_files(c.files, scene_files(model.scene), path);
  if (c.scene_fingerprint != scene_fingerprint(model.scene)) {
    // A scene that names no SEMM solver, checkpointed while the rows were the default.
    std::string how;
    if (model.scene.contact.model == ContactModel::semm &&
        model.scene.contact.solver == ContactSolver::newton) {
      SceneDef rows = model.scene;
      rows.contact.solver = ContactSolver::rows;
      if (c.scene_fingerprint == scene_fingerprint(rows))
        how =
            "; it was taken with contact.solver \"rows\", the default before \"newton\": add "
            "\"solver\": \"rows\" to the scene's contact to resume it";
    }
    throw std::runtime_error(path + " was taken of another scene than " + scene_name +
                             " (only duration and checkpoint_interval may change" + how + ")");
  }
  // Where bodies come and go, the checkpoint's tags say which are there (restore checks them).
  if (!model.bodies_come_and_go && c.state.bodies.size() != model.bodies.size())
    throw std::runtime_error(path + " holds " + std::to_string(c.state.bodies.size()) +
                             " bodies, the scene " + std::to_string(model.bodies.size()));
  return c;
}

}  // namespace

// --- Impl ----------------------------------------------------------------------------------

Simulation::Impl::Impl(Model m) : model(std::move(m)) {
  state = initial_state(model);
  warnings = start_warnings(model, /*at_start=*/true);
  const size_t n = model.bodies.size();
  workspace.loads.force.assign(n, Vec3::Zero());
  workspace.loads.torque.assign(n, Vec3::Zero());
  if (model.bodies_come_and_go) initial_bodies = model.bodies;
  reserve_capacity();
  start_population(model, state, links(), removed);
  refresh_views();
}

void Simulation::Impl::reserve_capacity() {
  const size_t capacity = population_capacity(model);
  try {
    model.bodies.reserve(capacity);  // the mass, volume and inertia views point into it
    state.bodies.reserve(capacity);
    state.tags.reserve(capacity);
    workspace.loads.force.reserve(capacity);
    workspace.loads.torque.reserve(capacity);
    quaternions.reserve(4 * capacity);
    angular_velocities.reserve(3 * capacity);
  } catch (const std::exception&) {  // std::bad_alloc, or std::length_error past max_size()
    // Not a bare "std::bad_alloc": say how many bodies, how much memory and which keys.
    const double per_body =
        sizeof(Body) + sizeof(BodyState) + sizeof(BodyTag) + 2 * sizeof(Vec3) + 7 * sizeof(Real);
    std::ostringstream m;
    m << "the run must hold up to " << capacity << " bodies at once (" << model.bodies.size()
      << " at the start";
    for (const InletDef& inlet : model.scene.inlets)
      m << ", " << inlet.path << ".count " << inlet.count;
    m << "), about " << std::setprecision(3) << per_body * static_cast<double>(capacity) / 1e9
      << " GB for their records alone, more than this machine can allocate; lower the inlets' "
         "count";
    throw std::runtime_error(m.str());
  }
}

void Simulation::Impl::refresh_views() {
  quaternions.resize(4 * state.bodies.size());
  angular_velocities.resize(3 * state.bodies.size());
  for (size_t i = 0; i < state.bodies.size(); ++i) {
    const BodyState& s = state.bodies[i];
    const Quat q = attitude_quaternion(s.g);
    quaternions[4 * i] = q.w();
    quaternions[4 * i + 1] = q.x();
    quaternions[4 * i + 2] = q.y();
    quaternions[4 * i + 3] = q.z();
    const Vec3 w = s.angular_velocity_world();
    for (int k = 0; k < 3; ++k) angular_velocities[3 * i + k] = w[k];
  }
}

void Simulation::Impl::restore(const Checkpoint& checkpoint) {
  state = checkpoint.state;
  warnings = start_warnings(model, /*at_start=*/false);  // the start's overlaps are past
  if (model.bodies_come_and_go) restore_population(model, initial_bodies, state);
  const size_t n = model.bodies.size();
  workspace.loads.force.assign(n, Vec3::Zero());
  workspace.loads.torque.assign(n, Vec3::Zero());
  removed.clear();
  reserve_capacity();
  restore_memory(checkpoint, model.scene.contact, workspace.forces, workspace.contact.features);
  refresh_views();
}

void Simulation::Impl::start_recording(const std::string& dir, std::unique_ptr<RunOutput> out) {
  output = std::move(out);
  directory = dir;
  const SceneDef& scene = model.scene;
  every = steps_per(scene.output.interval, scene.time_step);
  checkpoint_every = scene.output.checkpoint_interval > 0
                         ? steps_per(scene.output.checkpoint_interval, scene.time_step)
                         : 0;
  first_step = state.step;
  written_step = -1;
  // Bodies that left at the start (an outlet holding some, removed_at 0) before recording.
  output->write_removed(removed);
  removed.clear();
}

void Simulation::Impl::write_row() {
  StepHooks none;
  find_forces(model, state, workspace, none);
  write_found_row();
}

void Simulation::Impl::write_found_row() {
  output->write(model, state, workspace);
  output->write_sensors(model, state.time, take_sensor_readings(model, state, workspace.forces));
  written_step = state.step;
}

void Simulation::Impl::advance_one() {
  take_step(model, state, workspace, removed, *this);
  stepped = true;
}

// As `tem run`: a checkpoint where a step begins, before its rows (resuming redoes them).
void Simulation::Impl::step_begins(const Model&, State&, Workspace&) {
  const long long k = state.step;
  if (output && checkpoint_every > 0 && k % checkpoint_every == 0 && k != first_step)
    tem::write_checkpoint(directory + "/checkpoint.bin",
                          make_checkpoint(model.scene, state, workspace.forces,
                                          workspace.contact.features, output->sizes()));
}

void Simulation::Impl::forces_found(const Model&, const State&, const Workspace&) {
  const long long k = state.step;
  if (output && k % every == 0 && written_step != k) write_found_row();
}

void Simulation::Impl::bodies_left(const std::vector<RemovedBody>& left) {
  if (output) output->write_removed(left);
}

// --- loading -------------------------------------------------------------------------------

Simulation::Simulation(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Simulation::Simulation(Simulation&&) noexcept = default;
Simulation& Simulation::operator=(Simulation&&) noexcept = default;
Simulation::~Simulation() = default;

Simulation Simulation::load(const std::string& scene_file) {
  return Simulation(std::make_unique<Impl>(load_model_or_throw(scene_file)));
}

Simulation Simulation::from_json(const std::string& scene_json, const std::string& origin) {
  SceneReadResult read = read_scene_text(scene_json, origin);
  load_scene_meshes(read);
  return Simulation(std::make_unique<Impl>(build_model_or_throw(read, origin)));
}

Simulation Simulation::from_scene(const SceneDef& scene) {
  // Through the scene file's text, so that a scene built in code meets every check a file does
  // (a negative size, NaN, a missing key's default).
  const std::string origin = scene.source.empty() ? "<scene>" : scene.source;
  return from_json(write_scene_text(scene), origin);
}

Simulation Simulation::resume(const std::string& scene_file, const std::string& checkpoint_file) {
  Simulation sim = load(scene_file);
  sim.impl_->restore(read_matching_checkpoint(sim.impl_->model, checkpoint_file, scene_file));
  return sim;
}

Simulation Simulation::resume_recording(const std::string& scene_file, const std::string& directory,
                                        bool contacts) {
  Simulation sim = load(scene_file);
  Impl& m = *sim.impl_;
  const std::string file = directory + "/checkpoint.bin";
  const Checkpoint c = read_matching_checkpoint(m.model, file, scene_file);
  if (c.state.step > sim.total_steps())
    throw std::runtime_error(file + " is at step " + std::to_string(c.state.step) +
                             ", beyond the scene's " + std::to_string(sim.total_steps()) +
                             " steps");
  if ((c.sizes.contacts >= 0) != contacts)
    throw std::runtime_error(std::string("the run in ") + directory + " was started " +
                             (contacts ? "without" : "with") +
                             " --contacts; resume it the same way");
  m.restore(c);
  m.start_recording(directory, std::make_unique<RunOutput>(directory, m.model, contacts, &c));
  return sim;
}

// --- stepping ------------------------------------------------------------------------------

void Simulation::step(long long n) {
  const int threads = requested_threads.load();
  if (threads > 0 && max_threads() != threads) tem::set_threads(threads);
  for (long long i = 0; i < n; ++i) impl_->advance_one();
  impl_->refresh_views();
}

Real Simulation::time() const { return impl_->state.time; }
long long Simulation::step_count() const { return impl_->state.step; }
Real Simulation::time_step() const { return impl_->model.scene.time_step; }
long long Simulation::total_steps() const {
  return std::llround(impl_->model.scene.duration / impl_->model.scene.time_step);
}
void Simulation::set_threads(int threads) {
  if (threads == 0) threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  if (threads < 0) return;
  requested_threads.store(threads);
  tem::set_threads(threads);
}

int Simulation::threads() { return max_threads(); }

// --- bodies --------------------------------------------------------------------------------

namespace {
void check_body(const Model& model, int body) {
  if (body < 0 || body >= static_cast<int>(model.bodies.size()))
    throw std::out_of_range("body index " + std::to_string(body) + " is not in 0.." +
                            std::to_string(static_cast<long long>(model.bodies.size()) - 1));
}
}  // namespace

int Simulation::body_count() const { return static_cast<int>(impl_->model.bodies.size()); }
int Simulation::body_capacity() const {
  return static_cast<int>(population_capacity(impl_->model));
}
long long Simulation::population_version() const { return impl_->model.population_version; }
bool Simulation::bodies_come_and_go() const { return impl_->model.bodies_come_and_go; }
const std::string& Simulation::body_name(int body) const {
  check_body(impl_->model, body);
  return impl_->model.bodies[body].name;
}
int Simulation::body_index(const std::string& name) const {
  for (size_t i = 0; i < impl_->model.bodies.size(); ++i)
    if (impl_->model.bodies[i].name == name) return static_cast<int>(i);
  return -1;
}
bool Simulation::body_fixed(int body) const {
  check_body(impl_->model, body);
  return impl_->model.bodies[body].fixed;
}
Real Simulation::mass(int body) const {
  check_body(impl_->model, body);
  return impl_->model.bodies[body].inertia.mass;
}
Mat3 Simulation::inertia_body(int body) const {
  check_body(impl_->model, body);
  return impl_->model.bodies[body].inertia.inertia;
}
Mat3 Simulation::inertia_world(int body) const {
  check_body(impl_->model, body);
  const Mat3& g = impl_->state.bodies[body].g;
  return g * impl_->model.bodies[body].inertia.inertia * g.transpose();
}
Real Simulation::volume(int body) const {
  check_body(impl_->model, body);
  return impl_->model.bodies[body].volume;
}

Vec3 Simulation::position(int body) const {
  check_body(impl_->model, body);
  return impl_->state.bodies[body].x;
}
Quat Simulation::attitude(int body) const {
  check_body(impl_->model, body);
  return attitude_quaternion(impl_->state.bodies[body].g);
}
Vec3 Simulation::velocity(int body) const {
  check_body(impl_->model, body);
  return impl_->state.bodies[body].v;
}
Vec3 Simulation::angular_velocity(int body) const {
  check_body(impl_->model, body);
  return impl_->state.bodies[body].angular_velocity_world();
}

const Real* Simulation::position_data() const {
  return impl_->state.bodies.empty() ? nullptr : impl_->state.bodies[0].x.data();
}
const Real* Simulation::velocity_data() const {
  return impl_->state.bodies.empty() ? nullptr : impl_->state.bodies[0].v.data();
}
std::ptrdiff_t Simulation::state_stride() const { return sizeof(BodyState); }
const Real* Simulation::quaternion_data() const { return impl_->quaternions.data(); }
const Real* Simulation::angular_velocity_data() const { return impl_->angular_velocities.data(); }
int Simulation::first_non_finite_body() const { return tem::first_non_finite_body(impl_->state); }

// --- external loads ------------------------------------------------------------------------

void Simulation::set_external_force(int body, const Vec3& force) {
  check_body(impl_->model, body);
  impl_->workspace.loads.force[body] = force;
}
void Simulation::set_external_torque(int body, const Vec3& torque) {
  check_body(impl_->model, body);
  impl_->workspace.loads.torque[body] = torque;
}
Vec3 Simulation::external_force(int body) const {
  check_body(impl_->model, body);
  return impl_->workspace.loads.force[body];
}
Vec3 Simulation::external_torque(int body) const {
  check_body(impl_->model, body);
  return impl_->workspace.loads.torque[body];
}
// Vec3 is three packed doubles (Eigen's fixed vectors carry no padding), so the vector of them
// is one contiguous array of 3 N doubles.
static_assert(sizeof(Vec3) == 3 * sizeof(Real));
Real* Simulation::external_force_data() { return impl_->workspace.loads.force.data()->data(); }
Real* Simulation::external_torque_data() { return impl_->workspace.loads.torque.data()->data(); }
void Simulation::clear_external_loads() {
  for (Vec3& f : impl_->workspace.loads.force) f.setZero();
  for (Vec3& t : impl_->workspace.loads.torque) t.setZero();
}

// --- results -------------------------------------------------------------------------------

std::vector<Contact> Simulation::contacts() const {
  std::vector<Contact> out;
  if (!impl_->stepped) return out;
  const Workspace& w = impl_->workspace;
  out.reserve(w.patches.size());
  for (size_t k = 0; k < w.patches.size(); ++k) {
    const ContactPatch& p = w.patches[k];
    Contact c;
    c.body_a = p.body_a;
    c.body_b = p.body_b;
    c.wall = p.wall;
    c.point = p.point;
    c.normal = p.normal;
    c.depth = p.depth;
    if (k < w.forces.patch_forces.size()) {
      c.normal_force = w.forces.patch_forces[k].normal;
      c.tangential_force = w.forces.patch_forces[k].tangential;
    }
    out.push_back(c);
  }
  return out;
}

std::size_t Simulation::write_contacts_csv(std::ostream& out) const {
  const Impl& m = *impl_;
  ContactWorkspace scratch;
  std::vector<ContactPatch> patches;
  detect_contacts(m.model, m.state, patch_variant(m.model.scene), scratch, patches);
  out << kContactsCsvHeader << "\n";
  write_contact_rows(out, m.model, m.state.time, patches);
  return patches.size();
}

RunStatistics Simulation::run_statistics() const {
  const StageTimes& t = impl_->workspace.times;
  RunStatistics r;
  r.steps = t.steps;
  r.broad_phase = t.broad_phase;
  r.narrow_phase = t.narrow_phase;
  r.forces = t.forces;
  r.integrate = t.integrate;
  r.solver_iterations = t.sweeps;
  r.max_solver_iterations = t.max_sweeps;
  long long below = 0;  // steps that took at most `count` iterations
  for (size_t count = 0; count < t.steps_by_sweeps.size(); ++count) {
    below += t.steps_by_sweeps[count];
    if (2 * below >= t.steps) {
      r.median_solver_iterations = static_cast<int>(count);
      break;
    }
  }
  r.unconverged_steps = t.unconverged_steps;
  r.scaled_steps = t.scaled_steps;
  r.corrected_steps = t.corrected_steps;
  r.fallback_islands = t.fallback_islands;
  r.regularised_islands = t.regularised_islands;
  r.newton_iteration_limit = kMaxNewtonIterations;
  r.moving_polish_bodies = kMovingPolishBodies;
  r.outran_margin = t.outran_margin;
  r.substeps = t.substeps;
  r.max_substeps = t.max_substeps;
  r.patches = t.patches;
  r.points = t.points;
  r.block_pairs = t.block_pairs;
  r.cached_pairs = t.cached_pairs;
  r.apart_pairs = t.apart_pairs;
  r.sleeping_bodies = sleeping_bodies(impl_->state);
  return r;
}

SystemEnergies Simulation::energies() const {
  const Energies e = system_energies(impl_->model, impl_->state);
  return {e.kinetic, e.potential, impl_->state.driven_work};
}

std::vector<Simulation::InletDelivery> Simulation::inlet_deliveries() const {
  std::vector<InletDelivery> out;
  const SceneDef& scene = impl_->model.scene;
  for (size_t j = 0; j < scene.inlets.size(); ++j) {
    const InletDef& inlet = scene.inlets[j];
    out.push_back({inlet.name, impl_->state.inlets[j].placed, copies_due(inlet, impl_->state.time),
                   inlet.count});
  }
  return out;
}

std::uint64_t Simulation::state_hash() const { return tem::state_hash(impl_->state); }
std::string Simulation::state_hash_hex() const { return hash_hex(state_hash()); }

// --- files ---------------------------------------------------------------------------------

std::vector<std::string> Simulation::record(const std::string& directory, bool contacts) {
  auto output = std::make_unique<RunOutput>(directory, impl_->model, contacts);
  std::vector<std::string> removed = output->earlier_files_removed();
  impl_->start_recording(directory, std::move(output));
  return removed;
}

bool Simulation::recording() const { return impl_->output != nullptr; }

void Simulation::finish_recording() {
  Impl& m = *impl_;
  if (!m.output) return;
  if (m.written_step != m.state.step) m.write_row();
  m.output.reset();
}

void Simulation::write_checkpoint(const std::string& path) {
  Impl& m = *impl_;
  const OutputSizes sizes = m.output ? m.output->sizes() : OutputSizes{0, 0, -1};
  tem::write_checkpoint(path, make_checkpoint(m.model.scene, m.state, m.workspace.forces,
                                              m.workspace.contact.features, sizes));
}

const SceneDef& Simulation::scene() const { return impl_->model.scene; }
const std::vector<std::string>& Simulation::warnings() const { return impl_->warnings; }

}  // namespace tem
