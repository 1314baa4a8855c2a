#include "tem/scene_report.hpp"

#include <cmath>

#include "api/scene_loading.hpp"
#include "mesh/mesh_body.hpp"

namespace tem {
namespace {

// The definition each body came from: the scene's bodies first, then the copies of each fill.
const BodyDef& body_def(const Model& model, std::size_t i) {
  const SceneDef& scene = model.scene;
  if (i < scene.bodies.size()) return scene.bodies[i];
  i -= scene.bodies.size();
  for (const FillDef& fill : scene.fill) {
    if (i < static_cast<std::size_t>(fill.count)) return fill.body;
    i -= fill.count;
  }
  return scene.bodies.back();  // not reached: every body comes from a def
}

std::optional<MeshBodyCheck> mesh_check(const Model& model, std::size_t i) {
  const ShapeDef& shape = body_def(model, i).shape;
  if (shape.type != ShapeType::mesh || !shape.mesh) return std::nullopt;
  const Body& body = model.bodies[i];
  const MeshBody& mesh = *shape.mesh;
  const MassProperties& surface = mesh.surface;
  MeshBodyCheck c;
  c.file = mesh.file_path;
  c.exact = mesh.cutting == MeshCutting::exact;
  c.faces = mesh.check.faces;
  c.blocks = static_cast<int>(mesh.decomposition.blocks.size());
  c.mesh_volume = surface.volume;
  c.blocks_volume = mesh.decomposition.blocks_volume;
  c.volume_error = std::abs(body.volume - surface.volume) / surface.volume;
  // The body frame's origin is the mesh's; the centre of mass sits at -origin_offset in it.
  c.centre_error = (-body.origin_offset - surface.center).norm() / body_size(model, body);
  const Mat3 mesh_inertia = body.density * inertia_from_second_moment(surface.second_moment);
  c.inertia_error = (body.inertia.inertia - mesh_inertia).cwiseAbs().maxCoeff() /
                    mesh_inertia.cwiseAbs().maxCoeff();
  return c;
}

}  // namespace

SceneReport report_scene(const std::string& scene_file) {
  const Model model = load_model_or_throw(scene_file);
  const State state = initial_state(model);
  SceneReport report;
  report.warnings = start_warnings(model, /*at_start=*/true);
  for (std::size_t i = 0; i < model.bodies.size(); ++i) {
    const Body& body = model.bodies[i];
    const Mat3& g = state.bodies[i].g;
    // g A g^T is symmetric but for round-off; give the symmetric tensor it stands for.
    const Mat3 world = g * body.inertia.inertia * g.transpose();
    BodyReport b;
    b.name = body.name;
    b.fixed = body.fixed;
    b.blocks = static_cast<int>(body.blocks.size());
    for (const BlockInstance& instance : body.blocks) {
      const Block& block = model.blocks[instance.block];
      b.nodes += static_cast<int>(block.nodes().size());
      b.elements += static_cast<int>(block.elements().size());
    }
    b.volume = body.volume;
    b.mass = body.inertia.mass;
    b.center_of_mass = state.bodies[i].x;
    b.inertia = 0.5 * (world + world.transpose());
    b.mesh = mesh_check(model, i);
    report.bodies.push_back(std::move(b));
  }
  report.blocks = static_cast<int>(model.blocks.size());
  report.walls = static_cast<int>(model.walls.size());
  report.inlets = static_cast<int>(model.scene.inlets.size());
  for (const InletDef& inlet : model.scene.inlets) report.inlet_copies += inlet.count;
  report.duration = model.scene.duration;
  report.time_step = model.scene.time_step;
  return report;
}

}  // namespace tem
