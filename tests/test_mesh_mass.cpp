// A body cut approximately from a mesh weighs what the mesh does: its mass, centre and inertia
// are the mesh's own surface integrals (its blocks cover more than the mesh), with the mesh's
// `scale`, the body's density, the pose of the mesh in a compound and a fill copy's size factor.
// The references are the surface integrals of the mesh's triangles as read, moved and scaled
// here, and the torus's closed-form volume; the blocks' own sum is shown to differ from them.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>
#include <vector>

#include "io/scene_reader.hpp"
#include "mass/mass_properties.hpp"
#include "mass/surface_integrals.hpp"
#include "mesh/mesh_body.hpp"
#include "mesh/mesh_reader.hpp"
#include "support/mesh_shapes.hpp"
#include "support/tem_process.hpp"
#include "world/model.hpp"

namespace tem {
namespace test_mesh_mass {

using testing_support::temp_path;

constexpr Real kR = 1, kr = 0.3;  // the torus's centre-line and tube radii
constexpr int kAround = 48, kTube = 24;
constexpr Real kMeshScale = 0.5, kDensity = 2.5, kSizeFactor = 0.7;

// The torus's triangles as the reader gives them (single precision, times the mesh's scale),
// each vertex mapped by `place`.
template <class Place>
std::vector<std::array<Vec3, 3>> torus_triangles(const std::string& file, Place place) {
  const TriangleMesh mesh = read_mesh_file(file, kMeshScale);
  std::vector<std::array<Vec3, 3>> triangles;
  for (const auto& f : mesh.faces)
    triangles.push_back(
        {place(mesh.vertices[f[0]]), place(mesh.vertices[f[1]]), place(mesh.vertices[f[2]])});
  return triangles;
}

// Mass, centre (body frame: -origin_offset) and inertia of `body` against unit-density surface
// integrals times the density, to 1e-12 of each quantity's size.
void expect_mass_properties(const Body& body, const MassProperties& unit, Real size,
                            const std::string& what) {
  EXPECT_NEAR(body.inertia.mass, kDensity * unit.volume, 1e-12 * kDensity * unit.volume) << what;
  EXPECT_NEAR(body.volume, unit.volume, 1e-12 * unit.volume) << what;
  EXPECT_LT((-body.origin_offset - unit.center).norm(), 1e-12 * size) << what;
  const Mat3 inertia = kDensity * inertia_from_second_moment(unit.second_moment);
  EXPECT_LT((body.inertia.inertia - inertia).cwiseAbs().maxCoeff(),
            1e-12 * inertia.cwiseAbs().maxCoeff())
      << what << "\n"
      << body.inertia.inertia << "\nexpected\n"
      << inertia;
}

// What the body's blocks weigh together (the rule for bodies of other shapes).
MassProperties blocks_mass(const Model& model, const Body& body) {
  std::vector<PlacedMass> parts;
  for (const BlockInstance& b : body.blocks)
    parts.push_back(
        {block_mass_properties(model.blocks[b.block], body.density), b.rotation, b.offset});
  return combine(parts);
}

class MeshMass : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = temp_path("mesh_mass_" +
                     std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    std::filesystem::create_directories(dir_);
    file_ = dir_ + "/torus.obj";
    testing_support::write_obj(testing_support::torus_mesh(kR, kr, kAround, kTube), file_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  Model build(const std::string& scene_text) {
    SceneReadResult read = read_scene_text(scene_text, dir_ + "/scene.json");
    load_scene_meshes(read);
    EXPECT_TRUE(read.ok()) << (read.ok() ? "" : read.problems[0].message);
    return build_model(read.scene);
  }

  std::string mesh_shape() const {
    return R"({"type": "mesh", "file": "torus.obj", "scale": 0.5, "blocks": "approximate",
               "max_blocks": 4})";
  }

