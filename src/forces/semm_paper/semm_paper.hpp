// The paper's SEMM (contact.model "semm-paper", method.md "Paper mode"): K S = D (eqs. 30-31,
// 36-39), normal impulses only, one point per patch, impulses of either sign, one dense
// symmetric solve. It keeps no memory from step to step.
#pragma once

#include <vector>

#include "forces/semm.hpp"

namespace tem {

// The paper's unconstrained normal-only SEMM: K S = D, solved directly.
SolverReport solve_semm_paper(const std::vector<ContactPoint>& points,
                              const std::vector<BodyResponse>& bodies,
                              const std::vector<Vec3>& centres,
                              std::vector<PointImpulse>& impulses);

}  // namespace tem
