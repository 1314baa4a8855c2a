// Checkpoints of a run (`tem run`, interface.md): everything needed to continue a run so that
// the continuation is bit-identical to a run that was never stopped.
//
// What that takes besides the State: the contact solver's memory (the last step's contact
// points, their impulses and the patches' friction, which warm-start the next step, and the
// penalty model's tangential springs), and the pair cache's features (pair_cache.hpp). A warm
// start changes where Gauss-Seidel stops and a cached feature which search answers a pair, so
// a resumed run without them would differ in the last bits. Everything else a step keeps
// between steps is scratch, rebuilt from the State.
//
// The file also records how long each output file was when the checkpoint was taken: the rows
// written after it are cut off on resuming and written again by the continued run, so the files
// of a resumed run are byte for byte those of an uninterrupted one.
//
// Format: binary, in this machine's byte order and double layout (not meant to move between
// architectures): a magic string and version, the fingerprint of the scene, the output sizes,
// the State, the memory, and an FNV-1a checksum of all of it. Written to a temporary file and
// renamed over the old one, so a run killed while writing leaves the previous checkpoint whole.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "contact/pair_cache.hpp"
#include "forces/contact_forces.hpp"
#include "world/model.hpp"

namespace tem {

// The sizes in bytes of the run's output files when the checkpoint was taken (-1: the file is
// not written by this run).
struct OutputSizes {
  std::int64_t bodies = 0, energy = 0, contacts = -1;
  std::int64_t removed = -1, sensors = -1;  // removed.csv, sensors.csv (processes)
};

// A file the scene reads (a mesh shape's file) and the hash of its contents when it was read.
struct ReadFile {
  std::string path;
  std::uint64_t content_hash = 0;
};

struct Checkpoint {
  std::uint64_t scene_fingerprint = 0;
  // The files the scene read (version 6 on; empty before): the scene's text names a file, not
  // what it holds, so a file changed between a run and its resume is caught here.
  std::vector<ReadFile> files;
  OutputSizes sizes;
  State state;
  std::uint32_t version = 0;  // of the file it was read from; 0: made here
  // The contact memory the next step starts from: the force model's records (force_model.hpp;
  // version 7 on).
  std::vector<MemoryRecord> memory;
  // Before version 7, the memory as ContactForces held it (points, impulses, friction, springs
  // of the last step), put back as it was.
  std::vector<ContactPoint> points;
  std::vector<PointImpulse> impulses;
  std::vector<PatchFriction> friction;
  std::vector<PenaltySpring> springs;
  std::vector<CachedFeatures> features;  // the pair cache (version 4 on; empty before)
};

// The fingerprint of a scene: a hash of the scene as `scene.json` states it (every default
// filled in), but for its duration and checkpoint interval. A checkpoint resumes only the scene
// it was taken of, possibly with a longer duration.
std::uint64_t scene_fingerprint(const SceneDef& scene);

// The files `scene` read, each once, in the order the scene names them (bodies, fill and inlet
// templates, parts of compounds).
std::vector<ReadFile> scene_files(const SceneDef& scene);

// Throws std::runtime_error naming the first file of `taken` whose contents now differ from
// `now`'s, or that the scene no longer reads. `checkpoint` names the checkpoint in the message.
void require_same_files(const std::vector<ReadFile>& taken, const std::vector<ReadFile>& now,
                        const std::string& checkpoint);

// The checkpoint of `state`, whose next step will start from the memory in `forces` and the
// pair cache `features`.
Checkpoint make_checkpoint(const SceneDef& scene, const State& state, const ContactForces& forces,
                           const std::vector<CachedFeatures>& features, const OutputSizes& sizes);

// Puts a checkpoint's memory back into a fresh ContactForces (by the force model of `contact`,
// which throws std::runtime_error for records not its own) and pair cache.
void restore_memory(const Checkpoint& checkpoint, const ContactDef& contact, ContactForces& forces,
                    std::vector<CachedFeatures>& features);

// Writes atomically (temporary file, then rename). Throws std::runtime_error naming the file.
void write_checkpoint(const std::string& path, const Checkpoint& checkpoint);

// Whether `path` is a file that starts as a TEM checkpoint does (its magic string).
bool is_checkpoint_file(const std::string& path);

// Reads and verifies a checkpoint. Throws std::runtime_error that says what is wrong (missing,
// truncated, corrupted, another version).
Checkpoint read_checkpoint(const std::string& path);

}  // namespace tem
