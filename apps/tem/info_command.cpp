// `tem info`: the mass properties of each body at its initial pose, for a person (aligned
// text) or for a script (--json: one object on stdout, numbers that read back exactly).
#include <Eigen/Eigenvalues>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>

#include "commands.hpp"
#include "tem/scene_report.hpp"

namespace tem::cli {
namespace {

nlohmann::ordered_json to_json(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

void print_json(const std::vector<BodyReport>& bodies) {
  using Json = nlohmann::ordered_json;
  Json list = Json::array();
  for (const BodyReport& s : bodies) {
    Json inertia = Json::array();
    for (int r = 0; r < 3; ++r) inertia.push_back(to_json(s.inertia.row(r).transpose()));
    Json entry{{"name", s.name},
               {"volume", s.volume},
               {"mass", s.mass},
               {"center_of_mass", to_json(s.center_of_mass)},
               {"inertia", std::move(inertia)}};
    if (s.mesh) {
      const MeshBodyCheck& m = *s.mesh;
      entry["mesh"] = Json{{"file", m.file},
                           {"cutting", m.exact ? "exact" : "approximate"},
                           {"blocks", m.blocks},
                           {"mesh_volume", m.mesh_volume},
                           {"blocks_volume", m.blocks_volume},
                           {"volume_error", s.mesh->volume_error},
                           {"centre_error", s.mesh->centre_error},
                           {"inertia_error", s.mesh->inertia_error}};
    }
    list.push_back(std::move(entry));
  }
  // dump() writes the shortest digits that read back as the same double (at most 17).
  std::cout << Json{{"bodies", std::move(list)}}.dump() << "\n";
}

void print_text(const std::string& scene_file, const std::vector<BodyReport>& bodies) {
  std::printf("%s: %zu bod%s\n", scene_file.c_str(), bodies.size(),
              bodies.size() == 1 ? "y" : "ies");
  for (const BodyReport& s : bodies) {
    const Vec3 principal = Eigen::SelfAdjointEigenSolver<Mat3>(s.inertia).eigenvalues();
    std::printf("\n%s%s\n", s.name.c_str(), s.fixed ? " (fixed)" : "");
    std::printf("  blocks %d, nodes %d, elements %d\n", s.blocks, s.nodes, s.elements);
    std::printf("  volume              %.10g\n", s.volume);
    std::printf("  mass                %.10g\n", s.mass);
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
      const MeshBodyCheck& m = *s.mesh;
      std::printf("  mesh %s: %d faces, cut %s into %d blocks\n", m.file.c_str(), m.faces,
                  m.exact ? "exactly" : "approximately", m.blocks);
      const bool exact = m.exact;
      std::printf("  %s against the mesh's surface integrals (relative): volume %.3g, "
                  "centre %.3g, inertia %.3g\n",
                  exact ? "blocks" : "body", s.mesh->volume_error, s.mesh->centre_error,
                  s.mesh->inertia_error);
      if (!exact)
        std::printf("  mass properties from the mesh; its blocks cover %.3g %% more volume\n",
                    100 * (m.blocks_volume - m.mesh_volume) / m.mesh_volume);
    }
  }
}

}  // namespace

int info_command(const std::string& scene_file, bool json) {
  SceneReport scene;
  try {
    scene = report_scene(scene_file);
  } catch (const std::exception& e) {
    std::cerr << load_failure(scene_file, e) << "\n";
    return kExitBadInput;
  }
  for (const std::string& warning : scene.warnings)
    std::cerr << scene_file << ": warning: " << warning << "\n";
  const std::vector<BodyReport>& bodies = scene.bodies;
  if (json) {
    print_json(bodies);
  } else {
    print_text(scene_file, bodies);
  }
  std::cout.flush();
  return kExitOk;
}

}  // namespace tem::cli
