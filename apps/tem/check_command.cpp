// `tem check`: validates a scene as fully as a run would (reading, then building every block)
// and prints every problem, or a one-line summary of what the scene holds.
#include <cmath>
#include <cstdio>
#include <string>

#include "commands.hpp"
#include "contact/initial_overlap.hpp"

namespace tem::cli {
namespace {

std::string plural(std::size_t n, const char* one, const char* many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

}  // namespace

int check_command(const std::string& scene_file) {
  int problems = 0;
  const std::optional<Model> model = load_model(scene_file, &problems);
  if (!model) {
    std::fprintf(stderr, "%s: %s\n", scene_file.c_str(),
                 plural(problems, "problem", "problems").c_str());
    return kExitBadInput;
  }
  print_warnings(scene_file, *model);
  for (const InitialOverlap& o : deep_initial_overlaps(*model))
    std::fprintf(stderr, "%s: warning: %s\n", scene_file.c_str(), describe(*model, o).c_str());
  const SceneDef& scene = model->scene;
  const double steps = std::round(scene.duration / scene.time_step);
  long long inlet_copies = 0;
  for (const InletDef& inlet : scene.inlets) inlet_copies += inlet.count;
  const std::string inlets =
      scene.inlets.empty() ? ""
                           : ", " + plural(static_cast<std::size_t>(inlet_copies), "body", "bodies") +
                                 " to come from " +
                                 plural(scene.inlets.size(), "inlet", "inlets");
  std::printf("%s: ok (%s%s, %s, %s; %g s in %.0f steps of %g s)\n", scene_file.c_str(),
              plural(model->bodies.size(), "body", "bodies").c_str(), inlets.c_str(),
              plural(model->blocks.size(), "block", "blocks").c_str(),
              plural(model->walls.size(), "wall", "walls").c_str(), scene.duration, steps,
              scene.time_step);
  return kExitOk;
}

}  // namespace tem::cli
