// `tem info`: the mass properties of each body at its initial pose, for a person (aligned
// text) or for a script (--json: one object on stdout, numbers that read back exactly).
#include <Eigen/Eigenvalues>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "commands.hpp"
#include "mesh/mesh_body.hpp"

namespace tem::cli {
namespace {

// A body made from one mesh shape, checked against the mesh's own surface integrals: the
// body's volume, centre and inertia beside the mesh's. Exact cutting: the body's come from its
// blocks, equal to the mesh's to rounding. Approximate: the body's are the mesh's own (the
// blocks cover more than the mesh and only shape the contacts), so the check shows that and
// the blocks' over-coverage is given beside it.
struct MeshCrossCheck {
  const MeshBody* mesh = nullptr;
  Real volume_error = 0;   // |V_blocks - V_mesh| / V_mesh
  Real centre_error = 0;   // |c_blocks - c_mesh| / the body's size
  Real inertia_error = 0;  // largest entry of |J_blocks - J_mesh| / largest entry of J_mesh
};

struct BodySummary {
  const Body* body;
  Vec3 center_of_mass;  // world
  Mat3 inertia;         // about the centre of mass, world axes: g A g^T
  int nodes = 0;
  int elements = 0;
  std::optional<MeshCrossCheck> mesh;
};

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

std::optional<MeshCrossCheck> mesh_cross_check(const Model& model, std::size_t i) {
  const ShapeDef& shape = body_def(model, i).shape;
  if (shape.type != ShapeType::mesh || !shape.mesh) return std::nullopt;
  const Body& body = model.bodies[i];
  const MassProperties& surface = shape.mesh->surface;
  MeshCrossCheck c;
  c.mesh = shape.mesh.get();
  c.volume_error = std::abs(body.volume - surface.volume) / surface.volume;
  // The body frame's origin is the mesh's; the centre of mass sits at -origin_offset in it.
  c.centre_error = (-body.origin_offset - surface.center).norm() / body_size(model, body);
  const Mat3 mesh_inertia = body.density * inertia_from_second_moment(surface.second_moment);
  c.inertia_error = (body.inertia.inertia - mesh_inertia).cwiseAbs().maxCoeff() /
                    mesh_inertia.cwiseAbs().maxCoeff();
  return c;
}

std::vector<BodySummary> summarise(const Model& model) {
  const State state = initial_state(model);
  std::vector<BodySummary> out;
  for (std::size_t i = 0; i < model.bodies.size(); ++i) {
    const Body& body = model.bodies[i];
    const Mat3& g = state.bodies[i].g;
    // g A g^T is symmetric but for round-off; show the symmetric tensor it stands for.
    const Mat3 world = g * body.inertia.inertia * g.transpose();
    BodySummary s{&body, state.bodies[i].x, 0.5 * (world + world.transpose()), 0, 0, std::nullopt};
    s.mesh = mesh_cross_check(model, i);
    for (const BlockInstance& instance : body.blocks) {
      const Block& block = model.blocks[instance.block];
      s.nodes += static_cast<int>(block.nodes().size());
      s.elements += static_cast<int>(block.elements().size());
    }
    out.push_back(s);
  }
  return out;
}

nlohmann::ordered_json to_json(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

void print_json(const std::vector<BodySummary>& bodies) {
  using Json = nlohmann::ordered_json;
  Json list = Json::array();
  for (const BodySummary& s : bodies) {
    Json inertia = Json::array();
    for (int r = 0; r < 3; ++r) inertia.push_back(to_json(s.inertia.row(r).transpose()));
    Json entry{{"name", s.body->name},
               {"volume", s.body->volume},
               {"mass", s.body->inertia.mass},
               {"center_of_mass", to_json(s.center_of_mass)},
               {"inertia", std::move(inertia)}};
    if (s.mesh) {
      const MeshBody& m = *s.mesh->mesh;
      entry["mesh"] = Json{{"file", m.file_path},
                           {"cutting", m.cutting == MeshCutting::exact ? "exact" : "approximate"},
                           {"blocks", m.decomposition.blocks.size()},
                           {"mesh_volume", m.surface.volume},
                           {"blocks_volume", m.decomposition.blocks_volume},
                           {"volume_error", s.mesh->volume_error},
                           {"centre_error", s.mesh->centre_error},
                           {"inertia_error", s.mesh->inertia_error}};
    }
    list.push_back(std::move(entry));
  }
  // dump() writes the shortest digits that read back as the same double (at most 17).
  std::cout << Json{{"bodies", std::move(list)}}.dump() << "\n";
}

void print_text(const std::string& scene_file, const std::vector<BodySummary>& bodies) {
  std::printf("%s: %zu bod%s\n", scene_file.c_str(), bodies.size(),
              bodies.size() == 1 ? "y" : "ies");
  for (const BodySummary& s : bodies) {
    const Body& b = *s.body;
    const Vec3 principal = Eigen::SelfAdjointEigenSolver<Mat3>(s.inertia).eigenvalues();
    std::printf("\n%s%s\n", b.name.c_str(), b.fixed ? " (fixed)" : "");
    std::printf("  blocks %zu, nodes %d, elements %d\n", b.blocks.size(), s.nodes, s.elements);
    std::printf("  volume              %.10g\n", b.volume);
    std::printf("  mass                %.10g\n", b.inertia.mass);
    std::printf("  centre of mass      %.10g %.10g %.10g\n", s.center_of_mass.x(),
                s.center_of_mass.y(), s.center_of_mass.z());
    // Off-diagonal rounding noise (1e-20 next to 1e-4) would hide the tensor's structure; a
    // person reading this table sees it as 0. --json keeps every digit.
    const Real noise = 1e-13 * s.inertia.cwiseAbs().maxCoeff();
    const Mat3 shown = s.inertia.unaryExpr([noise](Real x) { return std::abs(x) < noise ? 0 : x; });
    std::printf("  inertia about the centre of mass, world axes, initial pose:\n");
    for (int r = 0; r < 3; ++r) {
      std::printf("    %17.10g %17.10g %17.10g\n", shown(r, 0), shown(r, 1), shown(r, 2));
    }
    std::printf("  principal moments   %.10g %.10g %.10g\n", principal.x(), principal.y(),
                principal.z());
    if (s.mesh) {
      const MeshBody& m = *s.mesh->mesh;
      std::printf("  mesh %s: %d faces, cut %s into %zu blocks\n", m.file_path.c_str(),
                  m.check.faces, m.cutting == MeshCutting::exact ? "exactly" : "approximately",
                  m.decomposition.blocks.size());
      const bool exact = m.cutting == MeshCutting::exact;
      std::printf("  %s against the mesh's surface integrals (relative): volume %.3g, "
                  "centre %.3g, inertia %.3g\n",
                  exact ? "blocks" : "body", s.mesh->volume_error, s.mesh->centre_error,
                  s.mesh->inertia_error);
      if (!exact)
        std::printf("  mass properties from the mesh; its blocks cover %.3g %% more volume\n",
                    100 * (m.decomposition.blocks_volume - m.surface.volume) / m.surface.volume);
    }
  }
}

}  // namespace

int info_command(const std::string& scene_file, bool json) {
  const std::optional<Model> model = load_model(scene_file);
  if (!model) return kExitBadInput;
  print_warnings(scene_file, *model);
  const std::vector<BodySummary> bodies = summarise(*model);
  if (json) {
    print_json(bodies);
  } else {
    print_text(scene_file, bodies);
  }
  std::cout.flush();
  return kExitOk;
}

}  // namespace tem::cli
