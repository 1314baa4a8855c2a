#include <string>

#include "commands.hpp"
#include "tem/simulation.hpp"

namespace tem::cli {

std::string load_failure(const std::string& scene_file, const std::exception& e) {
  if (dynamic_cast<const SceneLoadError*>(&e)) return e.what();  // its lines name the file
  return scene_file + ": " + e.what();
}

}  // namespace tem::cli
