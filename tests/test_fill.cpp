// Particle insertion (`fill`): N copies of a body at random positions and orientations in a
// region, with no initial overlap, reproducible from the seed, sharing one set of blocks.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "contact/detect_contacts.hpp"
#include "io/scene_reader.hpp"
#include "io/scene_writer.hpp"
#include "world/fill.hpp"
#include "world/placement.hpp"

namespace tem {
namespace test_fill {

// 150 of the paper's coins in a 2 x 2 x 3 region above a floor, beside one explicit box.
std::string pile_text(int seed, int count = 150) {
  return R"({
  "container": {"min": [0, 0, 0], "max": [2, 2, 4]},
  "bodies": [{"name": "box", "shape": {"type": "box", "size": [0.5, 0.5, 0.5]},
              "position": [1, 1, 1]}],
  "fill": [{"name": "coin", "count": )" +
         std::to_string(count) + R"(, "seed": )" + std::to_string(seed) + R"(,
            "region": {"min": [0, 0, 0], "max": [2, 2, 3]},
            "body": {"shape": {"type": "prism", "sides": 6, "radius": 0.15, "height": 0.1},
                     "density": 7, "velocity": [0, 0, -10]}}]
})";
}

Model pile(int seed, int count = 150) {
  const SceneReadResult read = read_scene_text(pile_text(seed, count), "pile.json");
  EXPECT_TRUE(read.ok()) << (read.ok() ? "" : read.problems[0].path + ": " + read.problems[0].message);
  return build_model(read.scene);
}

TEST(Fill, PlacesEveryCopyInsideTheRegionWithoutOverlap) {
  const Model model = pile(7);
  ASSERT_EQ(model.bodies.size(), 151u);
  EXPECT_EQ(model.bodies[0].name, "box");
  EXPECT_EQ(model.bodies[1].name, "coin_0");
  EXPECT_EQ(model.bodies[150].name, "coin_149");
  // The copies share the template's one block: two blocks in all.
  EXPECT_EQ(model.blocks.size(), 2u);
  const State state = initial_state(model);
  const Real r = body_size(model, 1);
  EXPECT_NEAR(r, std::hypot(0.15, 0.05), 1e-12);
  for (size_t i = 1; i < model.bodies.size(); ++i) {
    const BodyState& s = state.bodies[i];
    for (int k = 0; k < 3; ++k) {
      EXPECT_GE(s.x[k], r - 1e-12);
      EXPECT_LE(s.x[k], (k == 2 ? 3.0 : 2.0) - r + 1e-12);
    }
    EXPECT_NEAR((s.g.transpose() * s.g - Mat3::Identity()).norm(), 0, 1e-14);
    EXPECT_NEAR(s.g.determinant(), 1, 1e-14);
    EXPECT_EQ(s.v, Vec3(0, 0, -10));
    // The box was there first: judged by its block (placement.hpp), the copies by spheres.
    EXPECT_TRUE(sphere_clear_of_body(model, model.bodies[0], state.bodies[0], s.x, r)) << i;
    for (size_t j = 1; j < i; ++j)
      ASSERT_GE((s.x - state.bodies[j].x).norm(), r + body_size(model, static_cast<int>(j)) - 1e-12)
          << i << " " << j;
  }
  // And TEM's own contact detection finds nothing touching at the start.
  ContactWorkspace workspace;
  std::vector<ContactPatch> patches;
  detect_contacts(model, state, patch_variant(model.scene), workspace, patches);
  EXPECT_TRUE(patches.empty()) << patches.size() << " patches";
}

TEST(Fill, TheSeedDecidesEverything) {
  const State a = initial_state(pile(7)), b = initial_state(pile(7)), c = initial_state(pile(8));
  int same_as_other_seed = 0;
  for (size_t i = 1; i < a.bodies.size(); ++i) {
    EXPECT_EQ(a.bodies[i].x, b.bodies[i].x);
    EXPECT_EQ(a.bodies[i].g, b.bodies[i].g);
    same_as_other_seed += a.bodies[i].x == c.bodies[i].x;
  }
  EXPECT_EQ(same_as_other_seed, 0);
}

