// Scene text -> Model for the public API's loaders (tem::Simulation, tem::report_scene), with
// every problem reported the same way, and the warnings a scene's start earns.
#pragma once

#include <string>
#include <vector>

#include "io/scene_reader.hpp"
#include "world/model.hpp"

namespace tem {

// Builds the model of a scene read; throws SceneLoadError holding every problem, one per line
// ("ORIGIN: JSON.path: reason").
Model build_model_or_throw(const SceneReadResult& read, const std::string& origin);
Model load_model_or_throw(const std::string& scene_file);

// The model's warnings (accepted defects), then, with `at_start`, the bodies that overlap
// deeply at the scene's start, then a penalty contact's time step above its stable limit.
std::vector<std::string> start_warnings(const Model& model, bool at_start);

}  // namespace tem
