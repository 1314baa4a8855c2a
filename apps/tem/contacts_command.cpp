// `tem contacts`: the contact patches of a scene at its initial state, as contacts.csv rows, so
// that a user can see what the detection finds (and fix a scene whose bodies start inside each
// other) before running anything.
#include <fstream>
#include <iostream>
#include <optional>

#include "commands.hpp"
#include "tem/simulation.hpp"

namespace tem::cli {

int contacts_command(const std::string& scene_file, const std::string& out_file) {
  std::optional<Simulation> sim;
  try {
    sim.emplace(Simulation::load(scene_file));
  } catch (const std::exception& e) {
    std::cerr << load_failure(scene_file, e) << "\n";
    return kExitBadInput;
  }
  for (const std::string& warning : sim->warnings())
    std::cerr << scene_file << ": warning: " << warning << "\n";

  std::ofstream file;
  if (!out_file.empty()) {
    file.open(out_file);
    if (!file) {
      std::cerr << out_file << ": cannot be written\n";
      return kExitBadInput;
    }
  }
  std::ostream& out = out_file.empty() ? std::cout : file;
  const std::size_t patches = sim->write_contacts_csv(out);
  out.flush();
  if (!out) {
    std::cerr << (out_file.empty() ? "stdout" : out_file) << ": write failed\n";
    return kExitBadInput;
  }
  if (!out_file.empty())
    std::cerr << scene_file << ": " << patches << " contact patches written to " << out_file
              << "\n";
  return kExitOk;
}

}  // namespace tem::cli
