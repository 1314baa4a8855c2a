#include "io/contacts_csv.hpp"

#include <string>

#include "io/csv_number.hpp"

namespace tem {

void write_contact_rows(std::ostream& out, const Model& model, Real time,
                        const std::vector<ContactPatch>& patches,
                        const std::vector<PatchForce>& forces) {
  std::string row;
  for (size_t i = 0; i < patches.size(); ++i) {
    const ContactPatch& p = patches[i];
    const PatchForce f = forces.empty() ? PatchForce{} : forces[i];
    row.clear();
    append_number(row, time);
    row += ',' + model.bodies[p.body_a].name + ',';
    row += p.body_b >= 0 ? model.bodies[p.body_b].name : std::string("wall");
    for (int k = 0; k < 3; ++k) append_field(row, p.point[k]);
    for (int k = 0; k < 3; ++k) append_field(row, p.normal[k]);
    append_field(row, p.depth);
    append_field(row, f.normal);
    append_field(row, f.tangential);
    row += '\n';
    out << row;
  }
}

}  // namespace tem
