// Scene file -> Model for the commands, with every problem reported the same way.
#include <iostream>
#include <string>

#include "commands.hpp"
#include "io/scene_reader.hpp"

namespace tem::cli {

std::optional<Model> load_model(const std::string& scene_file, int* problem_count) {
  if (problem_count) *problem_count = 0;
  const SceneReadResult read = read_scene_file(scene_file);
  for (const SceneProblem& problem : read.problems) {
    std::cerr << format_problem(scene_file, problem) << "\n";
  }
  if (!read.ok()) {
    if (problem_count) *problem_count = static_cast<int>(read.problems.size());
    return std::nullopt;
  }
  // Geometric problems (a flat point cloud, a non-convex block) show up only when the blocks
  // are built; the core names the shape's JSON path in them.
  try {
    return build_model(read.scene);
  } catch (const SceneError& e) {
    std::cerr << format_problem(scene_file, {e.path(), e.reason()}) << "\n";
  } catch (const std::exception& e) {
    std::cerr << scene_file << ": " << e.what() << "\n";
  }
  if (problem_count) *problem_count = 1;
  return std::nullopt;
}

void print_warnings(const std::string& scene_file, const Model& model) {
  for (const std::string& warning : model.warnings) {
    std::cerr << scene_file << ": warning: " << warning << "\n";
  }
}

}  // namespace tem::cli
