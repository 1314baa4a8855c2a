// The scene reader and writer (src/io): every key of the scene format read into its field,
// defaults, orientation conventions against hand-worked rotations, the writer/reader round
// trip, and one broken scene per kind of mistake (tests/scenes/bad/, expected.tsv), each
// giving its JSON path and reason.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "io/scene_reader.hpp"
#include "io/scene_writer.hpp"

namespace tem {
namespace test_scene_reader {

const std::string kScenes = std::string(TEM_SOURCE_DIR) + "/tests/scenes";

SceneDef read_good(const std::string& path) {
  SceneReadResult result = read_scene_file(path);
  for (const SceneProblem& p : result.problems) ADD_FAILURE() << format_problem(path, p);
  return result.scene;
}

SceneReadResult read_text(const std::string& text) { return read_scene_text(text, "test.json"); }

// A one-body scene with `body_extra` appended to the body and `top_extra` to the root.
std::string scene_with(const std::string& shape, const std::string& body_extra = "",
                       const std::string& top_extra = "") {
  return "{" + top_extra + (top_extra.empty() ? "" : ", ") +
         R"("bodies": [{"name": "a", "position": [0, 0, 0], "shape": )" + shape + body_extra +
         "}]}";
}

void expect_vec(const Vec3& actual, const Vec3& expected, double tolerance = 0) {
  EXPECT_LE((actual - expected).cwiseAbs().maxCoeff(), tolerance)
      << "actual " << actual.transpose() << ", expected " << expected.transpose();
}

void expect_mat(const Mat3& actual, const Mat3& expected, double tolerance = 0) {
  EXPECT_LE((actual - expected).cwiseAbs().maxCoeff(), tolerance) << "actual\n"
                                                                  << actual << "\nexpected\n"
                                                                  << expected;
}

Mat3 rows(const Vec3& a, const Vec3& b, const Vec3& c) {
  Mat3 m;
  m.row(0) = a;
  m.row(1) = b;
  m.row(2) = c;
  return m;
}

// Rotations written as Euler angles come back exactly; those written as quaternions (no short
// decimal Euler triple gives them) to rounding.
void expect_shape_eq(const ShapeDef& a, const ShapeDef& b, double rotation_tolerance) {
  SCOPED_TRACE(a.path);
  EXPECT_EQ(a.type, b.type);
  EXPECT_EQ(a.path, b.path);
  EXPECT_EQ(a.sides, b.sides);
  EXPECT_EQ(a.radius, b.radius);
  EXPECT_EQ(a.height, b.height);
  EXPECT_EQ(a.segments, b.segments);
  EXPECT_EQ(a.section_radius, b.section_radius);
  EXPECT_EQ(a.blocks, b.blocks);
  EXPECT_EQ(a.allow_nonconvex, b.allow_nonconvex);
  // Keys a type does not take keep their defaults; compare what the type uses.
  if (a.type == ShapeType::prism || a.type == ShapeType::ring) {
    EXPECT_EQ(a.axis, b.axis);
  }
  EXPECT_EQ(a.size, b.size);
  EXPECT_EQ(a.points, b.points);
  EXPECT_EQ(a.position, b.position);
  expect_mat(a.rotation, b.rotation, rotation_tolerance);
  ASSERT_EQ(a.parts.size(), b.parts.size());
  for (std::size_t k = 0; k < a.parts.size(); ++k) {
    expect_shape_eq(a.parts[k], b.parts[k], rotation_tolerance);
  }
}

void expect_scene_eq(const SceneDef& a, const SceneDef& b, double rotation_tolerance = 0) {
  EXPECT_EQ(a.gravity, b.gravity);
  EXPECT_EQ(a.time_step, b.time_step);
  EXPECT_EQ(a.duration, b.duration);
  EXPECT_EQ(a.integrator, b.integrator);
  EXPECT_EQ(a.contact.model, b.contact.model);
  EXPECT_EQ(a.contact.friction, b.contact.friction);
  EXPECT_EQ(a.contact.restitution, b.contact.restitution);
  EXPECT_EQ(a.contact.stiffness, b.contact.stiffness);
  EXPECT_EQ(a.contact.damping, b.contact.damping);
  EXPECT_EQ(a.contact.normals, b.contact.normals);
  EXPECT_EQ(a.contact.points, b.contact.points);
  ASSERT_EQ(a.container.has_value(), b.container.has_value());
  if (a.container) {
    EXPECT_EQ(a.container->min, b.container->min);
    EXPECT_EQ(a.container->max, b.container->max);
  }
  ASSERT_EQ(a.walls.size(), b.walls.size());
  for (std::size_t i = 0; i < a.walls.size(); ++i) {
    EXPECT_EQ(a.walls[i].point, b.walls[i].point);
    EXPECT_EQ(a.walls[i].normal, b.walls[i].normal);
  }
  ASSERT_EQ(a.bodies.size(), b.bodies.size());
  for (std::size_t i = 0; i < a.bodies.size(); ++i) {
    const BodyDef& x = a.bodies[i];
    const BodyDef& y = b.bodies[i];
    SCOPED_TRACE(x.path);
    EXPECT_EQ(x.name, y.name);
    EXPECT_EQ(x.path, y.path);
    EXPECT_EQ(x.density, y.density);
    EXPECT_EQ(x.position, y.position);
    expect_mat(x.rotation, y.rotation, rotation_tolerance);
    EXPECT_EQ(x.velocity, y.velocity);
    EXPECT_EQ(x.angular_velocity, y.angular_velocity);
    EXPECT_EQ(x.fixed, y.fixed);
    expect_shape_eq(x.shape, y.shape, rotation_tolerance);
  }
  EXPECT_EQ(a.output.interval, b.output.interval);
  EXPECT_EQ(a.output.checkpoint_interval, b.output.checkpoint_interval);
  EXPECT_EQ(a.output.paraview, b.output.paraview);
}

// ---- Reading every key -------------------------------------------------------------------

TEST(SceneReader, ReadsEveryKeyOfAFullScene) {
  const SceneDef s = read_good(kScenes + "/full.json");
  EXPECT_EQ(s.source, kScenes + "/full.json");
  EXPECT_EQ(s.gravity, Vec3(1.5, -2, -3.25));
  EXPECT_EQ(s.time_step, 2e-5);
  EXPECT_EQ(s.duration, 0.5);
  EXPECT_EQ(s.integrator, IntegratorKind::paper);
  EXPECT_EQ(s.contact.model, ContactModel::penalty);
  EXPECT_EQ(s.contact.friction, 0.5);
  EXPECT_EQ(s.contact.restitution, 0.25);
  EXPECT_EQ(s.contact.stiffness, 1e5);
  EXPECT_EQ(s.contact.damping, 10);
  ASSERT_TRUE(s.container.has_value());
  EXPECT_EQ(s.container->min, Vec3(-1, -2, -3));
  EXPECT_EQ(s.container->max, Vec3(4, 5, 6));
  ASSERT_EQ(s.walls.size(), 2u);
  EXPECT_EQ(s.walls[0].point, Vec3(0, 0, 1));
  EXPECT_EQ(s.walls[0].normal, Vec3(0, 0, 1));  // [0, 0, 2] normalised
  EXPECT_EQ(s.walls[1].point, Vec3(1, 2, 3));
  expect_vec(s.walls[1].normal, Vec3(0.6, 0.8, 0), 1e-16);  // [3, 4, 0] normalised
  EXPECT_EQ(s.output.interval, 0.02);
  EXPECT_EQ(s.output.checkpoint_interval, 0.1);
  EXPECT_TRUE(s.output.paraview);
  ASSERT_EQ(s.bodies.size(), 5u);

  const BodyDef& coin = s.bodies[0];
  EXPECT_EQ(coin.name, "coin");
  EXPECT_EQ(coin.path, "bodies[0]");
  EXPECT_EQ(coin.shape.path, "bodies[0].shape");
  EXPECT_EQ(coin.shape.type, ShapeType::prism);
  EXPECT_EQ(coin.shape.sides, 8);
  EXPECT_EQ(coin.shape.radius, 0.2);
  EXPECT_EQ(coin.shape.height, 0.05);
  EXPECT_EQ(coin.shape.axis, Axis::x);
  EXPECT_EQ(coin.density, 7);
  EXPECT_EQ(coin.position, Vec3(0.1, 0.2, 0.3));
  // euler (90, 0, 0) = Rz(90 deg): x -> y, y -> -x, z -> z; exact at quarter turns.
  EXPECT_EQ(coin.rotation, rows({0, -1, 0}, {1, 0, 0}, {0, 0, 1}));
  EXPECT_EQ(coin.velocity, Vec3(1, 2, 3));
  EXPECT_EQ(coin.angular_velocity, Vec3(4, 5, 6));
  EXPECT_FALSE(coin.fixed);

  const BodyDef& donut = s.bodies[1];
  EXPECT_EQ(donut.shape.type, ShapeType::ring);
  EXPECT_EQ(donut.shape.segments, 12);
  EXPECT_EQ(donut.shape.sides, 4);
  EXPECT_EQ(donut.shape.radius, 0.3);
  EXPECT_EQ(donut.shape.section_radius, 0.1);
  EXPECT_EQ(donut.shape.blocks, 4);
  EXPECT_EQ(donut.shape.axis, Axis::y);
  EXPECT_TRUE(donut.shape.allow_nonconvex);
  EXPECT_EQ(donut.density, 1.0);
  // Quaternion (1/2)(1, 1, 1, 1): 120 degrees about (1, 1, 1), which cycles x -> y -> z -> x.
  EXPECT_EQ(donut.rotation, rows({0, 0, 1}, {1, 0, 0}, {0, 1, 0}));

  const BodyDef& floor = s.bodies[2];
  EXPECT_EQ(floor.shape.type, ShapeType::box);
  EXPECT_EQ(floor.shape.size, Vec3(2, 3, 0.5));
  EXPECT_EQ(floor.density, 2.5);
  EXPECT_TRUE(floor.fixed);
  // euler (90, 90, 0) = Rz(90) Rx(90): x -> x -> y, y -> z -> z, z -> -y -> x.
  EXPECT_EQ(floor.rotation, rows({0, 0, 1}, {1, 0, 0}, {0, 1, 0}));

  const BodyDef& rock = s.bodies[3];
  EXPECT_EQ(rock.shape.type, ShapeType::convex);
  const std::vector<Vec3> points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0.5, 0.5, 0.5}};
  EXPECT_EQ(rock.shape.points, points);
  EXPECT_EQ(rock.rotation, Mat3::Identity());

