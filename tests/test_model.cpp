// Building a Model from definitions: errors name the JSON path, accepted defects become
// warnings, walls come from the container, and the initial state places the centre of mass.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "world/model.hpp"

namespace tem {
namespace test_model {

ShapeDef paper_ring(int blocks, bool allow_nonconvex) {
  ShapeDef ring;
  ring.type = ShapeType::ring;
  ring.path = "bodies[0].shape";
  ring.segments = 16;
  ring.sides = 6;
  ring.radius = 0.15;
  ring.section_radius = 0.05;
  ring.blocks = blocks;
  ring.allow_nonconvex = allow_nonconvex;
  ring.axis = Axis::y;
  return ring;
}

SceneDef scene_with(ShapeDef shape) {
  SceneDef scene;
  BodyDef body;
  body.name = "b";
  body.path = "bodies[0]";
  body.shape = std::move(shape);
  scene.bodies.push_back(body);
  return scene;
}

TEST(Model, NonConvexRingBlockIsAnErrorNamingTheShape) {
  try {
    build_model(scene_with(paper_ring(8, false)));
    FAIL() << "accepted a non-convex block";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.path(), "bodies[0].shape");
    EXPECT_NE(std::string(e.what()).find("block 1 of 8"), std::string::npos) << e.what();
    EXPECT_NE(e.reason().find("not convex"), std::string::npos) << e.what();
    EXPECT_NE(e.reason().find("blocks = segments"), std::string::npos) << e.what();
  }
}

TEST(Model, AllowedNonConvexBlocksAreReported) {
  const Model model = build_model(scene_with(paper_ring(8, true)));
  ASSERT_EQ(model.warnings.size(), 1u);  // one per shape, not one per block
  EXPECT_NE(model.warnings[0].find("bodies[0].shape: 8 of its blocks are not convex"),
            std::string::npos)
      << model.warnings[0];
  EXPECT_EQ(model.bodies[0].blocks.size(), 8u);
  EXPECT_TRUE(build_model(scene_with(paper_ring(16, false))).warnings.empty());
}

TEST(Model, DegeneratePointsNameThePointsPath) {
  ShapeDef flat;
  flat.type = ShapeType::convex;
  flat.path = "bodies[0].shape";
  flat.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}};
  try {
    build_model(scene_with(flat));
    FAIL() << "accepted coplanar points";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.path(), "bodies[0].shape.points");
    EXPECT_NE(std::string(e.what()).find("coplanar"), std::string::npos) << e.what();
  }
}

TEST(Model, ContainerGivesSixInwardWalls) {
  SceneDef scene = scene_with(paper_ring(16, false));
  scene.container = ContainerDef{Vec3(0, 0, 0), Vec3(1, 2, 3)};
  scene.walls.push_back({Vec3(0, 0, 0.5), Vec3(0, 0, 2)});
  const Model model = build_model(scene);
  ASSERT_EQ(model.walls.size(), 7u);
  const Vec3 inside(0.5, 1.0, 1.5);
  for (size_t i = 0; i < 6; ++i)
    EXPECT_GT(model.walls[i].normal.dot(inside - model.walls[i].point), 0) << i;
  EXPECT_NEAR(model.walls[6].normal.norm(), 1.0, 1e-15);
}

// A compound whose centre of mass is off the origin of its frame: the scene's position places
// the frame's origin, the state holds the centre of mass; velocities are given in world axes.
TEST(Model, InitialStatePlacesTheCentreOfMass) {
  ShapeDef a, b, compound;
  a.type = b.type = ShapeType::box;
  a.size = Vec3(1, 1, 1);
  b.size = Vec3(1, 1, 1);
  b.position = Vec3(2, 0, 0);
  compound.type = ShapeType::compound;
  compound.parts = {a, b};
  SceneDef scene = scene_with(compound);
  BodyDef& def = scene.bodies[0];
  def.position = Vec3(10, 20, 30);
  def.rotation = euler_zxz(std::numbers::pi / 2, 0, 0);  // body x -> world y
  def.velocity = Vec3(1, 2, 3);
  def.angular_velocity = Vec3(0, 0, 5);
  const Model model = build_model(scene);
  const State state = initial_state(model);
  const BodyState& s = state.bodies[0];
  EXPECT_LT((model.bodies[0].origin_offset - Vec3(-1, 0, 0)).norm(), 1e-15);
  EXPECT_LT((s.x - Vec3(10, 21, 30)).norm(), 1e-14);
  EXPECT_LT((s.v - Vec3(1, 2, 3)).norm(), 1e-15);
  EXPECT_LT((s.angular_velocity_world() - Vec3(0, 0, 5)).norm(), 1e-14);
  EXPECT_LT((s.omega - Vec3(0, 0, 5)).norm(), 1e-14);  // z is unchanged by a turn about z
  // Blocks sit at +-1 along body x from the centre of mass.
  EXPECT_LT((model.bodies[0].blocks[0].offset - Vec3(-1, 0, 0)).norm(), 1e-15);
  EXPECT_LT((model.bodies[0].blocks[1].offset - Vec3(1, 0, 0)).norm(), 1e-15);
}

// The paper's column (method.md §7): axis along body y, Euler (0, 80, 0) deg, centre at z 0.3,
// lowest point z = 0.3 - (h/2) sin 80 - r cos 80 = 0.0944 with a node of the hexagon along
// body z (the axis convention of geometry/primitives.hpp).
TEST(Model, PaperColumnLowestPoint) {
  ShapeDef column;
  column.type = ShapeType::prism;
  column.path = "bodies[0].shape";
  column.sides = 6;
  column.radius = 0.05;
  column.height = 0.4;
  column.axis = Axis::y;
  SceneDef scene = scene_with(column);
  const Real deg = std::numbers::pi / 180;
  scene.bodies[0].rotation = euler_zxz(0, 80 * deg, 0);
  scene.bodies[0].position = Vec3(0.5, 0.5, 0.3);
  const Model model = build_model(scene);
  const BodyState s = initial_state(model).bodies[0];
  Real lowest = 1e9;
  const BlockInstance& bi = model.bodies[0].blocks[0];
  for (const Vec3& p : model.blocks[bi.block].nodes())
    lowest = std::min(lowest, (s.x + s.g * (bi.rotation * p + bi.offset)).z());
  EXPECT_NEAR(lowest, 0.3 - 0.2 * std::sin(80 * deg) - 0.05 * std::cos(80 * deg), 1e-15);
}

}  // namespace test_model
}  // namespace tem
