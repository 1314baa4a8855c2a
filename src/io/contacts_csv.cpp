#include "io/contacts_csv.hpp"

#include <charconv>
#include <string>

namespace tem {
namespace {

// Shortest round-trip digits, independent of the stream's locale and precision settings.
void put(std::string& row, Real value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value + 0.0);  // no "-0"
  row.push_back(',');
  row.append(buffer, result.ptr);
}

}  // namespace

void write_contact_rows(std::ostream& out, const Model& model, Real time,
                        const std::vector<ContactPatch>& patches,
                        const std::vector<PatchForce>& forces) {
  std::string row;
  for (size_t i = 0; i < patches.size(); ++i) {
    const ContactPatch& p = patches[i];
    const PatchForce f = forces.empty() ? PatchForce{} : forces[i];
    row.clear();
    char buffer[32];
    row.append(buffer, std::to_chars(buffer, buffer + sizeof buffer, time).ptr);
    row += ',' + model.bodies[p.body_a].name + ',';
    row += p.body_b >= 0 ? model.bodies[p.body_b].name : std::string("wall");
    for (int k = 0; k < 3; ++k) put(row, p.point[k]);
    for (int k = 0; k < 3; ++k) put(row, p.normal[k]);
    put(row, p.depth);
    put(row, f.normal);
    put(row, f.tangential);
    row += '\n';
    out << row;
  }
}

}  // namespace tem
