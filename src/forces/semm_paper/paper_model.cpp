#include "forces/semm_paper/paper_model.hpp"

#include <stdexcept>

#include "forces/semm_paper/semm_paper.hpp"
#include "forces/semm_step.hpp"

namespace tem {
namespace {

class PaperModel final : public ForceModel {
 public:
  void compute(const ForceStep& step, ContactForces& f) const override {
    if (!begin_semm_step(step, f)) return;
    f.solver = solve_semm_paper(f.points, f.responses, f.centres, f.impulses);
    semm_impulses_to_forces(step.dt, false, f);
  }
  // The paper's solve starts from nothing: no memory.
  void save_memory(const ContactForces&, std::vector<MemoryRecord>&) const override {}
  void load_memory(const std::vector<MemoryRecord>& records, ContactForces& f) const override {
    if (!records.empty())
      throw std::runtime_error("contact.model 'semm-paper' keeps no contact memory");
    f.points.clear();  // the last step's, numbered for the bodies there were
    f.impulses.clear();
  }
  bool solves_across_ranks() const override { return true; }
  std::string not_distributed_because() const override {
    return "over MPI ranks TEM runs the penalty model and SEMM with the rows solver; "
           "contact.model 'semm-paper' (the paper's direct solve) is not distributed: run this "
           "scene without mpirun (threads: --threads N)";
  }
};

}  // namespace

const ForceModel& semm_paper_model() {
  static const PaperModel model;
  return model;
}

}  // namespace tem
