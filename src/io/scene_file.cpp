// Reading a scene from its file: the text (scene_reader.cpp parses it), then the mesh files its
// mesh shapes name. Kept apart from the parser so that the parser's fuzz target touches no file.
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "io/json_reader.hpp"
#include "io/scene_reader.hpp"
#include "mesh/mesh_body.hpp"

namespace tem {
namespace {

using json::child;

// Every mesh shape of the scene (bodies, fill and inlet templates, parts of compounds), with its file
// resolved against the scene file's directory, read, checked and cut (mesh_body.hpp).
void load_mesh_shape(ShapeDef& shape, const std::filesystem::path& base,
                     std::vector<SceneProblem>& problems) {
  for (ShapeDef& part : shape.parts) load_mesh_shape(part, base, problems);
  if (shape.type != ShapeType::mesh) return;
  const std::filesystem::path file(shape.file);
  std::error_code ec;
  const std::filesystem::path resolved =
      std::filesystem::absolute(file.is_absolute() ? file : base / file, ec).lexically_normal();
  shape.file_path = ec ? (base / file).string() : resolved.string();
  try {
    shape.mesh = load_mesh_body(shape.file_path, shape.scale, shape.cutting, shape.max_blocks);
  } catch (const std::exception& e) {
    problems.push_back({child(shape.path, "file"), e.what()});
  }
}


}  // namespace

void load_scene_meshes(SceneReadResult& result) {
  if (!result.ok()) return;
  SceneDef& scene = result.scene;
  const std::filesystem::path base = std::filesystem::path(scene.source).parent_path();
  for (BodyDef& body : scene.bodies) load_mesh_shape(body.shape, base, result.problems);
  for (FillDef& fill : scene.fill) load_mesh_shape(fill.body.shape, base, result.problems);
  for (InletDef& inlet : scene.inlets) load_mesh_shape(inlet.body.shape, base, result.problems);
}

SceneReadResult read_scene_file(const std::string& filename) {
  std::error_code ec;
  const std::filesystem::path path(filename);
  std::string failure;
  if (!std::filesystem::exists(path, ec)) {
    failure = "no such file";
  } else if (std::filesystem::is_directory(path, ec)) {
    failure = "is a directory, not a scene file";
  }
  std::string text;
  if (failure.empty()) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream buffer;
    if (in) buffer << in.rdbuf();
    if (!in || in.bad()) {
      failure = std::string("cannot be read (") + std::strerror(errno) + ")";
    } else {
      text = std::move(buffer).str();
    }
  }
  if (!failure.empty()) {
    SceneReadResult result;
    result.scene.source = filename;
    result.problems.push_back({"", failure});
    return result;
  }
  SceneReadResult result = read_scene_text(text, filename);
  load_scene_meshes(result);
  return result;
}

}  // namespace tem
