// The commands of the `tem` program, one file each; main.cpp only parses the command line.
// Every command returns the process's exit status and prints its own messages: results to
// stdout, problems and warnings to stderr, each naming the scene file. The commands are clients
// of TEM's public API (include/tem/), like any other program.
#pragma once

#include <exception>
#include <string>

#include "tem/types.hpp"

namespace tem::cli {

// Exit statuses shared by all commands.
inline constexpr int kExitOk = 0;
inline constexpr int kExitBadInput = 1;  // the scene has problems, or the file is missing
inline constexpr int kExitUsage = 2;     // the command line itself is wrong
inline constexpr int kExitFailed = 3;    // a run failed: its output could not be written, or
                                         // its state stopped being finite
inline constexpr int kExitInterrupted = 130;  // `run` stopped by Ctrl-C or SIGTERM, after
                                              // writing a checkpoint (128 + SIGINT, the shell's)

// A scene that could not be loaded, as the commands print it: SceneLoadError's lines (one
// problem each, naming the file) as they are, anything else after the file's name.
std::string load_failure(const std::string& scene_file, const std::exception& e);

// `tem info SCENE [--json]`: each body's volume, mass, centre of mass and inertia.
int info_command(const std::string& scene_file, bool json);

// `tem check SCENE`: every problem of the scene, or a one-line summary when there is none.
int check_command(const std::string& scene_file);

// `tem contacts SCENE [--out FILE]`: the contact patches at the initial state as contacts.csv
// (to stdout, or to FILE).
int contacts_command(const std::string& scene_file, const std::string& out_file);

// `tem mesh FILE [--blocks exact|approximate] [--max-blocks N] [--scale S] [--out BLOCKS.vtu]
// [--json]`: reads, checks and cuts a mesh; prints its figures and the blocks'.
int mesh_command(const std::string& mesh_file, const std::string& cutting, int max_blocks,
                 Real scale, const std::string& out_file, bool json);

// `tem run SCENE --out DIR [--contacts] [--resume] [--hash]`: simulates and writes bodies.csv,
// energy.csv, scene.json (and contacts.csv, checkpoint.bin) into DIR; with --resume, continues
// from DIR/checkpoint.bin; with --hash, prints as its last line `hash: <hex>` of the final
// state's exact bits. `threads`: 0 one per core, < 0 one unless OMP_NUM_THREADS says otherwise.
int run_command(const std::string& scene_file, const std::string& out_dir, bool contacts,
                bool resume, bool hash, int threads = -1);
#ifdef TEM_MPI
// `tem run` started by mpirun: the same files, the run shared among the ranks.
int run_distributed_command(const std::string& scene_file, const std::string& out_dir,
                            bool contacts, bool resume, bool hash, int threads = -1);
#endif

}  // namespace tem::cli