  const ShapeDef& dumbbell = s.bodies[4].shape;
  EXPECT_EQ(dumbbell.type, ShapeType::compound);
  ASSERT_EQ(dumbbell.parts.size(), 2u);
  EXPECT_EQ(dumbbell.parts[0].path, "bodies[4].shape.blocks[0]");
  EXPECT_EQ(dumbbell.parts[0].type, ShapeType::box);
  EXPECT_EQ(dumbbell.parts[0].size, Vec3(0.1, 0.2, 0.3));
  EXPECT_EQ(dumbbell.parts[0].position, Vec3(-1, 0, 0));
  EXPECT_EQ(dumbbell.parts[0].rotation, rows({1, 0, 0}, {0, 0, -1}, {0, 1, 0}));  // Rx(90)
  EXPECT_EQ(dumbbell.parts[1].path, "bodies[4].shape.blocks[1]");
  EXPECT_EQ(dumbbell.parts[1].type, ShapeType::prism);
  EXPECT_EQ(dumbbell.parts[1].sides, 3);
  EXPECT_EQ(dumbbell.parts[1].axis, Axis::z);
  EXPECT_EQ(dumbbell.parts[1].position, Vec3(1, 0, 0));
  EXPECT_EQ(dumbbell.parts[1].rotation, Mat3::Identity());
}

