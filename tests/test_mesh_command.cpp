// `tem mesh --json` as a user runs it: the over-coverage and Hausdorff distance of an approximate
// cut also as percentages (of the mesh's volume and of its bounding-box diagonal), the figures
// max_blocks is chosen by; and a refused mesh's one message on stderr.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "mass/surface_integrals.hpp"
#include "mesh/mesh_reader.hpp"
#include "support/mesh_shapes.hpp"
#include "support/tem_process.hpp"

namespace tem {
namespace test_mesh_command {

using testing_support::run_tem;
using testing_support::temp_path;

TEST(MeshCommand, JsonGivesOverCoverageAndHausdorffInPercent) {
  const std::string dir = temp_path("mesh_command_percent");
  std::filesystem::create_directories(dir);
  const std::string file = dir + "/torus.obj";
  testing_support::write_obj(testing_support::torus_mesh(1, 0.3, 48, 24), file);
  const auto run = run_tem("mesh '" + file + "' --blocks approximate --max-blocks 4 --json");
  ASSERT_EQ(run.status, 0) << run.err;
  const nlohmann::json j = nlohmann::json::parse(run.out);

  // The denominators, from the mesh as read: its volume and its bounding box's diagonal.
  const TriangleMesh mesh = read_mesh_file(file);
  Eigen::AlignedBox<Real, 3> box;
  for (const auto& f : mesh.faces)
    for (int v : f) box.extend(mesh.vertices[v]);
  const Real volume = surface_mass_properties(corner_triangles(mesh)).volume;
  const Real diagonal = box.diagonal().norm();
  EXPECT_NEAR(j["volume"].get<double>(), volume, 1e-12 * volume);
  EXPECT_NEAR(j["diagonal"].get<double>(), diagonal, 1e-12 * diagonal);

  const Real over_coverage = j["over_coverage"].get<double>();
  const Real hausdorff = j["hausdorff"].get<double>();
  EXPECT_NEAR(j["over_coverage_percent"].get<double>(), 100 * over_coverage / volume,
              1e-12 * 100 * over_coverage / volume);
  EXPECT_NEAR(j["hausdorff_percent"].get<double>(), 100 * hausdorff / diagonal,
              1e-12 * 100 * hausdorff / diagonal);
  // Four hulls round a torus cover part of its hole: the figures are far from 0.
  EXPECT_GT(j["over_coverage_percent"].get<double>(), 10.0);
  EXPECT_GT(j["hausdorff_percent"].get<double>(), 1.0);

  // An exact cut: the blocks are the mesh.
  testing_support::write_obj(testing_support::l_mesh(), dir + "/l.obj");
  const auto exact = run_tem("mesh '" + dir + "/l.obj' --blocks exact --json");
  ASSERT_EQ(exact.status, 0) << exact.err;
  const nlohmann::json e = nlohmann::json::parse(exact.out);
  EXPECT_EQ(e["over_coverage_percent"].get<double>(), 0.0);
  EXPECT_EQ(e["hausdorff_percent"].get<double>(), 0.0);
  std::filesystem::remove_all(dir);
}

// A refused mesh: exit status 1 and one message for all its defects.
TEST(MeshCommand, RefusedMeshGivesOneMessage) {
  const std::string dir = temp_path("mesh_command_refused");
  std::filesystem::create_directories(dir);
  TriangleMesh mesh = testing_support::l_mesh();
  mesh.faces.erase(mesh.faces.begin());           // 3 open edges
  std::swap(mesh.faces[4][1], mesh.faces[4][2]);  // a turned face
  testing_support::write_obj(mesh, dir + "/broken.obj");
  const auto run = run_tem("mesh '" + dir + "/broken.obj' --json");
  EXPECT_EQ(run.status, 1);
  EXPECT_TRUE(run.out.empty()) << run.out;
  EXPECT_EQ(run.err.rfind(dir + "/broken.obj: refused: ", 0), 0u) << run.err;
  EXPECT_TRUE(testing_support::contains(run.err, " open edges")) << run.err;
  EXPECT_TRUE(testing_support::contains(run.err, " inconsistently oriented edge")) << run.err;
  std::filesystem::remove_all(dir);
}

}  // namespace test_mesh_command
}  // namespace tem