// Shoemake's rotations are uniform: over many draws each entry of R averages 0 with variance
// 1/3 (R's columns are uniform unit vectors), so the sample means of R and of R o R (entrywise)
// lie within 4 standard errors of 0 and 1/3.
TEST(Fill, OrientationsAreUniform) {
  const int n = 20000;
  Mat3 mean = Mat3::Zero(), mean_square = Mat3::Zero();
  std::uint64_t state = 12345;
  auto next = [&] {  // a small LCG: the test needs numbers, not the fill's generator
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<Real>(state >> 11) * 0x1.0p-53;
  };
  for (int i = 0; i < n; ++i) {
    const Real u1 = next(), u2 = next(), u3 = next();
    const Mat3 r = uniform_rotation(u1, u2, u3);
    mean += r / n;
    mean_square += r.cwiseProduct(r) / n;
  }
  const Real se_mean = std::sqrt(1.0 / 3 / n);
  const Real se_square = std::sqrt((1.0 / 5 - 1.0 / 9) / n);  // E[x^4] = 1/5 on the sphere
  for (int k = 0; k < 9; ++k) {
    EXPECT_LT(std::abs(mean(k)), 4 * se_mean) << k;
    EXPECT_LT(std::abs(mean_square(k) - 1.0 / 3), 4 * se_square) << k;
  }
}

TEST(Fill, TooManyForTheRegionSaysHowManyFit) {
  const SceneReadResult read = read_scene_text(pile_text(1, 5000), "pile.json");
  ASSERT_TRUE(read.ok());
  try {
    build_model(read.scene);
    FAIL() << "5000 coins fitted in 12 cm^3";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.path(), "fill[0].count");
    EXPECT_NE(e.reason().find(" of 5000 bodies fit in the region"), std::string::npos) << e.reason();
  }
}

// A scene needs bodies from somewhere: with an empty fill list and no `bodies`, it is an error
// naming `bodies` (the fuzzer found such a scene accepted and written back as one with none).
TEST(Fill, AnEmptyFillListStillNeedsBodies) {
  const SceneReadResult read = read_scene_text(
      R"({"container": {"min": [0, 0, 0], "max": [1, 1, 1]}, "fill": []})", "empty.json");
  ASSERT_FALSE(read.ok());
  ASSERT_EQ(read.problems.size(), 1u);
  EXPECT_NE(read.problems[0].message.find("missing required key 'bodies'"), std::string::npos)
      << read.problems[0].message;
}

TEST(Fill, ANameTakenByABodyIsAnError) {
  std::string text = pile_text(1, 3);
  text.replace(text.find("\"name\": \"box\""), 13, "\"name\": \"coin_2\"");
  const SceneReadResult read = read_scene_text(text, "pile.json");
  ASSERT_TRUE(read.ok());
  try {
    build_model(read.scene);
    FAIL();
  } catch (const SceneError& e) {
    EXPECT_EQ(e.path(), "fill[0].name");
  }
}

// scene.json keeps the fill (not 150 bodies) and gives back the same bodies.
TEST(Fill, SceneFileRoundTrip) {
  const SceneReadResult read = read_scene_text(pile_text(3), "pile.json");
  ASSERT_TRUE(read.ok());
  const std::string written = write_scene_text(read.scene);
  EXPECT_NE(written.find("\"fill\""), std::string::npos);
  const SceneReadResult again = read_scene_text(written, "scene.json");
  ASSERT_TRUE(again.ok());
  EXPECT_EQ(written, write_scene_text(again.scene));
  const State a = initial_state(build_model(read.scene));
  const State b = initial_state(build_model(again.scene));
  ASSERT_EQ(a.bodies.size(), b.bodies.size());
  for (size_t i = 0; i < a.bodies.size(); ++i) EXPECT_EQ(a.bodies[i].x, b.bodies[i].x);
}

}  // namespace test_fill
}  // namespace tem