TEST(SceneReader, FillsDefaults) {
  const SceneDef s = read_good(kScenes + "/minimal.json");
  EXPECT_EQ(s.gravity, Vec3(0, 0, -980.665));
  EXPECT_EQ(s.time_step, 1e-5);
  EXPECT_EQ(s.duration, 1.0);
  EXPECT_EQ(s.integrator, IntegratorKind::default_);
  EXPECT_EQ(s.contact.model, ContactModel::semm);
  EXPECT_EQ(s.contact.friction, ContactDef{}.friction);
  EXPECT_EQ(s.contact.restitution, 0.0);
  EXPECT_EQ(s.contact.stiffness, 0.0);
  EXPECT_EQ(s.contact.damping, 0.0);
  EXPECT_FALSE(s.contact.margin.has_value());  // "auto"
  EXPECT_EQ(s.contact.solver, ContactSolver::newton);
  EXPECT_FALSE(s.container.has_value());
  EXPECT_TRUE(s.walls.empty());
  EXPECT_EQ(s.output.interval, 0.01);
  EXPECT_EQ(s.output.checkpoint_interval, 0.0);
  EXPECT_FALSE(s.output.paraview);
  ASSERT_EQ(s.bodies.size(), 1u);
  const BodyDef& b = s.bodies[0];
  EXPECT_EQ(b.density, 1.0);
  EXPECT_EQ(b.rotation, Mat3::Identity());
  EXPECT_EQ(b.velocity, Vec3::Zero());
  EXPECT_EQ(b.angular_velocity, Vec3::Zero());
  EXPECT_FALSE(b.fixed);
}

