// `tem contacts`: the contact patches of a scene at its initial state, as contacts.csv rows, so
// that a user can see what the detection finds (and fix a scene whose bodies start inside each
// other) before running anything.
#include <fstream>
#include <iostream>

#include "commands.hpp"
#include "contact/detect_contacts.hpp"
#include "io/contacts_csv.hpp"

namespace tem::cli {

int contacts_command(const std::string& scene_file, const std::string& out_file) {
  const std::optional<Model> model = load_model(scene_file);
  if (!model) return kExitBadInput;
  print_warnings(scene_file, *model);

  const State state = initial_state(*model);
  ContactWorkspace workspace;
  std::vector<ContactPatch> patches;
  detect_contacts(*model, state, patch_variant(model->scene), workspace, patches);

  std::ofstream file;
  if (!out_file.empty()) {
    file.open(out_file);
    if (!file) {
      std::cerr << out_file << ": cannot be written\n";
      return kExitBadInput;
    }
  }
  std::ostream& out = out_file.empty() ? std::cout : file;
  out << kContactsCsvHeader << "\n";
  write_contact_rows(out, *model, state.time, patches);
  out.flush();
  if (!out) {
    std::cerr << (out_file.empty() ? "stdout" : out_file) << ": write failed\n";
    return kExitBadInput;
  }
  if (!out_file.empty())
    std::cerr << scene_file << ": " << patches.size() << " contact patches written to "
              << out_file << "\n";
  return kExitOk;
}

}  // namespace tem::cli
