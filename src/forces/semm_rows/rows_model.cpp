#include "forces/semm_rows/rows_model.hpp"

#include "forces/semm_step.hpp"

namespace tem {
namespace {

class RowsModel final : public DefaultSemmModel {
 public:
  void compute(const ForceStep& step, ContactForces& f) const override {
    if (!begin_semm_step(step, f)) return;
    const SolverSettings settings = begin_default_semm(step, f);
    normal_targets(f.points, f.approach, f.approach_linear, settings, f.targets, &f.friction);
    f.solver = solve_semm_rows(f.points, f.approach, f.targets, f.responses, f.centres, settings,
                               f.friction, f.impulses, f.rows);
    semm_impulses_to_forces(step.dt, true, f);
  }
};

}  // namespace

const ForceModel& semm_rows_model() {
  static const RowsModel model;
  return model;
}

}  // namespace tem