// contact.margin: "auto" (the default), a number, or 0; contact.solver: newton (the default), rows or blocks.
TEST(SceneReader, ContactMarginAndSolver) {
  auto contact = [](const std::string& keys) {
    const SceneReadResult r = read_scene_text(
        R"({"contact": {)" + keys +
            R"(}, "bodies": [{"name": "a", "shape": {"type": "box", "size": [1, 1, 1]}, )"
            R"("position": [0, 0, 0]}]})",
        "inline.json");
    EXPECT_TRUE(r.ok()) << keys;
    return r.scene.contact;
  };
  EXPECT_FALSE(contact(R"("margin": "auto")").margin.has_value());
  EXPECT_EQ(contact(R"("margin": 0.02)").margin, std::optional<Real>(0.02));
  EXPECT_EQ(contact(R"("margin": 0)").margin, std::optional<Real>(0.0));
  EXPECT_EQ(contact(R"("solver": "blocks")").solver, ContactSolver::blocks);
  EXPECT_EQ(contact(R"("solver": "rows")").solver, ContactSolver::rows);
}

TEST(SceneReader, ShapeDefaults) {
  SceneReadResult r =
      read_text(scene_with(R"({"type": "ring", "radius": 2, "section_radius": 1})"));
  ASSERT_TRUE(r.ok());
  const ShapeDef& ring = r.scene.bodies[0].shape;
  EXPECT_EQ(ring.segments, 16);
  EXPECT_EQ(ring.sides, 6);
  EXPECT_EQ(ring.blocks, 16);  // one block per segment
  EXPECT_EQ(ring.axis, Axis::z);
  EXPECT_FALSE(ring.allow_nonconvex);

  r = read_text(
      scene_with(R"({"type": "ring", "segments": 10, "radius": 2, "section_radius": 1})"));
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r.scene.bodies[0].shape.blocks, 10);

  // `blocks` is checked against the default segment count too.
  r = read_text(scene_with(R"({"type": "ring", "blocks": 5, "radius": 2, "section_radius": 1})"));
  ASSERT_EQ(r.problems.size(), 1u);
  EXPECT_EQ(r.problems[0].path, "bodies[0].shape.blocks");
  EXPECT_NE(r.problems[0].message.find("must divide segments (16)"), std::string::npos);

  r = read_text(
      scene_with(R"({"type": "compound", "blocks": [{"type": "box", "size": [1, 2, 3]}]})"));
  ASSERT_TRUE(r.ok());
  const ShapeDef& part = r.scene.bodies[0].shape.parts.at(0);
  EXPECT_EQ(part.position, Vec3::Zero());
  EXPECT_EQ(part.rotation, Mat3::Identity());
}

TEST(SceneReader, GravityByName) {
  SceneReadResult r =
      read_text(scene_with(R"({"type": "box", "size": [1, 1, 1]})", "", R"("gravity": "paper")"));
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r.scene.gravity, Vec3(0, 0, -98.0));
  r = read_text(scene_with(R"({"type": "box", "size": [1, 1, 1]})", "", R"("gravity": "earth")"));
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r.scene.gravity, Vec3(0, 0, -980.665));
}

TEST(SceneReader, IntegralValuedNumbersCountAsIntegers) {
  const SceneReadResult r = read_text(
      scene_with(R"({"type": "prism", "sides": 6.0, "radius": 1, "height": 1, "axis": "y"})"));
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r.scene.bodies[0].shape.sides, 6);
}

