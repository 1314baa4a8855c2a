// Default SEMM by scalar rows (semm_rows.hpp) as a force model (force_model.hpp):
// contact.model "semm" with contact.solver "rows", the default.
#pragma once

#include "forces/force_model.hpp"

namespace tem {

const ForceModel& semm_rows_model();

}  // namespace tem
