// The files of `tem run` (interface.md): bodies.csv, energy.csv, contacts.csv (optional) and
// scene.json in the output directory. Every row is flushed as it is written, so that the files
// stay readable whatever stops the run.
#pragma once

#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "io/checkpoint.hpp"
#include "io/paraview_output.hpp"
#include "process/population.hpp"
#include "process/sensors.hpp"
#include "simulation/step.hpp"

namespace tem {

class RunOutput {
 public:
  // Creates `directory` if needed and writes scene.json and the CSV headers. Throws
  // std::runtime_error naming the file that cannot be written. With `resume`, the files of an
  // earlier run are cut back to the sizes they had at its checkpoint and appended to.
  RunOutput(const std::string& directory, const Model& model, bool contacts,
            const Checkpoint* resume = nullptr);

  // Rows for `state`, with the patches and forces of the step that starts from it.
  void write(const Model& model, const State& state, const Workspace& workspace);

  // Rows of removed.csv for bodies that left (scenes where bodies can leave).
  void write_removed(const std::vector<RemovedBody>& removed);
  // Rows of sensors.csv at `time` (scenes with sensors).
  void write_sensors(const Model& model, Real time, const std::vector<SensorReading>& readings);

  // How long the files are now (what a checkpoint records).
  OutputSizes sizes();

  // The files of an earlier run that a new (not resumed) run removed from the directory because
  // it does not write them again (contacts.csv, removed.csv, sensors.csv, ParaView frames):
  // left there, they would pass for this run's. Only files TEM writes, recognised by name and
  // by their header, are removed. (An earlier checkpoint.bin is removed too, unlisted: the run
  // writes its own.)
  const std::vector<std::string>& earlier_files_removed() const { return earlier_removed_; }

  // The ParaView collection (output.paraview), or null.
  ParaviewOutput* paraview() { return paraview_.get(); }

 private:
  std::ofstream bodies_, energy_, contacts_, removed_, sensors_;
  bool with_contacts_;
  bool with_removed_ = false, with_sensors_ = false, with_driven_work_ = false;
  std::unique_ptr<ParaviewOutput> paraview_;  // with output.paraview
  std::vector<std::string> earlier_removed_;
};

// Attitude quaternion (w >= 0) of the rotation nearest to g: g itself in the default mode; in
// paper mode, where eq. 16 lets g drift off the rotations, its polar factor.
Quat attitude_quaternion(const Mat3& g);

// bodies.csv: its header, and one row a body of `state` (interface.md's columns) appended to
// `rows`.
inline constexpr const char* kBodiesHeader = "time,body,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz";
void append_body_rows(std::string& rows, const Model& model, const State& state);

}  // namespace tem
