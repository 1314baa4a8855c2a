// Contact detection through the whole pipeline of a step (broad phase, narrow phase, patches,
// merging across blocks) on bodies built from scene definitions, with expectations worked out
// by hand: a ring threaded on a column, a body of several blocks, a body in a corner of walls.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "contact/detect_contacts.hpp"

namespace tem {
namespace test_contact_scenes {

constexpr Real kTight = 1e-12;
constexpr Real kPi = std::numbers::pi;

ShapeDef box_shape(const Vec3& size) {
  ShapeDef s;
  s.type = ShapeType::box;
  s.size = size;
  return s;
}

ShapeDef prism_shape(int sides, Real radius, Real height) {
  ShapeDef s;
  s.type = ShapeType::prism;
  s.sides = sides;
  s.radius = radius;
  s.height = height;
  return s;
}

ShapeDef ring_shape(int sides, Real radius, Real section_radius) {
  ShapeDef s;
  s.type = ShapeType::ring;
  s.segments = 16;
  s.sides = sides;
  s.radius = radius;
  s.section_radius = section_radius;
  return s;
}

BodyDef body(const std::string& name, ShapeDef shape, const Vec3& position,
             const Mat3& rotation = Mat3::Identity()) {
  BodyDef b;
  b.name = name;
  b.path = "bodies[" + name + "]";
  b.shape = std::move(shape);
  b.position = position;
  b.rotation = rotation;
  return b;
}

std::vector<ContactPatch> contacts(const SceneDef& scene) {
  const Model model = build_model(scene);
  const State state = initial_state(model);
  ContactWorkspace workspace;
  std::vector<ContactPatch> patches;
  detect_contacts(model, state, patch_variant(scene), workspace, patches);
  return patches;
}

// A ring of 16 segments with a triangular section (R 0.15, r_s 0.05; its apex points outward, so
// its inside is a 16-gon of flat faces at rho cos(pi/16), rho = R - r_s/2) threaded on a plank
// column 0.02 thick, 0.4 tall, whose two narrow ends reach 0.002 past the ring's inner faces.
// Turned by half a segment, each end meets the middle of one inner face: two patches, normals
// from the ring into the column along the plank's long axis, depth 0.002, points 0.001 inside
// the inner face, at the mid-height of the section.
TEST(ContactScenes, RingThreadedOnAColumnTouchesAtTwoPlaces) {
  const Real big_r = 0.15, section = 0.05, rho = big_r - section / 2;
  const Real inner = rho * std::cos(kPi / 16), d = 0.002, turn = kPi / 16;
  const ShapeDef ring = ring_shape(3, big_r, section);
  SceneDef scene;
  scene.bodies.push_back(body("ring", ring, Vec3::Zero()));
  scene.bodies.push_back(
      body("column", box_shape(Vec3(2 * (inner + d), 0.02, 0.4)), Vec3::Zero(), rotation_z(turn)));
  const std::vector<ContactPatch> patches = contacts(scene);
  ASSERT_EQ(patches.size(), 2u);
  const Vec3 axis(std::cos(turn), std::sin(turn), 0);  // the plank's long axis
  for (const ContactPatch& p : patches) {
    EXPECT_EQ(p.body_a, 0);
    EXPECT_EQ(p.body_b, 1);
    EXPECT_EQ(p.wall, -1);
    const Real side = p.point.dot(axis) > 0 ? 1 : -1;
    EXPECT_LT((p.normal + side * axis).norm(), 1e-9) << p.normal.transpose();
    EXPECT_NEAR(p.depth, d, 1e-9);
    EXPECT_LT((p.point - side * (inner + d / 2) * axis).norm(), 1e-9) << p.point.transpose();
  }
  EXPECT_LT((patches[0].point + patches[1].point).norm(), 1e-9);  // one place on each side

  // Turned to the seam between two segments instead and lengthened to reach d past it, each end
  // meets the mitre edge of two blocks: the two blocks' patches merge into one place per end. Each block's overlap is
  // thinnest along its own inner face's normal (11.25 deg off the long axis), over which the
  // plank's far corner (half-thickness 0.01 sideways) lies d cos + 0.01 sin deep; the merged
  // normal is their mean, the long axis itself.
  scene.bodies[1].rotation = Mat3::Identity();
  scene.bodies[1].shape.size.x() = 2 * (rho + d);
  const std::vector<ContactPatch> seam = contacts(scene);
  ASSERT_EQ(seam.size(), 2u);
  for (const ContactPatch& p : seam) {
    const Real side = p.point.x() > 0 ? 1 : -1;
    EXPECT_LT((p.normal + side * Vec3::UnitX()).norm(), 1e-9) << p.normal.transpose();
    EXPECT_NEAR(p.depth, d * std::cos(kPi / 16) + 0.01 * std::sin(kPi / 16), 1e-9);
    EXPECT_NEAR(p.point.y(), 0, 1e-9);
    EXPECT_NEAR(p.point.z(), 0, 1e-9);
  }
}

// The paper's own shapes: the 16-segment ring of hexagonal section (R 0.15, r_s 0.05, one
// block per segment) around the origin, axis z, and the hexagonal column (r 0.05, h 0.4) through
// it, tilted about x until its flat side faces press on the ring's innermost ridge above on one
// side and below on the other. Both bodies are symmetric under the half turn about x and under
// the mirror x -> -x, so the patches must be too: at 53 degrees two patches, one the half turn
// of the other, on the plane x = 0, their normals the column's side-face normal (0, cos, sin)
// turned from the ring into the column. At 51 degrees the face meets the ridge at two of its
// corners on each side, well off the plane x = 0: four patches, images of each other in pairs.
TEST(ContactScenes, PaperRingThreadedOnThePaperColumn) {
  const ShapeDef ring = ring_shape(6, 0.15, 0.05), column = prism_shape(6, 0.05, 0.4);
  auto half_turn = [](const Vec3& v) { return Vec3(v.x(), -v.y(), -v.z()); };
  auto mirror = [](const Vec3& v) { return Vec3(-v.x(), v.y(), v.z()); };

  const Real tilt = 53 * kPi / 180;
  SceneDef scene;
  scene.bodies.push_back(body("ring", ring, Vec3::Zero()));
  scene.bodies.push_back(body("column", column, Vec3::Zero(), rotation_x(tilt)));
  const std::vector<ContactPatch> two = contacts(scene);
  ASSERT_EQ(two.size(), 2u);
  EXPECT_LT((two[1].point - half_turn(two[0].point)).norm(), kTight);
  EXPECT_LT((two[1].normal - half_turn(two[0].normal)).norm(), kTight);
  EXPECT_NEAR(two[0].depth, two[1].depth, kTight);
  EXPECT_GT(two[0].depth, 0);
  EXPECT_LT(two[0].depth, 0.01);
  const Vec3 face(0, std::cos(tilt), std::sin(tilt));  // a side face's outward normal
  for (const ContactPatch& p : two) {
    EXPECT_NEAR(p.point.x(), 0, kTight);
    const Real side = p.point.y() > 0 ? -1 : 1;
    EXPECT_LT((p.normal - side * face).norm(), kTight) << p.normal.transpose();
  }

  scene.bodies[1].rotation = rotation_x(51 * kPi / 180);
  const std::vector<ContactPatch> four = contacts(scene);
  ASSERT_EQ(four.size(), 4u);
  for (const ContactPatch& p : four) {
    int images = 0;
    for (const ContactPatch& q : four) {
      images += (q.point - mirror(p.point)).norm() < kTight &&
                (q.normal - mirror(p.normal)).norm() < kTight;
      images += (q.point - half_turn(p.point)).norm() < kTight &&
                (q.normal - half_turn(p.normal)).norm() < kTight;
    }
    EXPECT_EQ(images, 2) << p.point.transpose();
    EXPECT_NEAR(std::abs(p.point.x()), std::abs(four[0].point.x()), kTight);
    EXPECT_GT(std::abs(p.point.x()), 0.01);
  }
}

// A dumbbell, one body of three blocks (two cubes joined by a bar that stays clear of the table),
// pressed d into a fixed table: two patches, one under each cube, normal -z, depth d.
TEST(ContactScenes, BodyOfSeveralBlocksTouchesWithTwoOfThem) {
  const Real d = 0.004;
  ShapeDef dumbbell;
  dumbbell.type = ShapeType::compound;
  ShapeDef left = box_shape(Vec3(0.1, 0.1, 0.1)), right = left,
           bar = box_shape(Vec3(0.2, 0.02, 0.02));
  left.position = Vec3(-0.15, 0, 0);
  right.position = Vec3(0.15, 0, 0);
  bar.position = Vec3(0, 0, 0.03);
  dumbbell.parts = {left, bar, right};
  SceneDef scene;
  scene.bodies.push_back(body("table", box_shape(Vec3(1, 1, 0.2)), Vec3(0, 0, -0.1)));
  scene.bodies[0].fixed = true;
  scene.bodies.push_back(body("dumbbell", dumbbell, Vec3(0.2, 0.1, 0.05 - d)));
  const std::vector<ContactPatch> patches = contacts(scene);
  ASSERT_EQ(patches.size(), 2u);
  for (const ContactPatch& p : patches) {
    EXPECT_EQ(p.body_a, 0);  // the table comes first: normals point from the table up
    EXPECT_EQ(p.body_b, 1);
    EXPECT_LT((p.normal - Vec3::UnitZ()).norm(), kTight);
    EXPECT_NEAR(p.depth, d, kTight);
    EXPECT_NEAR(p.point.z(), -d / 2, kTight);
    EXPECT_NEAR(p.point.y(), 0.1, kTight);
  }
  EXPECT_NEAR(std::min(patches[0].point.x(), patches[1].point.x()), 0.2 - 0.15, kTight);
  EXPECT_NEAR(std::max(patches[0].point.x(), patches[1].point.x()), 0.2 + 0.15, kTight);
}

// A cube of side 0.2 pushed dx into the container's wall x = 0 and dz into its floor: two
// patches, one per wall, with the walls' exact normals (from the body into the wall) and depths;
// 1e-9 away from both walls, none.
TEST(ContactScenes, BodyTouchingTwoWalls) {
  const Real dx = 0.003, dz = 0.005, s = 0.2;
  SceneDef scene;
  scene.container = ContainerDef{};
  scene.bodies.push_back(body("cube", box_shape(Vec3(s, s, s)), Vec3(s / 2 - dx, 0.5, s / 2 - dz)));
  const std::vector<ContactPatch> patches = contacts(scene);
  ASSERT_EQ(patches.size(), 2u);
  // Walls in the container's order: x = 0 is wall 0, z = 0 is wall 4.
  EXPECT_EQ(patches[0].wall, 0);
  EXPECT_EQ(patches[1].wall, 4);
  EXPECT_LT((patches[0].normal - Vec3(-1, 0, 0)).norm(), kTight);
  EXPECT_LT((patches[1].normal - Vec3(0, 0, -1)).norm(), kTight);
  EXPECT_NEAR(patches[0].depth, dx, kTight);
  EXPECT_NEAR(patches[1].depth, dz, kTight);
  EXPECT_LT((patches[0].point - Vec3(-dx / 2, 0.5, s / 2 - dz)).norm(), kTight);
  EXPECT_LT((patches[1].point - Vec3(s / 2 - dx, 0.5, -dz / 2)).norm(), kTight);

  scene.bodies[0].position = Vec3(s / 2 + 1e-9, 0.5, s / 2 + 1e-9);
  EXPECT_TRUE(contacts(scene).empty());
}

// The paper's coin resting flat on the floor of its container, 1e-4 deep: one patch with the
// floor's normal, the depth as placed, at the coin's centre.
TEST(ContactScenes, CoinFlatOnTheFloor) {
  const ShapeDef coin = prism_shape(6, 0.15, 0.1);
  SceneDef scene;
  scene.container = ContainerDef{};
  scene.bodies.push_back(body("coin", coin, Vec3(0.5, 0.5, 0.05 - 1e-4)));
  const std::vector<ContactPatch> patches = contacts(scene);
  ASSERT_EQ(patches.size(), 1u);
  EXPECT_LT((patches[0].normal - Vec3(0, 0, -1)).norm(), kTight);
  EXPECT_NEAR(patches[0].depth, 1e-4, kTight);
  EXPECT_LT((patches[0].point - Vec3(0.5, 0.5, -0.5e-4)).norm(), 1e-12);
}

}  // namespace test_contact_scenes
}  // namespace tem
