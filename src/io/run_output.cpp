#include "io/run_output.hpp"

#include <Eigen/SVD>
#include <algorithm>
#include <filesystem>
#include <stdexcept>

#include "io/contacts_csv.hpp"
#include "io/csv_number.hpp"
#include "io/scene_writer.hpp"
#include "process/population.hpp"

namespace tem {
namespace {

// A new file with its header; or, resuming, the earlier run's file cut back to `size` bytes.
void open(std::ofstream& file, const std::string& path, const char* header,
          std::int64_t resume_size) {
  if (resume_size >= 0) {
    std::error_code error;
    const auto size = std::filesystem::file_size(path, error);
    if (error || size < static_cast<std::uintmax_t>(resume_size))
      throw std::runtime_error(path + ": shorter than at the checkpoint; cannot resume");
    std::filesystem::resize_file(path, static_cast<std::uintmax_t>(resume_size), error);
    if (error) throw std::runtime_error(path + ": cannot be cut back: " + error.message());
    // Not ios::app: tellp (the sizes a checkpoint records) starts at 0 there until a write.
    file.open(path, std::ios::in | std::ios::out | std::ios::ate);
    if (!file) throw std::runtime_error(path + ": cannot be written");
    return;
  }
  file.open(path, std::ios::out | std::ios::trunc);
  if (!file) throw std::runtime_error(path + ": cannot be written");
  file << header << '\n' << std::flush;
}

constexpr const char* kEnergyHeader = "time,kinetic,potential,total,contacts,max_depth";
// Where bodies have a prescribed motion, the work they did on the others (interface.md): last,
// after the columns every scene has.
constexpr const char* kEnergyHeaderDriven =
    "time,kinetic,potential,total,contacts,max_depth,driven_work";
constexpr const char* kRemovedHeader = "time,body,x,y,z,vx,vy,vz,mass";
constexpr const char* kSensorsHeader = "time,sensor,count,mass,fx,fy,fz,tx,ty,tz";

// Removes `directory/name` if its first line is `header` (a file TEM wrote); true if removed.
bool remove_if_written_by_tem(const std::string& directory, const std::string& name,
                              const char* header) {
  const std::string path = directory + "/" + name;
  std::string first;
  {
    std::ifstream file(path);
    if (!file || !std::getline(file, first) || first != header) return false;
  }
  std::error_code error;
  return std::filesystem::remove(path, error);
}

}  // namespace

Quat attitude_quaternion(const Mat3& g) {
  Mat3 rotation = g;
  if ((g.transpose() * g - Mat3::Identity()).norm() > 1e-12) {
    const Eigen::JacobiSVD<Mat3> svd(g, Eigen::ComputeFullU | Eigen::ComputeFullV);
    rotation = svd.matrixU() * svd.matrixV().transpose();
  }
  Quat q(rotation);
  q.normalize();
  if (q.w() < 0) q.coeffs() *= -1;
  return q;
}

RunOutput::RunOutput(const std::string& directory, const Model& model, bool contacts,
                     const Checkpoint* checkpoint)
    : with_contacts_(contacts) {
  const OutputSizes* resume = checkpoint ? &checkpoint->sizes : nullptr;
  if (resume && (resume->contacts >= 0) != contacts)
    throw std::runtime_error(std::string("the run being resumed was started ") +
                             (contacts ? "without" : "with") +
                             " --contacts; resume it the same way");
  std::error_code error;
  std::filesystem::create_directories(directory, error);
  if (error) throw std::runtime_error(directory + ": cannot be created: " + error.message());
  with_removed_ = model.bodies_come_and_go;
  with_sensors_ = !model.scene.sensors.empty();
  if (!resume) {
    // A new run into a directory that holds an earlier run's files: those this run does not
    // write again go, so that no file in the directory is older than the run.
    const auto stale = [&](bool written, const std::string& name, const char* header) {
      if (!written && remove_if_written_by_tem(directory, name, header))
        earlier_removed_.push_back(name);
    };
    stale(contacts, "contacts.csv", kContactsCsvHeader);
    stale(with_removed_, "removed.csv", kRemovedHeader);
    stale(with_sensors_, "sensors.csv", kSensorsHeader);
    // The earlier checkpoint too: until this run writes its own, --resume would continue it
    // over this run's files. Not listed: the run writes checkpoint.bin again.
    const std::string checkpoint_file = directory + "/checkpoint.bin";
    if (is_checkpoint_file(checkpoint_file)) std::filesystem::remove(checkpoint_file, error);
    if (!model.scene.output.paraview)
      for (std::string& name : ParaviewOutput::remove_collection(directory))
        earlier_removed_.push_back(std::move(name));
  }
  std::string message;
  if (!write_scene_file(model.scene, directory + "/scene.json", &message))
    throw std::runtime_error(message);
  open(bodies_, directory + "/bodies.csv", kBodiesHeader, resume ? resume->bodies : -1);
  with_driven_work_ = model.any_motion;
  open(energy_, directory + "/energy.csv", with_driven_work_ ? kEnergyHeaderDriven : kEnergyHeader,
       resume ? resume->energy : -1);
  if (contacts)
    open(contacts_, directory + "/contacts.csv", kContactsCsvHeader,
         resume ? resume->contacts : -1);
  if (with_removed_)
    open(removed_, directory + "/removed.csv", kRemovedHeader, resume ? resume->removed : -1);
  if (with_sensors_)
    open(sensors_, directory + "/sensors.csv", kSensorsHeader, resume ? resume->sensors : -1);
  if (model.scene.output.paraview)
    // The frame of the checkpoint's step is written again by the resumed run.
    paraview_ = std::make_unique<ParaviewOutput>(
        directory, model,
        checkpoint ? std::optional<long long>(checkpoint->state.step - 1) : std::nullopt);
}

void append_body_rows(std::string& rows, const Model& model, const State& state) {
  for (size_t i = 0; i < model.bodies.size(); ++i) {
    const BodyState& s = state.bodies[i];
    const Quat q = attitude_quaternion(s.g);
    const Vec3 w = s.angular_velocity_world();
    append_number(rows, state.time);
    rows += ',' + model.bodies[i].name;
    for (int k = 0; k < 3; ++k) append_field(rows, s.x[k]);
    for (Real c : {q.w(), q.x(), q.y(), q.z()}) append_field(rows, c);
    for (int k = 0; k < 3; ++k) append_field(rows, s.v[k]);
    for (int k = 0; k < 3; ++k) append_field(rows, w[k]);
    rows += '\n';
  }
}

void RunOutput::write(const Model& model, const State& state, const Workspace& workspace) {
  std::string rows;
  append_body_rows(rows, model, state);
  bodies_ << rows << std::flush;

  const Energies e = system_energies(model, state);
  Real max_depth = 0;
  for (const ContactPatch& p : workspace.patches) max_depth = std::max(max_depth, p.depth);
  rows.clear();
  append_number(rows, state.time);
  append_field(rows, e.kinetic);
  append_field(rows, e.potential);
  append_field(rows, e.total());
  rows += ',' + std::to_string(workspace.patches.size());
  append_field(rows, max_depth);
  if (with_driven_work_) append_field(rows, state.driven_work);
  rows += '\n';
  energy_ << rows << std::flush;

  if (with_contacts_) {
    write_contact_rows(contacts_, model, state.time, workspace.patches,
                       workspace.forces.patch_forces);
    contacts_ << std::flush;
  }
  if (!bodies_ || !energy_ || (with_contacts_ && !contacts_))
    throw std::runtime_error("writing the results failed (disk full?)");
  if (paraview_) paraview_->write(model, state, workspace);
}

void RunOutput::write_removed(const std::vector<RemovedBody>& removed) {
  if (!with_removed_ || removed.empty()) return;
  std::string rows;
  for (const RemovedBody& r : removed) {
    append_number(rows, r.time);
    rows += ',' + r.name;
    for (int k = 0; k < 3; ++k) append_field(rows, r.x[k]);
    for (int k = 0; k < 3; ++k) append_field(rows, r.v[k]);
    append_field(rows, r.mass);
    rows += '\n';
  }
  removed_ << rows << std::flush;
  if (!removed_) throw std::runtime_error("writing removed.csv failed (disk full?)");
}

void RunOutput::write_sensors(const Model& model, Real time,
                              const std::vector<SensorReading>& readings) {
  if (!with_sensors_) return;
  std::string rows;
  for (size_t k = 0; k < readings.size(); ++k) {
    const SensorReading& r = readings[k];
    append_number(rows, time);
    rows += ',' + model.scene.sensors[k].name + ',' + std::to_string(r.count);
    append_field(rows, r.mass);
    for (int a = 0; a < 3; ++a) append_field(rows, r.force[a]);
    for (int a = 0; a < 3; ++a) append_field(rows, r.torque[a]);
    rows += '\n';
  }
  sensors_ << rows << std::flush;
  if (!sensors_) throw std::runtime_error("writing sensors.csv failed (disk full?)");
}

OutputSizes RunOutput::sizes() {
  OutputSizes s;
  s.bodies = static_cast<std::int64_t>(bodies_.tellp());
  s.energy = static_cast<std::int64_t>(energy_.tellp());
  s.contacts = with_contacts_ ? static_cast<std::int64_t>(contacts_.tellp()) : -1;
  s.removed = with_removed_ ? static_cast<std::int64_t>(removed_.tellp()) : -1;
  s.sensors = with_sensors_ ? static_cast<std::int64_t>(sensors_.tellp()) : -1;
  return s;
}

}  // namespace tem
