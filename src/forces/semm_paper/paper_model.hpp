// The paper's SEMM (semm_paper.hpp) as a force model (force_model.hpp): contact.model
// "semm-paper".
#pragma once

#include "forces/force_model.hpp"

namespace tem {

const ForceModel& semm_paper_model();

}  // namespace tem