  std::string dir_, file_;
};

// A body of the torus alone, and a fill copy of it at size factor 0.7: the torus's mass
// properties, not its four blocks' (which cover part of the hole: 24 % more volume).
TEST_F(MeshMass, ApproximateBodyAndScaledCopyWeighWhatTheMeshDoes) {
  const std::string shape = mesh_shape();
  const Model model = build(R"({"container": {"min": [-5, -5, 0], "max": [5, 5, 10]},
    "bodies": [{"name": "torus", "shape": )" +
                            shape + R"(, "density": 2.5,
                "position": [0, 0, 1]}],
    "fill": [{"name": "copy", "count": 1, "region": {"min": [-4, -4, 3], "max": [4, 4, 8]},
              "body": {"shape": )" +
                            shape + R"(, "density": 2.5,
                       "scale": {"min": 0.7, "max": 0.7}}}]})");
  ASSERT_EQ(model.bodies.size(), 2u);

  const MassProperties unit =
      surface_mass_properties(torus_triangles(file_, [](const Vec3& p) { return p; }));
  // The closed form of the polyhedral torus (MeshCheck.TorusVolumeIsExact), to single precision.
  const Real section = (kTube / 2.0) * kr * kr * std::sin(2 * std::numbers::pi / kTube);
  const Real swept = kAround * std::sin(2 * std::numbers::pi / kAround) * kR * section;
  const Real scale3 = kMeshScale * kMeshScale * kMeshScale;
  EXPECT_NEAR(unit.volume, swept * scale3, 1e-6 * swept * scale3);
  expect_mass_properties(model.bodies[0], unit, kMeshScale * (kR + kr), "body");

  const MassProperties scaled = surface_mass_properties(
      torus_triangles(file_, [](const Vec3& p) { return Vec3(kSizeFactor * p); }));
  expect_mass_properties(model.bodies[1], scaled, kSizeFactor * kMeshScale * (kR + kr), "copy");

  // The blocks alone weigh more, by the decomposition's over-coverage, and turn differently.
  const auto mesh = load_mesh_body(file_, kMeshScale, MeshCutting::approximate, 4);
  const MassProperties blocks = blocks_mass(model, model.bodies[0]);
  EXPECT_GT(blocks.mass, 1.1 * model.bodies[0].inertia.mass);
  EXPECT_NEAR(blocks.mass - model.bodies[0].inertia.mass,
              kDensity * mesh->decomposition.over_coverage, 1e-9 * blocks.mass);
  const Mat3 blocks_inertia = inertia_from_second_moment(blocks.second_moment);
  EXPECT_GT((blocks_inertia - model.bodies[0].inertia.inertia).cwiseAbs().maxCoeff(),
            0.01 * model.bodies[0].inertia.inertia.cwiseAbs().maxCoeff());
}

// The torus as a part of a compound, turned a quarter about x and moved, beside a box: the
// torus's surface integrals where the part puts it, and the box's closed form.
TEST_F(MeshMass, ApproximateMeshInACompoundIsPlacedByItsPose) {
  const Vec3 torus_at(0.2, -0.1, 0.3), box_at(2, 0, 0), box_size(0.4, 0.2, 0.1);
  std::string shape = mesh_shape();
  shape.pop_back();  // the closing brace: the part's pose goes in
  shape += R"(, "position": [0.2, -0.1, 0.3], "euler_zxz_deg": [0, 90, 0]})";
  const Model model =
      build(R"({"bodies": [{"name": "pair", "density": 2.5, "position": [0, 0, 1], "shape":
    {"type": "compound", "blocks": [)" +
            shape + R"(,
      {"type": "box", "size": [0.4, 0.2, 0.1], "position": [2, 0, 0]}]}}]})");
  ASSERT_EQ(model.bodies.size(), 1u);

  const Mat3 turn = Eigen::AngleAxis<Real>(std::numbers::pi / 2, Vec3::UnitX()).toRotationMatrix();
  const MassProperties torus = surface_mass_properties(
      torus_triangles(file_, [&](const Vec3& p) { return Vec3(turn * p + torus_at); }));
  const Real box_volume = box_size.prod();
  MassProperties both;
  both.volume = both.mass = torus.volume + box_volume;
  both.center = (torus.volume * torus.center + box_volume * box_at) / both.volume;
  const Vec3 dt = torus.center - both.center, db = box_at - both.center;
  const Mat3 box_moment =
      box_volume / 12 * box_size.cwiseProduct(box_size).asDiagonal().toDenseMatrix();
  both.second_moment = torus.second_moment + torus.volume * dt * dt.transpose() + box_moment +
                       box_volume * db * db.transpose();
  expect_mass_properties(model.bodies[0], both, 2.5, "compound");
  EXPECT_GT(blocks_mass(model, model.bodies[0]).mass, 1.1 * model.bodies[0].inertia.mass);
}

}  // namespace test_mesh_mass
}  // namespace tem
