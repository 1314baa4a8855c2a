// `tem check`: validates a scene as fully as a run would (reading, then building every block)
// and prints every problem, or a one-line summary of what the scene holds.
#include <cmath>
#include <cstdio>
#include <string>

#include "commands.hpp"
#include "tem/scene_report.hpp"

namespace tem::cli {
namespace {

std::string plural(std::size_t n, const char* one, const char* many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

int problems_failed(const std::string& scene_file, std::size_t problems) {
  std::fprintf(stderr, "%s: %s\n", scene_file.c_str(),
               plural(problems, "problem", "problems").c_str());
  return kExitBadInput;
}

}  // namespace

int check_command(const std::string& scene_file) {
  SceneReport scene;
  try {
    scene = report_scene(scene_file);
  } catch (const std::exception& e) {
    const std::string message = load_failure(scene_file, e);  // one problem per line
    std::fprintf(stderr, "%s\n", message.c_str());
    std::size_t lines = 1;
    for (char c : message) lines += c == '\n';
    return problems_failed(scene_file, lines);
  }
  for (const std::string& warning : scene.warnings)
    std::fprintf(stderr, "%s: warning: %s\n", scene_file.c_str(), warning.c_str());
  const double steps = std::round(scene.duration / scene.time_step);
  const std::string inlets =
      scene.inlets == 0 ? ""
                        : ", " + plural(static_cast<std::size_t>(scene.inlet_copies), "body", "bodies") +
                              " to come from " +
                              plural(static_cast<std::size_t>(scene.inlets), "inlet", "inlets");
  std::printf("%s: ok (%s%s, %s, %s; %g s in %.0f steps of %g s)\n", scene_file.c_str(),
              plural(scene.bodies.size(), "body", "bodies").c_str(), inlets.c_str(),
              plural(static_cast<std::size_t>(scene.blocks), "block", "blocks").c_str(),
              plural(static_cast<std::size_t>(scene.walls), "wall", "walls").c_str(), scene.duration,
              steps, scene.time_step);
  return kExitOk;
}

}  // namespace tem::cli
