#include "io/paraview_output.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string_view>

#include "io/csv_number.hpp"
#include "io/paraview_frames.hpp"

namespace tem {
namespace {

namespace fs = std::filesystem;

void write_text_file(const std::string& path, const std::string& text) {
  std::ofstream file(path, std::ios::out | std::ios::trunc | std::ios::binary);
  if (file) file.write(text.data(), static_cast<std::streamsize>(text.size()));
  file.close();
  if (!file) throw std::runtime_error(path + ": cannot be written");
}

// The step of a frame file name "bodies_<12 digits>.vtu" or "contacts_<12 digits>.vtu", the
// .pvtu of a frame in pieces (".pvtu") or one of its pieces ("_r<rank>.vtu") (the directory
// part ignored), or nullopt for any other name.
std::optional<long long> frame_step(const std::string& path) {
  const std::string name = fs::path(path).filename().string();
  for (const std::string prefix : {"bodies_", "contacts_"}) {
    if (name.size() < prefix.size() + 12 + 4 || name.compare(0, prefix.size(), prefix) != 0)
      continue;
    const std::string tail = name.substr(prefix.size() + 12);
    const bool piece = tail.size() > 6 && tail.compare(0, 2, "_r") == 0 &&
                       tail.compare(tail.size() - 4, 4, ".vtu") == 0 &&
                       std::all_of(tail.begin() + 2, tail.end() - 4,
                                   [](char c) { return c >= '0' && c <= '9'; });
    if (tail != ".vtu" && tail != ".pvtu" && !piece) continue;
    long long step = 0;
    for (size_t i = prefix.size(); i < prefix.size() + 12; ++i) {
      if (name[i] < '0' || name[i] > '9') return std::nullopt;
      step = 10 * step + (name[i] - '0');
    }
    return step;
  }
  return std::nullopt;
}

// What tem.pvd ends with, after its last DataSet line.
constexpr std::string_view kCollectionTail = "</Collection>\n</VTKFile>\n";

// The two DataSet lines of a frame.
std::string dataset_lines(long long step, const std::string& time, int pieces) {
  const std::string start = "<DataSet timestep=\"" + time + "\" group=\"\" part=\"";
  return start + "0\" file=\"" + ParaviewOutput::bodies_file(step, pieces) + "\"/>\n" +
         start + "1\" file=\"" + ParaviewOutput::contacts_file(step, pieces) + "\"/>\n";
}

// The value of attribute `name` in one XML tag, or nullopt.
std::optional<std::string> attribute(const std::string& tag, const std::string& name) {
  const std::string key = " " + name + "=\"";
  const size_t start = tag.find(key);
  if (start == std::string::npos) return std::nullopt;
  const size_t end = tag.find('"', start + key.size());
  if (end == std::string::npos) return std::nullopt;
  return tag.substr(start + key.size(), end - start - key.size());
}

}  // namespace

std::string ParaviewOutput::bodies_file(long long step, int pieces) {
  char name[64];
  std::snprintf(name, sizeof name, "paraview/bodies_%012lld.%s", step, pieces > 0 ? "pvtu" : "vtu");
  return name;
}

std::string ParaviewOutput::contacts_file(long long step, int pieces) {
  char name[64];
  std::snprintf(name, sizeof name, "paraview/contacts_%012lld.%s", step,
                pieces > 0 ? "pvtu" : "vtu");
  return name;
}

std::string ParaviewOutput::bodies_piece(long long step, int rank) {
  char name[80];
  std::snprintf(name, sizeof name, "paraview/bodies_%012lld_r%d.vtu", step, rank);
  return name;
}

std::string ParaviewOutput::contacts_piece(long long step, int rank) {
  char name[80];
  std::snprintf(name, sizeof name, "paraview/contacts_%012lld_r%d.vtu", step, rank);
  return name;
}

void ParaviewOutput::write_piece(const std::string& directory, const Model& model,
                                 const State& state, const std::vector<char>& owned,
                                 const std::vector<ContactPatch>& patches,
                                 const std::vector<PatchForce>& forces, int rank) {
  write_text_file(directory + "/" + bodies_piece(state.step, rank),
                  bodies_vtu(model, state, &owned));
  write_text_file(directory + "/" + contacts_piece(state.step, rank),
                  contacts_vtu(state.time, patches, forces));
}

ParaviewOutput::ParaviewOutput(const std::string& directory, const Model& /*model*/,
                               std::optional<long long> resume_step)
    : directory_(directory) {
  const std::string frames_dir = directory + "/paraview";
  std::error_code error;
  fs::create_directories(frames_dir, error);
  if (error) throw std::runtime_error(frames_dir + ": cannot be created: " + error.message());

  // Frames of the existing collection up to the resume step, in the order it lists them (this
  // reads tem.pvd as write_collection() writes it: one DataSet tag per line).
  const long long keep_through = resume_step.value_or(-1);
  if (resume_step) {
    std::ifstream pvd(directory + "/tem.pvd");
    std::string line;
    while (std::getline(pvd, line)) {
      if (line.find("<DataSet") == std::string::npos) continue;
      const auto time = attribute(line, "timestep");
      const auto file = attribute(line, "file");
      const auto step = file ? frame_step(*file) : std::nullopt;
      if (!time || !step || *step > keep_through) continue;
      // A frame in pieces: as many as its .pvtu lists.
      int pieces = 0;
      if (file->size() > 5 && file->compare(file->size() - 5, 5, ".pvtu") == 0) {
        std::ifstream pvtu(directory + "/" + *file);
        std::string tag;
        while (std::getline(pvtu, tag)) pieces += tag.find("<Piece ") != std::string::npos;
        pieces = std::max(pieces, 1);
      }
      if (frames_.empty() || frames_.back().step != *step)
        frames_.push_back({*step, *time, pieces});
    }
  }

  // Frame files past the kept frames belong to a run that is being replaced.
  for (const fs::directory_entry& entry : fs::directory_iterator(frames_dir, error)) {
    const auto step = frame_step(entry.path().string());
    if (step && *step > keep_through) fs::remove(entry.path(), error);
  }
  write_collection();
}

std::vector<std::string> ParaviewOutput::remove_collection(const std::string& directory) {
  std::vector<std::string> removed;
  std::error_code error;
  const std::string pvd = directory + "/tem.pvd";
  {
    std::ifstream file(pvd);
    std::string first, second;
    std::getline(file, first);
    std::getline(file, second);
    if (first == "<?xml version=\"1.0\"?>" &&
        second.rfind("<VTKFile type=\"Collection\"", 0) == 0) {
      file.close();
      if (fs::remove(pvd, error)) removed.push_back("tem.pvd");
    }
  }
  const std::string frames_dir = directory + "/paraview";
  if (!fs::is_directory(frames_dir, error)) return removed;
  long long frames = 0;
  for (const fs::directory_entry& entry : fs::directory_iterator(frames_dir, error))
    if (frame_step(entry.path().string()) && fs::remove(entry.path(), error)) ++frames;
  if (frames > 0) removed.push_back("paraview/ (" + std::to_string(frames) + " frame files)");
  if (fs::is_empty(frames_dir, error)) fs::remove(frames_dir, error);
  return removed;
}

void ParaviewOutput::write(const Model& model, const State& state, const Workspace& workspace) {
  const bool replaces = !frames_.empty() && frames_.back().step >= state.step;
  while (!frames_.empty() && frames_.back().step >= state.step) frames_.pop_back();
  if (pieces_ > 0) {
    // The ranks wrote their pieces; the frame is the .pvtu over them (names relative to it).
    std::vector<std::string> bodies, contacts;
    for (int r = 0; r < pieces_; ++r) {
      bodies.push_back(fs::path(bodies_piece(state.step, r)).filename().string());
      contacts.push_back(fs::path(contacts_piece(state.step, r)).filename().string());
    }
    write_text_file(directory_ + "/" + bodies_file(state.step, pieces_), bodies_pvtu(bodies));
    write_text_file(directory_ + "/" + contacts_file(state.step, pieces_),
                    contacts_pvtu(contacts));
  } else {
    write_text_file(directory_ + "/" + bodies_file(state.step), bodies_vtu(model, state));
    write_text_file(directory_ + "/" + contacts_file(state.step),
                    contacts_vtu(state.time, workspace.patches, workspace.forces.patch_forces));
  }
  std::string time;
  append_number(time, state.time);
  frames_.push_back({state.step, time, pieces_});
  if (replaces)
    write_collection();
  else
    append_to_collection();
}

void ParaviewOutput::write_collection() {
  std::string text =
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      "<Collection>\n";
  for (const Frame& frame : frames_) text += dataset_lines(frame.step, frame.time, frame.pieces);
  tail_offset_ = static_cast<long long>(text.size());
  text += kCollectionTail;

  const std::string path = directory_ + "/tem.pvd", temporary = path + ".tmp";
  write_text_file(temporary, text);
  std::error_code error;
  fs::rename(temporary, path, error);
  if (error) throw std::runtime_error(path + ": cannot be written: " + error.message());
}

void ParaviewOutput::append_to_collection() {
  const Frame& frame = frames_.back();
  const std::string lines = dataset_lines(frame.step, frame.time, frame.pieces);
  const std::string text = lines + std::string(kCollectionTail);
  const std::string path = directory_ + "/tem.pvd";
  // in | out: the file is opened as it is, not emptied.
  std::fstream file(path, std::ios::in | std::ios::out | std::ios::binary);
  if (file) {
    file.seekp(tail_offset_);
    file.write(text.data(), static_cast<std::streamsize>(text.size()));
    file.flush();
  }
  file.close();
  if (!file) throw std::runtime_error(path + ": cannot be written");
  tail_offset_ += static_cast<long long>(lines.size());
}

}  // namespace tem