TEST(SceneReader, PaperScenes) {
  const SceneDef coin = read_good(std::string(TEM_SOURCE_DIR) + "/scenes/paper/coin.json");
  EXPECT_EQ(coin.gravity, Vec3(0, 0, -98.0));
  EXPECT_EQ(coin.integrator, IntegratorKind::paper);
  EXPECT_EQ(coin.contact.model, ContactModel::semm_paper);
  EXPECT_EQ(coin.contact.friction, 0.0);
  ASSERT_EQ(coin.bodies.size(), 1u);
  EXPECT_EQ(coin.bodies[0].shape.axis, Axis::y);
  const Real deg = M_PI / 180;
  expect_mat(coin.bodies[0].rotation, euler_zxz(10 * deg, 80 * deg, 10 * deg), 1e-15);

  const SceneDef ring = read_good(std::string(TEM_SOURCE_DIR) + "/scenes/paper/ring_column.json");
  ASSERT_EQ(ring.bodies.size(), 2u);
  EXPECT_EQ(ring.bodies[0].shape.blocks, 8);
  EXPECT_TRUE(ring.bodies[0].shape.allow_nonconvex);
  EXPECT_EQ(ring.bodies[1].shape.height, 0.4);
}

// ---- Orientation conventions -------------------------------------------------------------

TEST(Rotations, ElementaryRotationsAreActiveAndRightHanded) {
  const Real quarter = M_PI / 2;
  expect_vec(rotation_z(quarter) * Vec3::UnitX(), Vec3::UnitY(), 1e-16);
  expect_vec(rotation_z(quarter) * Vec3::UnitY(), -Vec3::UnitX(), 1e-16);
  expect_vec(rotation_x(quarter) * Vec3::UnitY(), Vec3::UnitZ(), 1e-16);
  expect_vec(rotation_x(quarter) * Vec3::UnitZ(), -Vec3::UnitY(), 1e-16);
  const Mat3 g = euler_zxz(0.3, 1.1, -0.7);
  expect_mat(g * g.transpose(), Mat3::Identity(), 1e-15);
  EXPECT_NEAR(g.determinant(), 1.0, 1e-15);
}

TEST(Rotations, EulerZxzHandWorked) {
  // (90, 0, 0): Rz(90) maps body x to world y.
  expect_vec(euler_zxz(M_PI / 2, 0, 0) * Vec3::UnitX(), Vec3::UnitY(), 1e-16);
  EXPECT_EQ(rotation_from_euler_zxz_deg({90, 0, 0}) * Vec3::UnitX(), Vec3::UnitY());
  // (0, 90, 0): Rx(90) maps body y to world z (the paper's symmetry axis tilts to vertical).
  EXPECT_EQ(rotation_from_euler_zxz_deg({0, 90, 0}) * Vec3::UnitY(), Vec3::UnitZ());
  // (0, 0, 90) is Rz(90) too, applied first: the same matrix as (90, 0, 0).
  EXPECT_EQ(rotation_from_euler_zxz_deg({0, 0, 90}), rotation_from_euler_zxz_deg({90, 0, 0}));
  // (90, 90, 90): x -Rz-> y -Rx-> z -Rz-> z; y -> -x -> -x -> -y; z -> z -> -y -> x.
  EXPECT_EQ(rotation_from_euler_zxz_deg({90, 90, 90}), rows({0, 0, 1}, {0, -1, 0}, {1, 0, 0}));
  // Negative and full turns reduce exactly.
  EXPECT_EQ(rotation_from_euler_zxz_deg({-270, 450, 720}),
            rotation_from_euler_zxz_deg({90, 90, 0}));
  // A general case against the radian form, and the paper coin's axis (body y) 14.1 degrees
  // from vertical (method.md section 1).
  const Real deg = M_PI / 180;
  const Mat3 g = rotation_from_euler_zxz_deg({10, 80, 10});
  expect_mat(g, euler_zxz(10 * deg, 80 * deg, 10 * deg), 1e-15);
  EXPECT_NEAR(std::acos(g.col(1).z()) / deg, 14.1, 0.05);
}

TEST(Rotations, QuaternionMatchesAxisAngle) {
  const Real angle = 0.7;
  const Mat3 q = rotation_from_quaternion(std::cos(angle / 2), 0, 0, std::sin(angle / 2));
  expect_mat(q, rotation_z(angle), 1e-15);
  const Mat3 qx = rotation_from_quaternion(std::cos(angle / 2), std::sin(angle / 2), 0, 0);
  expect_mat(qx, rotation_x(angle), 1e-15);
}

