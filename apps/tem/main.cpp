// The `tem` program: parses the command line (CLI11) and hands over to one command
// (commands.hpp). Nothing may escape main: a bug shows as a message and a non-zero status, not
// as an abort.
#include <CLI/CLI.hpp>
#include <exception>
#include <iostream>
#include <string>

#include "commands.hpp"

namespace {

int run(int argc, char** argv) {
  using namespace tem::cli;
  CLI::App app{"TEM: rigid bodies of arbitrary shape built from tetrahedral elements, in contact.",
               "tem"};
  app.set_version_flag("--version", std::string("tem ") + TEM_VERSION);
  app.require_subcommand(1);
  app.footer("Run 'tem COMMAND --help' for the options of one command.");

  std::string scene_file;
  bool json = false;
  CLI::App* info = app.add_subcommand(
      "info",
      "Print each body's volume, mass, centre of mass and inertia (world axes, initial pose).");
  info->add_option("scene", scene_file, "Scene file (JSON)")->required();
  info->add_flag("--json", json, "Print one JSON object with full-precision numbers");

  CLI::App* check =
      app.add_subcommand("check", "Validate a scene file; print every problem found.");
  check->add_option("scene", scene_file, "Scene file (JSON)")->required();

  std::string out_dir;
  bool with_contacts = false;
  CLI::App* run = app.add_subcommand("run", "Simulate a scene; write the results into a directory.");
  run->add_option("scene", scene_file, "Scene file (JSON)")->required();
  run->add_option("--out", out_dir, "Directory for bodies.csv, energy.csv, scene.json")->required();
  run->add_flag("--contacts", with_contacts, "Also write contacts.csv (every patch at every output)");
  bool with_resume = false;
  run->add_flag("--resume", with_resume,
                "Continue the run in --out from its last checkpoint (bit-identical results)");
  int threads = -1;
  run->add_option("--threads", threads,
                  "Threads that share each step (contact detection, the contact solve, "
                  "integration; 0: one per core; default 1, or OMP_NUM_THREADS); results are "
                  "bit-identical with any number")
      ->check(CLI::Validator(
          [](const std::string& text) -> std::string {
            // CLI11's own range check prints its bounds as 300-digit numbers.
            int n = -1;
            try {
              std::size_t used = 0;
              n = std::stoi(text, &used);
              if (used != text.size()) n = -1;
            } catch (const std::exception&) {
              n = -1;
            }
            if (n < 0)
              return "must be 0 (one thread per core) or a number of threads, got " + text;
            return "";
          },
          "INT >= 0"));
  bool with_hash = false;
  run->add_flag("--hash", with_hash, "Print 'hash: <hex>' of the final state as the last line");

  std::string out_file;
  CLI::App* contacts = app.add_subcommand(
      "contacts", "Print the contact patches of the initial state as contacts.csv rows.");
  contacts->add_option("scene", scene_file, "Scene file (JSON)")->required();
  contacts->add_option("--out", out_file, "Write the rows to this file instead of stdout");

  std::string mesh_file, cutting = "approximate", blocks_file;
  int max_blocks = 32;
  double scale = 1.0;
  CLI::App* mesh = app.add_subcommand(
      "mesh", "Read, check and cut a mesh file (OBJ, STL, PLY, OFF) into convex blocks.");
  mesh->add_option("file", mesh_file, "Mesh file")->required();
  mesh->add_option("--blocks", cutting,
                   "exact: blocks whose union is the mesh; approximate: few convex hulls "
                   "(default)")
      ->check(CLI::IsMember({"exact", "approximate"}));
  mesh->add_option("--max-blocks", max_blocks, "Most blocks of an approximate cut (default 32)")
      ->check(CLI::Range(1, 10000));
  mesh->add_option("--scale", scale, "Multiply every vertex by this (default 1)")
      ->check(CLI::PositiveNumber);
  mesh->add_option("--out", blocks_file, "Write the blocks for ParaView (.vtu)");
  mesh->add_flag("--json", json, "Print one JSON object");

  CLI::App* help = app.add_subcommand("help", "Print this help.");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version arrive here too, with exit code 0.
    const int code = app.exit(e);
    return code == 0 ? kExitOk : kExitUsage;
  }
  if (*help) {
    // The formatter directly: app.help() would describe the selected subcommand, `help` itself.
    std::cout << app.get_formatter()->make_help(&app, "tem", CLI::AppFormatMode::Normal);
    return kExitOk;
  }
  if (*info) return info_command(scene_file, json);
  if (*check) return check_command(scene_file);
  if (*contacts) return contacts_command(scene_file, out_file);
  if (*mesh) return mesh_command(mesh_file, cutting, max_blocks, scale, blocks_file, json);
  if (*run) return run_command(scene_file, out_dir, with_contacts, with_resume, with_hash, threads);
  return kExitUsage;  // unreachable: require_subcommand(1)
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "tem: internal error: " << e.what() << "\n";
  } catch (...) {
    std::cerr << "tem: internal error (unknown exception)\n";
  }
  return tem::cli::kExitBadInput;
}
