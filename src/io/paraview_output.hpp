// ParaView output of `tem run` (scene key output.paraview): per output frame, the bodies'
// surfaces and the contact patches as two .vtu files under DIR/paraview/, and DIR/tem.pvd, the
// collection that lists them with their times (part 0 bodies, part 1 contacts).
//
// tem.pvd is a complete, valid collection after every frame, however the run ends, and only ever
// lists frames whose files are complete. A frame costs the same however many came before it: its
// DataSet lines are written over the closing tags at the end of the file, followed by the closing
// tags again, in one write (so the file holds the old collection or the new one, unless the
// write itself is cut short). The whole file is written, to a temporary file renamed over the
// old one, only when the collection starts (new or resumed) and when a frame replaces listed ones.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "simulation/step.hpp"

namespace tem {

class ParaviewOutput {
 public:
  // Creates DIR/paraview/. With resume_step: keeps the frames of an existing DIR/tem.pvd whose
  // step <= *resume_step and deletes the frame files of later steps, so that a resumed run
  // continues the collection; without: starts a new collection and deletes the frame files of
  // an earlier run. Writes tem.pvd at once. Throws std::runtime_error naming the file or
  // directory that cannot be written.
  ParaviewOutput(const std::string& directory, const Model& model,
                 std::optional<long long> resume_step);

  // Removes an earlier run's ParaView files from `directory`: its frame files in paraview/
  // (named as this class names them), paraview/ itself once empty, and tem.pvd when it is a
  // collection as write_collection() writes it. Returns what it removed, for a message (empty
  // when there was nothing).
  static std::vector<std::string> remove_collection(const std::string& directory);

  // One frame at state.step and state.time: the bodies at `state`, and the patches and patch
  // forces of the step that starts from it (as bodies.csv and contacts.csv). A frame of a step
  // already listed replaces it, and drops the frames after it.
  void write(const Model& model, const State& state, const Workspace& workspace);

  // The file names, relative to DIR, of the frame of `step`: whole .vtu files, or with
  // `pieces` > 0 the .pvtu files over that many pieces.
  static std::string bodies_file(long long step, int pieces = 0);
  static std::string contacts_file(long long step, int pieces = 0);
  // One rank's piece of a frame, relative to DIR.
  static std::string bodies_piece(long long step, int rank);
  static std::string contacts_piece(long long step, int rank);

  // From now on, frames are written as `ranks` pieces (one per MPI rank, each written by its
  // rank with write_piece before write() is called for the frame), which write() gathers into
  // .pvtu files: one tem.pvd over per-rank pieces.
  void use_pieces(int ranks) { pieces_ = ranks; }
  // One rank's piece of the frame at state.step: the bodies flagged in `owned`, the patches
  // and forces given.
  static void write_piece(const std::string& directory, const Model& model, const State& state,
                          const std::vector<char>& owned, const std::vector<ContactPatch>& patches,
                          const std::vector<PatchForce>& forces, int rank);

 private:
  struct Frame {
    long long step;
    std::string time;  // as written in tem.pvd, so a resumed collection keeps it digit for digit
    int pieces = 0;    // 0: whole .vtu files; else .pvtu files over that many pieces
  };

  // The whole collection, to tem.pvd.tmp renamed over tem.pvd.
  void write_collection();
  // Lists the last frame of frames_, after the ones tem.pvd lists.
  void append_to_collection();

  std::string directory_;
  std::vector<Frame> frames_;
  long long tail_offset_ = 0;  // where tem.pvd's closing tags start
  int pieces_ = 0;
};

}  // namespace tem