TEST(SceneReader, AcceptsQuaternionWithinToleranceOfUnitNorm) {
  const std::string box = R"({"type": "box", "size": [1, 1, 1]})";
  EXPECT_TRUE(read_text(scene_with(box, R"(, "quaternion": [1.0000005, 0, 0, 0])")).ok());
  const SceneReadResult r = read_text(scene_with(box, R"(, "quaternion": [1.00001, 0, 0, 0])"));
  ASSERT_EQ(r.problems.size(), 1u);
  EXPECT_EQ(r.problems[0].path, "bodies[0].quaternion");
  EXPECT_NE(r.problems[0].message.find("1.00001"), std::string::npos) << r.problems[0].message;
}

// ---- Writer round trip -------------------------------------------------------------------

TEST(SceneWriter, RoundTripGivesTheSameScene) {
  for (const std::string& file : {kScenes + "/full.json", kScenes + "/minimal.json",
                                  std::string(TEM_SOURCE_DIR) + "/scenes/paper/coin.json",
                                  std::string(TEM_SOURCE_DIR) + "/scenes/paper/ring_column.json"}) {
    SCOPED_TRACE(file);
    const SceneDef original = read_good(file);
    const std::string text = write_scene_text(original);
    const SceneReadResult again = read_scene_text(text, "written.json");
    for (const SceneProblem& p : again.problems) ADD_FAILURE() << format_problem("written", p);
    expect_scene_eq(original, again.scene);
  }
}

// A wall normal is scaled to unit length once: written back and read again, it stays the same
// double triple (the fuzzer found normals that moved by an ulp when divided by their rounded
// length a second time, so scene.json gave a different scene.json).
TEST(SceneWriter, WallNormalsReadBackBitForBit) {
  for (const char* normal : {"[5, 6, 1]", "[0.98058067569092, 0.0, 0.19611613513818402]",
                             "[1e-200, 3e-200, 0]", "[0, 0, 1]"}) {
    SCOPED_TRACE(normal);
    const std::string text =
        std::string(R"({"bodies": [{"name": "a", "shape": {"type": "box", "size": [1, 1, 1]},)") +
        R"( "position": [0, 0, 2]}], "walls": [{"point": [0, 0, 0], "normal": )" + normal + "}]}";
    const SceneReadResult first = read_scene_text(text, "walls.json");
    for (const SceneProblem& p : first.problems) ADD_FAILURE() << format_problem("walls", p);
    ASSERT_TRUE(first.ok());
    ASSERT_EQ(first.scene.walls.size(), 1u);
    const Vec3 n = first.scene.walls[0].normal;
    EXPECT_NEAR(n.norm(), 1, 4e-16);
    const std::string written = write_scene_text(first.scene);
    const SceneReadResult again = read_scene_text(written, "scene.json");
    ASSERT_TRUE(again.ok());
    for (int k = 0; k < 3; ++k) EXPECT_EQ(again.scene.walls[0].normal[k], n[k]) << k;
    EXPECT_EQ(write_scene_text(again.scene), written);
  }
}

// Written, read and written again, a rotation gives the same text: Euler angles [0, 220, 0]
// make a matrix no short Euler triple reproduces, so it is written as a quaternion, whose
// matrix read back differed in the last bit, and whose quaternion differed again (fuzz-found).
TEST(SceneWriter, RotationsWrittenTwiceGiveTheSameText) {
  for (const char* orientation :
       {R"("euler_zxz_deg": [0, 220, 0])", R"("euler_zxz_deg": [0, 80, 0])",
        R"("euler_zxz_deg": [33.3, 123.456, -7.1])", R"("quaternion": [0.1, 0.2, -0.3, 0.9273618495495704])"}) {
    SCOPED_TRACE(orientation);
    const SceneReadResult first =
        read_text(scene_with(R"({"type": "box", "size": [1, 2, 3]})", std::string(", ") + orientation));
    ASSERT_TRUE(first.ok());
    const std::string written = write_scene_text(first.scene);
    const SceneReadResult again = read_scene_text(written, "scene.json");
    ASSERT_TRUE(again.ok());
    EXPECT_EQ(write_scene_text(again.scene), written);
    EXPECT_TRUE(again.scene.bodies[0].rotation.isApprox(first.scene.bodies[0].rotation, 1e-15));
  }
}

