// SceneDef -> JSON, every default written out: the `scene.json` of a run's output, which says
// exactly what was simulated. Reading what this writes gives back the same SceneDef, bit for
// bit, with one exception: a rotation that no short decimal Euler triple reproduces exactly is
// written as a quaternion and comes back equal to rounding (about 1e-16).
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "tem/scene_def.hpp"

namespace tem {

// Keys in the order of the scene format's documentation, so the file reads like an example.
nlohmann::ordered_json scene_to_json(const SceneDef& scene);

// Indented JSON text ending in a newline. Numbers are written in the shortest form that reads
// back as the same double.
std::string write_scene_text(const SceneDef& scene);

// Writes write_scene_text() to `filename`. Returns false and sets *error on failure.
bool write_scene_file(const SceneDef& scene, const std::string& filename, std::string* error);

}  // namespace tem
