#include "api/scene_loading.hpp"

#include <sstream>

#include "contact/initial_overlap.hpp"
#include "forces/force_model.hpp"
#include "tem/simulation.hpp"

namespace tem {

Model build_model_or_throw(const SceneReadResult& read, const std::string& origin) {
  if (!read.ok()) {
    std::string message;
    for (const SceneProblem& p : read.problems) {
      if (!message.empty()) message += '\n';
      message += format_problem(origin, p);
    }
    throw SceneLoadError(message);
  }
  // Geometric problems (a flat point cloud, a non-convex block) show up only when the blocks
  // are built; the core names the shape's JSON path in them.
  try {
    return build_model(read.scene);
  } catch (const SceneError& e) {
    throw SceneLoadError(format_problem(origin, {e.path(), e.reason()}));
  }
}

Model load_model_or_throw(const std::string& scene_file) {
  return build_model_or_throw(read_scene_file(scene_file), scene_file);
}

std::vector<std::string> start_warnings(const Model& model, bool at_start) {
  std::vector<std::string> warnings = model.warnings;
  if (at_start)
    for (const InitialOverlap& o : deep_initial_overlaps(model))
      warnings.push_back(describe(model, o));
  force_model(model.scene.contact).add_warnings(model, warnings);
  return warnings;
}

}  // namespace tem