TEST(SceneWriter, RoundTripOfAnArbitraryRotation) {
  const std::string box = R"({"type": "box", "size": [1, 1, 1]})";
  // A unit quaternion to 17 digits: no short Euler triple gives it, so it is written back as a
  // quaternion.
  const Quat q = Quat(0.1, 0.2, -0.3, 0.9).normalized();
  std::ostringstream quaternion;
  quaternion.precision(17);
  quaternion << R"(, "quaternion": [)" << q.w() << ", " << q.x() << ", " << q.y() << ", " << q.z()
             << "]";
  const SceneReadResult original = read_text(scene_with(box, quaternion.str()));
  ASSERT_TRUE(original.ok());
  const std::string text = write_scene_text(original.scene);
  EXPECT_NE(text.find("\"quaternion\""), std::string::npos) << text;
  const SceneReadResult again = read_scene_text(text, "written.json");
  ASSERT_TRUE(again.ok());
  expect_scene_eq(original.scene, again.scene, 4e-16);
}

// A margin the scene gives (0: contact only after overlap) is written as given, with the pair
// cache on or off: the writer once put "auto" over it whenever the cache was on, so a run's
// scene.json ran differently from its scene and checkpoints of the two matched.
TEST(SceneWriter, KeepsTheContactMarginGiven) {
  for (const std::string margin : {"0", "0.05", "\"auto\""}) {
    for (const std::string cache : {"true", "false"}) {
      SCOPED_TRACE(margin + ", pair_cache " + cache);
      const std::string text = R"({"contact": {"margin": )" + margin + R"(, "pair_cache": )" +
                               cache + R"(}, "bodies": [{"name": "b", "position": [0, 0, 0],
                               "shape": {"type": "box", "size": [1, 1, 1]}}]})";
      const SceneReadResult first = read_scene_text(text, "margin.json");
      ASSERT_TRUE(first.problems.empty());
      const SceneReadResult again = read_scene_text(write_scene_text(first.scene), "written.json");
      ASSERT_TRUE(again.problems.empty());
      EXPECT_EQ(again.scene.contact.margin, first.scene.contact.margin);
      EXPECT_EQ(again.scene.contact.pair_cache, first.scene.contact.pair_cache);
    }
  }
}

TEST(SceneWriter, WritesEulerAnglesWhenTheyReproduceTheRotation) {
  const SceneDef coin = read_good(std::string(TEM_SOURCE_DIR) + "/scenes/paper/coin.json");
  const auto j = scene_to_json(coin);
  EXPECT_EQ(j["bodies"][0]["euler_zxz_deg"], nlohmann::ordered_json::parse("[10, 80, 10]"));
}

