#include "forces/penalty/penalty_model.hpp"

#include <sstream>
#include <stdexcept>

#include "forces/contact_forces.hpp"

namespace tem {
namespace {

// A spring's record: where it is and how far it is stretched (its keys are its sides).
constexpr size_t kSpringNumbers = 6;

class PenaltyModel final : public ForceModel {
 public:
  void compute(const ForceStep& step, ContactForces& f) const override {
    const SceneDef& scene = step.model.scene;
    f.points.clear();
    f.impulses.clear();
    f.solver.sweeps = 0;
    for (size_t i = 0; i < step.patches.size(); ++i)
      patch_points(step.patches[i], static_cast<int>(i), scene.contact.points == PatchPoints::one,
                   f.points);
    penalty_forces(step.model, step.state, step.patches, f.points, f.centres, f.springs, f.force,
                   f.torque, f.normal_magnitude, f.tangential_magnitude);
    for (size_t k = 0; k < step.patches.size(); ++k)
      f.patch_forces[k] = {f.normal_magnitude[k], f.tangential_magnitude[k]};
  }

  void save_memory(const ContactForces& f, std::vector<MemoryRecord>& out) const override {
    for (const PenaltySpring& s : f.springs) {
      MemoryRecord record{s.body_a, s.body_b, s.wall, {}};
      RecordWriter w(record.values);
      w.put(s.point);
      w.put(s.stretch);
      out.push_back(std::move(record));
    }
  }

  void load_memory(const std::vector<MemoryRecord>& records, ContactForces& f) const override {
    f.points.clear();  // the last step's, numbered for the bodies there were
    f.springs.clear();
    for (const MemoryRecord& record : records) {
      if (record.values.size() != kSpringNumbers)
        throw std::runtime_error("a penalty spring's memory record is not of its size");
      RecordReader r(record.values);
      PenaltySpring s;
      s.body_a = record.body_a;
      s.body_b = record.body_b;
      s.wall = record.wall;
      s.point = r.vec3();
      s.stretch = r.vec3();
      f.springs.push_back(s);
    }
  }

  bool solves_across_ranks() const override { return false; }

  // The penalty model is explicit: above a tenth of the contact's period it goes unstable.
  void add_warnings(const Model& model, std::vector<std::string>& warnings) const override {
    const Real limit = penalty_time_step_limit(model);
    if (model.scene.time_step <= limit) return;
    std::ostringstream w;
    w << "time_step " << model.scene.time_step
      << " is above the penalty contact's stable limit " << limit
      << " (a tenth of the contact oscillation period 2 pi sqrt(m/k) of the lightest body); "
         "bodies may bounce off or pass through each other";
    warnings.push_back(w.str());
  }
};

}  // namespace

const ForceModel& penalty_model() {
  static const PenaltyModel model;
  return model;
}

}  // namespace tem