TEST(SceneWriter, WritesEveryDefault) {
  const SceneDef s = read_good(kScenes + "/minimal.json");
  const auto j = scene_to_json(s);
  for (const char* key :
       {"gravity", "time_step", "duration", "integrator", "contact", "walls", "bodies", "output"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  EXPECT_FALSE(j.contains("container"));  // none given: no container
  for (const char* key : {"model", "friction", "restitution", "stiffness", "damping"}) {
    EXPECT_TRUE(j["contact"].contains(key)) << key;
  }
  const auto& body = j["bodies"][0];
  for (const char* key : {"name", "shape", "density", "position", "euler_zxz_deg", "velocity",
                          "angular_velocity", "fixed"}) {
    EXPECT_TRUE(body.contains(key)) << key;
  }
  for (const char* key : {"interval", "checkpoint_interval", "paraview"}) {
    EXPECT_TRUE(j["output"].contains(key)) << key;
  }
}

TEST(SceneWriter, WritesAFileThatReadsBack) {
  const SceneDef s = read_good(kScenes + "/full.json");
  const std::string file = testing::TempDir() + "tem_scene_writer_test.json";
  std::string error;
  ASSERT_TRUE(write_scene_file(s, file, &error)) << error;
  const SceneDef again = read_good(file);
  expect_scene_eq(s, again);
  std::filesystem::remove(file);
}

// ---- Broken scenes -----------------------------------------------------------------------

struct Expected {
  std::string path;  // "" for problems with the file itself
  std::string fragment;
};

// tests/scenes/bad/expected.tsv: file, path ('-' for none), message fragment.
std::map<std::string, std::vector<Expected>> load_expectations() {
  std::ifstream in(kScenes + "/bad/expected.tsv");
  EXPECT_TRUE(in) << "cannot read expected.tsv";
  std::map<std::string, std::vector<Expected>> table;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    std::string file, path, fragment;
    std::getline(fields, file, '\t');
    std::getline(fields, path, '\t');
    std::getline(fields, fragment);
    table[file].push_back({path == "-" ? "" : path, fragment});
  }
  return table;
}

TEST(SceneReader, EachBrokenSceneGivesItsPathAndReason) {
  const auto table = load_expectations();
  ASSERT_GE(table.size(), 30u);
  for (const auto& [file, expected] : table) {
    SCOPED_TRACE(file);
    const SceneReadResult r = read_scene_file(kScenes + "/bad/" + file);
    std::string all;
    for (const SceneProblem& p : r.problems) all += "\n  " + format_problem(file, p);
    EXPECT_EQ(r.problems.size(), expected.size()) << "problems:" << all;
    for (const Expected& e : expected) {
      bool found = false;
      for (const SceneProblem& p : r.problems) {
        found = found || (p.path == e.path && p.message.find(e.fragment) != std::string::npos);
      }
      EXPECT_TRUE(found) << "expected " << (e.path.empty() ? "-" : e.path) << ": ..." << e.fragment
                         << "...\nproblems:" << all;
    }
  }
}

TEST(SceneReader, EveryBrokenSceneIsInTheTable) {
  const auto table = load_expectations();
  for (const auto& entry : std::filesystem::directory_iterator(kScenes + "/bad")) {
    if (entry.path().extension() != ".json") continue;
    EXPECT_TRUE(table.count(entry.path().filename().string()))
        << entry.path().filename() << " has no row in expected.tsv";
  }
}

TEST(SceneReader, MissingFile) {
  const SceneReadResult r = read_scene_file(kScenes + "/no_such_scene.json");
  ASSERT_EQ(r.problems.size(), 1u);
  EXPECT_EQ(r.problems[0].path, "");
  EXPECT_NE(r.problems[0].message.find("no such file"), std::string::npos);
  EXPECT_EQ(format_problem("x.json", r.problems[0]), "x.json: no such file");
}

TEST(SceneReader, FormatsProblemsWithFileAndPath) {
  EXPECT_EQ(format_problem("s.json", {"bodies[1].shape.radius", "must be a positive number"}),
            "s.json: bodies[1].shape.radius: must be a positive number");
}

TEST(SceneReader, ShapeTypeDecidesTheAllowedKeys) {
  // A ring's `blocks` is a count, a compound's a list: each is checked as its own type says.
  SceneReadResult r = read_text(scene_with(R"({"type": "compound", "blocks": 4})"));
  ASSERT_EQ(r.problems.size(), 1u);
  EXPECT_EQ(r.problems[0].path, "bodies[0].shape.blocks");
  // A compound's part may carry a pose; a nested part's bad key names its full path.
  r = read_text(scene_with(
      R"({"type": "compound", "blocks": [{"type": "box", "size": [1, 1, 1], "sides": 3}]})"));
  ASSERT_EQ(r.problems.size(), 1u);
  EXPECT_EQ(r.problems[0].path, "bodies[0].shape.blocks[0]");
  EXPECT_NE(r.problems[0].message.find("'sides' does not apply to a box"), std::string::npos);
}

TEST(SceneReader, DuplicateKeyInsideAListNamesTheElement) {
  const SceneReadResult r = read_text(
      R"({"walls": [{"point": [0, 0, 0], "normal": [0, 0, 1]},
                    {"point": [0, 0, 0], "normal": [0, 0, 1], "point": [1, 1, 1]}],
          "bodies": [{"name": "a", "position": [0, 0, 0], "shape": {"type": "box", "size": [1, 1, 1]}}]})");
  ASSERT_EQ(r.problems.size(), 1u);
  EXPECT_EQ(r.problems[0].path, "walls[1].point");
}

}  // namespace test_scene_reader
}  // namespace tem
