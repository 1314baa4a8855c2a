// The granular-process keys of the scene format (interface.md "Granular processes",
// docs/scene_format.md): materials and contact.pairs, material, motion, removed_at and scale,
// inlets, outlets and sensors. Every key of a full scene read into its field, defaults filled
// in, the writer's round trip (read, written, read and written again: the same text), and one
// test per mistake, each giving its JSON path and the key words of its reason.
#include <gtest/gtest.h>

#include <cmath>
#include <initializer_list>
#include <limits>
#include <string>
#include <vector>

#include "io/checkpoint.hpp"
#include "io/scene_reader.hpp"
#include "io/scene_writer.hpp"

namespace tem {
namespace test_process_scene_reader {

SceneReadResult read_text(const std::string& text) { return read_scene_text(text, "test.json"); }

SceneDef read_good(const std::string& text) {
  const SceneReadResult r = read_text(text);
  for (const SceneProblem& p : r.problems) ADD_FAILURE() << format_problem("test.json", p);
  return r.scene;
}

std::string all_problems(const SceneReadResult& r) {
  std::string all;
  for (const SceneProblem& p : r.problems) all += "\n  " + format_problem("test.json", p);
  return all;
}

// Exactly one problem, at `path`, whose message holds every fragment.
void expect_problem(const std::string& text, const std::string& path,
                    std::initializer_list<std::string> fragments) {
  const SceneReadResult r = read_text(text);
  ASSERT_EQ(r.problems.size(), 1u) << "problems:" << all_problems(r) << "\nscene: " << text;
  EXPECT_EQ(r.problems[0].path, path) << r.problems[0].message;
  for (const std::string& f : fragments) {
    EXPECT_NE(r.problems[0].message.find(f), std::string::npos)
        << "expected '" << f << "' in: " << r.problems[0].message;
  }
}

const std::string kBox = R"({"type": "box", "size": [1, 1, 1]})";
const std::string kMaterials =
    R"("materials": {"grain": {"friction": 0.5}, "steel": {"restitution": 0.5}})";

// A scene of one body "a" with `body_extra` appended to it and `top_extra` to the root (by
// default the materials grain and steel).
std::string with_body(const std::string& body_extra, const std::string& top_extra = kMaterials) {
  return "{" + top_extra + (top_extra.empty() ? "" : ", ") +
         R"("bodies": [{"name": "a", "position": [0, 0, 0], "shape": )" + kBox + body_extra + "}]}";
}

// A scene whose bodies come from one inlet with `inlet_extra` appended to it (the body named
// by `body`), besides kMaterials and `top_extra`.
std::string with_inlet(const std::string& inlet_extra,
                       const std::string& body = R"({"shape": )" + kBox + "}",
                       const std::string& top_extra = "") {
  return "{" + kMaterials + (top_extra.empty() ? "" : ", " + top_extra) +
         R"(, "inlets": [{"name": "feed", "region": {"min": [0, 0, 0], "max": [4, 4, 4]}, )"
         R"("rate": 100, "count": 10, "body": )" +
         body + inlet_extra + "}]}";
}

// ---- A full scene ------------------------------------------------------------------------

const std::string kFull = R"({
  "materials": {
    "steel": {"friction": 0.3, "restitution": 0.5},
    "grain": {"friction": 0.5, "restitution": 0.1, "rolling_resistance": 0.02}
  },
  "contact": {"model": "semm",
              "pairs": [{"materials": ["grain", "steel"], "friction": 0.2, "restitution": 0.3},
                        {"materials": ["grain", "grain"], "rolling_resistance": 0.1}]},
  "container": {"min": [-10, -10, -20], "max": [50, 20, 20], "material": "steel"},
  "walls": [{"point": [0, 0, -15], "normal": [0, 0, 2], "material": "grain", "removed_at": 0.5}],
  "bodies": [
    {"name": "belt", "shape": {"type": "box", "size": [40, 10, 1]}, "position": [0, 0, -0.5],
     "material": "steel",
     "motion": {"velocity": [20, 0, 0], "angular_velocity": [0, 0, 0.5], "center": [1, 2, 3],
                "start": 0.1, "end": 1e9,
                "oscillation": {"amplitude": [0, 0, 0.1], "frequency": 30}}},
    {"name": "gate", "shape": {"type": "box", "size": [4, 4, 0.2]}, "position": [2, 2, -0.1],
     "fixed": true, "removed_at": 0.3},
    {"name": "drum", "shape": {"type": "box", "size": [1, 1, 1]}, "position": [20, 0, 0],
     "motion": {"angular_velocity": [0, 1, 0]}}
  ],
  "fill": [{"name": "seed", "count": 5, "region": {"min": [10, 0, 0], "max": [14, 4, 4]},
            "body": {"shape": {"type": "box", "size": [0.2, 0.2, 0.2]}, "material": "grain",
                     "scale": {"min": 0.9, "max": 1.1}}}],
  "inlets": [{"name": "feed", "region": {"min": [0, 0, 10], "max": [4, 4, 12]},
              "rate": 500, "count": 2000, "start": 0.25, "seed": 3,
              "velocity": [0, 0, -50],
              "body": {"shape": {"type": "prism", "sides": 6, "radius": 0.15, "height": 0.2},
                       "density": 2.5, "material": "grain", "scale": {"min": 0.8, "max": 1.2},
                       "angular_velocity": [1, 2, 3]}}],
  "outlets": [{"name": "bin", "region": {"min": [-1, -1, -10], "max": [5, 5, -5]}}],
  "sensors": [{"name": "orifice", "type": "plane", "point": [2, 2, -0.3], "normal": [0, 0, -2]},
              {"name": "drum", "type": "force", "bodies": ["drum", "seed_4"]},
              {"name": "bed", "type": "region", "region": {"min": [0, 0, 0], "max": [4, 4, 4]}}]
})";

TEST(ProcessSceneReader, ReadsEveryKeyOfAFullScene) {
  const SceneDef s = read_good(kFull);

  ASSERT_EQ(s.materials.size(), 2u);  // in name order
  EXPECT_EQ(s.materials[0].name, "grain");
  EXPECT_EQ(s.materials[0].path, "materials.grain");
  EXPECT_EQ(s.materials[0].friction, 0.5);
  EXPECT_EQ(s.materials[0].restitution, 0.1);
  EXPECT_EQ(s.materials[0].rolling_resistance, 0.02);
  EXPECT_EQ(s.materials[1].name, "steel");
  EXPECT_EQ(s.materials[1].friction, 0.3);
  EXPECT_EQ(s.materials[1].restitution, 0.5);
  EXPECT_EQ(s.materials[1].rolling_resistance, 0.0);

  ASSERT_EQ(s.contact.pairs.size(), 2u);
  EXPECT_EQ(s.contact.pairs[0].path, "contact.pairs[0]");
  EXPECT_EQ(s.contact.pairs[0].first, "grain");
  EXPECT_EQ(s.contact.pairs[0].second, "steel");
  EXPECT_EQ(s.contact.pairs[0].friction, std::optional<Real>(0.2));
  EXPECT_EQ(s.contact.pairs[0].restitution, std::optional<Real>(0.3));
  EXPECT_FALSE(s.contact.pairs[0].rolling_resistance.has_value());
  EXPECT_EQ(s.contact.pairs[1].first, "grain");
  EXPECT_EQ(s.contact.pairs[1].second, "grain");
  EXPECT_EQ(s.contact.pairs[1].rolling_resistance, std::optional<Real>(0.1));
  EXPECT_FALSE(s.contact.pairs[1].friction.has_value());

  ASSERT_TRUE(s.container.has_value());
  EXPECT_EQ(s.container->material, "steel");
  ASSERT_EQ(s.walls.size(), 1u);
  EXPECT_EQ(s.walls[0].normal, Vec3(0, 0, 1));
  EXPECT_EQ(s.walls[0].material, "grain");
  EXPECT_EQ(s.walls[0].removed_at, std::optional<Real>(0.5));

  ASSERT_EQ(s.bodies.size(), 3u);
  const BodyDef& belt = s.bodies[0];
  EXPECT_EQ(belt.material, "steel");
  ASSERT_TRUE(belt.motion.has_value());
  EXPECT_EQ(belt.motion->velocity, Vec3(20, 0, 0));
  EXPECT_EQ(belt.motion->angular_velocity, Vec3(0, 0, 0.5));
  EXPECT_EQ(belt.motion->center, std::optional<Vec3>(Vec3(1, 2, 3)));
  EXPECT_EQ(belt.motion->start, 0.1);
  EXPECT_EQ(belt.motion->end, 1e9);
  ASSERT_TRUE(belt.motion->oscillation.has_value());
  EXPECT_EQ(belt.motion->oscillation->amplitude, Vec3(0, 0, 0.1));
  EXPECT_EQ(belt.motion->oscillation->frequency, 30);
  EXPECT_FALSE(belt.fixed);
  EXPECT_FALSE(belt.removed_at.has_value());
  const BodyDef& gate = s.bodies[1];
  EXPECT_TRUE(gate.fixed);
  EXPECT_FALSE(gate.motion.has_value());
  EXPECT_EQ(gate.removed_at, std::optional<Real>(0.3));
  EXPECT_EQ(gate.material, "");

  ASSERT_EQ(s.fill.size(), 1u);
  EXPECT_EQ(s.fill[0].body.material, "grain");
  ASSERT_TRUE(s.fill[0].body.scale.has_value());
  EXPECT_EQ(s.fill[0].body.scale->min, 0.9);
  EXPECT_EQ(s.fill[0].body.scale->max, 1.1);

  ASSERT_EQ(s.inlets.size(), 1u);
  const InletDef& feed = s.inlets[0];
  EXPECT_EQ(feed.path, "inlets[0]");
  EXPECT_EQ(feed.name, "feed");
  EXPECT_EQ(feed.region.min, Vec3(0, 0, 10));
  EXPECT_EQ(feed.region.max, Vec3(4, 4, 12));
  EXPECT_EQ(feed.rate, 500);
  EXPECT_EQ(feed.count, 2000);
  EXPECT_EQ(feed.start, 0.25);
  EXPECT_EQ(feed.seed, 3u);
  EXPECT_EQ(feed.velocity, Vec3(0, 0, -50));
  EXPECT_EQ(feed.body.path, "inlets[0].body");
  EXPECT_EQ(feed.body.shape.path, "inlets[0].body.shape");
  EXPECT_EQ(feed.body.shape.type, ShapeType::prism);
  EXPECT_EQ(feed.body.density, 2.5);
  EXPECT_EQ(feed.body.material, "grain");
  ASSERT_TRUE(feed.body.scale.has_value());
  EXPECT_EQ(feed.body.scale->min, 0.8);
  EXPECT_EQ(feed.body.scale->max, 1.2);
  EXPECT_EQ(feed.body.angular_velocity, Vec3(1, 2, 3));

  ASSERT_EQ(s.outlets.size(), 1u);
  EXPECT_EQ(s.outlets[0].path, "outlets[0]");
  EXPECT_EQ(s.outlets[0].name, "bin");
  EXPECT_EQ(s.outlets[0].region.min, Vec3(-1, -1, -10));
  EXPECT_EQ(s.outlets[0].region.max, Vec3(5, 5, -5));

  ASSERT_EQ(s.sensors.size(), 3u);
  EXPECT_EQ(s.sensors[0].path, "sensors[0]");
  EXPECT_EQ(s.sensors[0].name, "orifice");
  EXPECT_EQ(s.sensors[0].type, SensorType::plane);
  EXPECT_EQ(s.sensors[0].point, Vec3(2, 2, -0.3));
  EXPECT_EQ(s.sensors[0].normal, Vec3(0, 0, -1));  // [0, 0, -2] normalised
  EXPECT_EQ(s.sensors[1].type, SensorType::force);
  EXPECT_EQ(s.sensors[1].bodies, (std::vector<std::string>{"drum", "seed_4"}));
  EXPECT_EQ(s.sensors[2].type, SensorType::region);
  EXPECT_EQ(s.sensors[2].region.min, Vec3(0, 0, 0));
  EXPECT_EQ(s.sensors[2].region.max, Vec3(4, 4, 4));
}

TEST(ProcessSceneReader, FillsDefaults) {
  const SceneDef s = read_good(
      with_body(R"(, "material": "grain", "motion": {})", R"("materials": {"grain": {}})"));
  ASSERT_EQ(s.materials.size(), 1u);
  EXPECT_EQ(s.materials[0].friction, 0.3);
  EXPECT_EQ(s.materials[0].restitution, 0.0);
  EXPECT_EQ(s.materials[0].rolling_resistance, 0.0);
  const MotionDef& m = *s.bodies[0].motion;
  EXPECT_EQ(m.velocity, Vec3::Zero());
  EXPECT_EQ(m.angular_velocity, Vec3::Zero());
  EXPECT_FALSE(m.center.has_value());
  EXPECT_EQ(m.start, 0.0);
  EXPECT_EQ(m.end, std::numeric_limits<Real>::infinity());
  EXPECT_FALSE(m.oscillation.has_value());

  const SceneDef in = read_good(with_inlet(""));
  EXPECT_TRUE(in.bodies.empty());  // inlets alone make the bodies
  ASSERT_EQ(in.inlets.size(), 1u);
  EXPECT_EQ(in.inlets[0].start, 0.0);
  EXPECT_EQ(in.inlets[0].seed, 1u);
  EXPECT_EQ(in.inlets[0].velocity, Vec3::Zero());
  EXPECT_EQ(in.inlets[0].body.density, 1.0);
  EXPECT_EQ(in.inlets[0].body.material, "");
  EXPECT_FALSE(in.inlets[0].body.scale.has_value());
}

TEST(ProcessSceneReader, InletsAllowEmptyBodies) {
  EXPECT_TRUE(read_text(with_inlet("", R"({"shape": )" + kBox + "}", R"("bodies": [])")).ok());
  // An empty inlet list makes no bodies: `bodies` is then required, as with an empty fill.
  expect_problem(R"({"inlets": []})", "(root)", {"missing required key 'bodies'"});
}

// ---- Writing -----------------------------------------------------------------------------

TEST(ProcessSceneWriter, FullSceneWrittenTwiceGivesTheSameText) {
  const SceneDef first = read_good(kFull);
  const std::string written = write_scene_text(first);
  const SceneReadResult again = read_scene_text(written, "scene.json");
  ASSERT_TRUE(again.ok()) << all_problems(again) << "\n" << written;
  EXPECT_EQ(write_scene_text(again.scene), written);
  // Every key came back.
  EXPECT_EQ(again.scene.materials.size(), 2u);
  EXPECT_EQ(again.scene.contact.pairs.size(), 2u);
  EXPECT_EQ(again.scene.container->material, "steel");
  EXPECT_EQ(again.scene.walls[0].removed_at, std::optional<Real>(0.5));
  EXPECT_EQ(again.scene.bodies[0].motion->oscillation->frequency, 30);
  EXPECT_EQ(again.scene.bodies[0].motion->end, 1e9);
  EXPECT_EQ(again.scene.bodies[1].removed_at, std::optional<Real>(0.3));
  EXPECT_EQ(again.scene.fill[0].body.scale->max, 1.1);
  EXPECT_EQ(again.scene.inlets[0].body.scale->min, 0.8);
  EXPECT_EQ(again.scene.inlets[0].seed, 3u);
  EXPECT_EQ(again.scene.outlets[0].name, "bin");
  EXPECT_EQ(again.scene.sensors[1].bodies, first.sensors[1].bodies);
  EXPECT_EQ(again.scene.sensors[0].normal, Vec3(0, 0, -1));
}

TEST(ProcessSceneWriter, WritesDefaultsFilledInAndLeavesOutAnInfiniteEnd) {
  const SceneDef s = read_good(
      with_body(R"(, "material": "grain", "motion": {})", R"("materials": {"grain": {}})"));
  const auto j = scene_to_json(s);
  const auto& grain = j["materials"]["grain"];
  EXPECT_EQ(grain["friction"], 0.3);
  EXPECT_EQ(grain["restitution"], 0.0);
  EXPECT_EQ(grain["rolling_resistance"], 0.0);
  const auto& motion = j["bodies"][0]["motion"];
  EXPECT_EQ(motion["start"], 0.0);
  EXPECT_EQ(motion["velocity"], nlohmann::ordered_json::parse("[0.0, 0.0, 0.0]"));
  EXPECT_EQ(motion["angular_velocity"], nlohmann::ordered_json::parse("[0.0, 0.0, 0.0]"));
  EXPECT_FALSE(motion.contains("end"));     // infinite: no end
  EXPECT_FALSE(motion.contains("center"));  // the centre of mass at start
  EXPECT_EQ(j["bodies"][0]["material"], "grain");

  const auto inlet = scene_to_json(read_good(with_inlet("")))["inlets"][0];
  for (const char* key : {"name", "region", "rate", "count", "start", "seed", "velocity", "body"})
    EXPECT_TRUE(inlet.contains(key)) << key;
  EXPECT_EQ(inlet["seed"], 1);
  EXPECT_EQ(inlet["start"], 0.0);
}

// A scene without process keys writes none of them (scene.json as before, and the same
// checkpoint fingerprint).
TEST(ProcessSceneWriter, ScenesWithoutProcessKeysWriteNone) {
  const auto j = scene_to_json(read_good(with_body("", "")));
  for (const char* key : {"materials", "inlets", "outlets", "sensors"})
    EXPECT_FALSE(j.contains(key)) << key;
  EXPECT_FALSE(j["contact"].contains("pairs"));
  for (const char* key : {"material", "motion", "removed_at", "scale"})
    EXPECT_FALSE(j["bodies"][0].contains(key)) << key;
}

TEST(ProcessSceneWriter, DefaultsWrittenReadBackToTheSameText) {
  for (const std::string& text :
       {with_body(R"(, "material": "grain", "motion": {"end": 0.5}, "removed_at": 0)"),
        with_inlet(R"(, "start": 1e-3)"),
        with_body("", R"("sensors": [{"name": "s", "type": "plane", "point": [0, 0, 0], )"
                      R"("normal": [0.98058067569092, 0.0, 0.19611613513818402]}])")}) {
    SCOPED_TRACE(text);
    const SceneReadResult first = read_text(text);
    ASSERT_TRUE(first.ok()) << all_problems(first);
    const std::string written = write_scene_text(first.scene);
    const SceneReadResult again = read_scene_text(written, "scene.json");
    ASSERT_TRUE(again.ok()) << all_problems(again);
    EXPECT_EQ(write_scene_text(again.scene), written);
  }
}

// A checkpoint's scene fingerprint is a hash of the written scene: it changes with every
// process key, so a run is not resumed under another material, motion or inlet.
TEST(ProcessSceneWriter, FingerprintCoversTheProcessKeys) {
  const SceneDef base = read_good(kFull);
  const std::uint64_t fingerprint = scene_fingerprint(base);
  EXPECT_EQ(scene_fingerprint(read_good(kFull)), fingerprint);
  auto changed = [&](auto change) {
    SceneDef s = base;
    change(s);
    return scene_fingerprint(s);
  };
  EXPECT_NE(changed([](SceneDef& s) { s.materials[0].rolling_resistance = 0.5; }), fingerprint);
  EXPECT_NE(changed([](SceneDef& s) { s.contact.pairs[0].friction.reset(); }), fingerprint);
  EXPECT_NE(changed([](SceneDef& s) { s.bodies[0].material = "grain"; }), fingerprint);
  EXPECT_NE(changed([](SceneDef& s) { s.bodies[0].motion->end = 2; }), fingerprint);
  EXPECT_NE(changed([](SceneDef& s) { s.bodies[1].removed_at = 0.4; }), fingerprint);
  EXPECT_NE(changed([](SceneDef& s) { s.walls[0].removed_at.reset(); }), fingerprint);
  EXPECT_NE(changed([](SceneDef& s) { s.container->material = ""; }), fingerprint);
  EXPECT_NE(changed([](SceneDef& s) { s.fill[0].body.scale->max = 1.5; }), fingerprint);
  EXPECT_NE(changed([](SceneDef& s) { s.inlets[0].rate = 10; }), fingerprint);
  EXPECT_NE(changed([](SceneDef& s) { s.outlets[0].region.min.x() = -2; }), fingerprint);
  EXPECT_NE(changed([](SceneDef& s) { s.sensors[1].bodies.pop_back(); }), fingerprint);
}

// ---- Materials and pairs -----------------------------------------------------------------

TEST(ProcessSceneReader, MaterialCoefficientsOutOfRange) {
  expect_problem(with_body("", R"("materials": {"grain": {"friction": -0.1}})"),
                 "materials.grain.friction", {"must be zero or positive", "-0.1"});
  expect_problem(with_body("", R"("materials": {"grain": {"restitution": 1.5}})"),
                 "materials.grain.restitution", {"between 0 and 1"});
  expect_problem(with_body("", R"("materials": {"grain": {"rolling_resistance": -1}})"),
                 "materials.grain.rolling_resistance", {"zero or positive"});
  expect_problem(with_body("", R"("materials": {"grain": {"frction": 1}})"), "materials.grain",
                 {"unknown key 'frction'", "did you mean 'friction'"});
}

TEST(ProcessSceneReader, MaterialNamesFollowTheRulesOfBodyNames) {
  expect_problem(with_body("", R"("materials": {"a,b": {}})"), "materials.a,b",
                 {"must not contain commas"});
  expect_problem(with_body("", R"("materials": {"": {}})"), "materials.", {"must not be empty"});
  expect_problem(with_body("", R"("materials": [1])"), "materials",
                 {"must be an object of named materials"});
}

TEST(ProcessSceneReader, PairNamesAnUnknownMaterial) {
  expect_problem(
      with_body("", kMaterials + R"(, "contact": {"pairs": [{"materials": ["grain", "steal"]}]})"),
      "contact.pairs[0].materials[1]",
      {"unknown material 'steal'", "did you mean 'steel'", "materials are: 'grain', 'steel'"});
}

TEST(ProcessSceneReader, PairGivenTwiceInEitherOrder) {
  expect_problem(with_body("", kMaterials + R"(, "contact": {"pairs": [)"
                                            R"({"materials": ["grain", "steel"], "friction": 1},)"
                                            R"({"materials": ["steel", "grain"]}]})"),
                 "contact.pairs[1].materials", {"already given by contact.pairs[0]"});
}

TEST(ProcessSceneReader, PairNeedsTwoNamesAndValidCoefficients) {
  expect_problem(
      with_body("", kMaterials + R"(, "contact": {"pairs": [{"materials": ["grain"]}]})"),
      "contact.pairs[0].materials", {"must be a list of 2 material names"});
  expect_problem(with_body("", kMaterials + R"(, "contact": {"pairs": [{"friction": 1}]})"),
                 "contact.pairs[0]", {"missing required key 'materials'"});
  expect_problem(
      with_body("", kMaterials + R"(, "contact": {"pairs": [{"materials": ["grain", "steel"], )"
                                 R"("restitution": 2}]})"),
      "contact.pairs[0].restitution", {"between 0 and 1"});
}

TEST(ProcessSceneReader, EveryMaterialKeyNamesADefinedMaterial) {
  expect_problem(with_body(R"(, "material": "grian")"), "bodies[0].material",
                 {"unknown material 'grian'", "did you mean 'grain'"});
  expect_problem(with_body("", kMaterials + R"(, "container": {"min": [-5, -5, -5], )"
                                            R"("max": [5, 5, 5], "material": "wood"})"),
                 "container.material", {"unknown material 'wood'", "materials are"});
  expect_problem(with_body("", kMaterials + R"(, "walls": [{"point": [0, 0, 0], )"
                                            R"("normal": [0, 0, 1], "material": "wood"}])"),
                 "walls[0].material", {"unknown material 'wood'"});
  expect_problem(with_inlet("", R"({"shape": )" + kBox + R"(, "material": "wood"})"),
                 "inlets[0].body.material", {"unknown material 'wood'"});
  expect_problem(with_body("", kMaterials +
                                   R"(, "fill": [{"name": "f", "count": 1, )"
                                   R"("region": {"min": [0, 0, 0], "max": [1, 1, 1]}, )"
                                   R"("body": {"shape": )" +
                                   kBox + R"(, "material": "wood"}}])"),
                 "fill[0].body.material", {"unknown material 'wood'"});
  // Without any materials, the message says so.
  expect_problem(with_body(R"(, "material": "grain")", ""), "bodies[0].material",
                 {"unknown material 'grain'", "defines no materials"});
  expect_problem(with_body(R"(, "material": 3)"), "bodies[0].material", {"must be a string"});
}

// ---- Motion, removed_at, scale -----------------------------------------------------------

TEST(ProcessSceneReader, MotionOnAFixedBody) {
  expect_problem(with_body(R"(, "fixed": true, "motion": {"velocity": [1, 0, 0]})"),
                 "bodies[0].fixed", {"prescribed motion is moved by it", "drop 'fixed'"});
}

TEST(ProcessSceneReader, MotionTimes) {
  expect_problem(with_body(R"(, "motion": {"start": 1, "end": 1})"), "bodies[0].motion.end",
                 {"must be later than start (1)", "got 1"});
  expect_problem(with_body(R"(, "motion": {"end": -2})"), "bodies[0].motion.end",
                 {"later than start (0)"});
  expect_problem(with_body(R"(, "motion": {"start": -1})"), "bodies[0].motion.start",
                 {"must be zero or positive", "-1"});
  expect_problem(with_body(R"(, "motion": {"velocity": [1, 0]})"), "bodies[0].motion.velocity",
                 {"list of 3 numbers"});
  expect_problem(with_body(R"(, "motion": {"speed": 1})"), "bodies[0].motion",
                 {"unknown key 'speed'"});
}

TEST(ProcessSceneReader, MotionOscillation) {
  expect_problem(with_body(R"(, "motion": {"oscillation": {"amplitude": [0, 0, 1], )"
                           R"("frequency": 0}})"),
                 "bodies[0].motion.oscillation.frequency", {"must be a positive number"});
  expect_problem(with_body(R"(, "motion": {"oscillation": {"frequency": 5}})"),
                 "bodies[0].motion.oscillation", {"missing required key 'amplitude'"});
}

TEST(ProcessSceneReader, MotionIsNotForTemplates) {
  expect_problem(with_inlet("", R"({"shape": )" + kBox + R"(, "motion": {}})"), "inlets[0].body",
                 {"unknown key 'motion'", "move freely"});
  expect_problem(with_body("", R"("fill": [{"name": "f", "count": 1, )"
                               R"("region": {"min": [0, 0, 0], "max": [1, 1, 1]}, )"
                               R"("body": {"shape": )" +
                                   kBox + R"(, "motion": {}}}])"),
                 "fill[0].body", {"unknown key 'motion'", "move freely"});
}

TEST(ProcessSceneReader, RemovedAtMustNotBeNegative) {
  expect_problem(with_body(R"(, "removed_at": -0.5)"), "bodies[0].removed_at",
                 {"must be zero or positive", "-0.5"});
  expect_problem(with_body("", R"("walls": [{"point": [0, 0, 0], "normal": [0, 0, 1], )"
                               R"("removed_at": -1}])"),
                 "walls[0].removed_at", {"must be zero or positive"});
  expect_problem(with_body(R"(, "removed_at": "soon")"), "bodies[0].removed_at",
                 {"must be a number"});
}

TEST(ProcessSceneReader, ScaleOnlyOnTemplates) {
  expect_problem(with_body(R"(, "scale": {"min": 1, "max": 2})"), "bodies[0]",
                 {"unknown key 'scale'", "fill or an inlet"});
}

TEST(ProcessSceneReader, ScaleBounds) {
  expect_problem(with_inlet("", R"({"shape": )" + kBox + R"(, "scale": {"min": 1.2, "max": 0.8}})"),
                 "inlets[0].body.scale.max", {"must be at least min (1.2)", "0.8"});
  expect_problem(with_inlet("", R"({"shape": )" + kBox + R"(, "scale": {"min": 0, "max": 1}})"),
                 "inlets[0].body.scale.min", {"must be a positive number"});
  expect_problem(with_inlet("", R"({"shape": )" + kBox + R"(, "scale": {"min": 1}})"),
                 "inlets[0].body.scale", {"missing required key 'max'"});
}

// ---- Inlets ------------------------------------------------------------------------------

// One inlet of the given rate and count (JSON text).
std::string inlet_of(const std::string& rate, const std::string& count) {
  return R"({"inlets": [{"name": "feed", "region": {"min": [0, 0, 0], "max": [1, 1, 1]}, )"
         R"("rate": )" +
         rate + R"(, "count": )" + count + R"(, "body": {"shape": )" + kBox + "}}]}";
}

TEST(ProcessSceneReader, InletRateCountAndStart) {
  EXPECT_TRUE(read_text(inlet_of("2.5", "3")).ok());
  expect_problem(inlet_of("0", "3"), "inlets[0].rate", {"must be a positive number"});
  expect_problem(inlet_of("-3", "3"), "inlets[0].rate", {"positive", "-3"});
  expect_problem(inlet_of("1e999", "3"), "inlets[0].rate", {"finite"});
  expect_problem(inlet_of("1", "0"), "inlets[0].count", {"at least 1", "got 0"});
  expect_problem(inlet_of("1", "2.5"), "inlets[0].count", {"must be an integer"});
  expect_problem(with_inlet(R"(, "start": -1)"), "inlets[0].start", {"zero or positive"});
  expect_problem(with_inlet(R"(, "seed": 1.5)"), "inlets[0].seed", {"must be an integer"});
  // Not finite: too large for a double.
  expect_problem(with_inlet(R"(, "start": 1e400)"), "inlets[0].start", {"finite"});
  expect_problem(R"({"inlets": [{"name": "feed", "region": {"min": [0, 0, 0], "max": [1, 1, 1]}, )"
                 R"("rate": 1, "body": {"shape": )" +
                     kBox + "}}]}",
                 "inlets[0]", {"missing required key 'count'"});
}

TEST(ProcessSceneReader, InletRegionIsABoxInsideTheContainer) {
  expect_problem(with_inlet("", R"({"shape": )" + kBox + "}",
                            R"("container": {"min": [-1, -1, -1], "max": [5, 5, 3]})"),
                 "inlets[0].region", {"must lie inside the container", "along z", "[0, 4]"});
  EXPECT_TRUE(read_text(with_inlet("", R"({"shape": )" + kBox + "}",
                                   R"("container": {"min": [0, 0, 0], "max": [4, 4, 4]})"))
                  .ok());
  expect_problem(R"({"inlets": [{"name": "feed", "region": {"min": [0, 0, 0], "max": [1, 0, 1]}, )"
                 R"("rate": 1, "count": 1, "body": {"shape": )" +
                     kBox + "}}]}",
                 "inlets[0].region.max", {"must exceed min", "y"});
}

// A fill's region is held to the container as an inlet's is: copies placed outside it would be
// shoved in by the overlap correction, with a flood of overlap warnings.
TEST(ProcessSceneReader, FillRegionIsInsideTheContainer) {
  const auto with_fill = [](const std::string& container) {
    return R"({"container": )" + container +
           R"(, "fill": [{"name": "g", "count": 4, "region": {"min": [0, 0, 0], "max": [4, 4, 4]},)"
           R"( "body": {"shape": {"type": "box", "size": [0.5, 0.5, 0.5]}}}]})";
  };
  expect_problem(with_fill(R"({"min": [-1, -1, 1], "max": [5, 5, 5]})"), "fill[0].region",
                 {"must lie inside the container", "along z", "[0, 4]", "[1, 5]"});
  EXPECT_TRUE(read_text(with_fill(R"({"min": [0, 0, 0], "max": [4, 4, 4]})")).ok());
}

TEST(ProcessSceneReader, InletBodyKeysThatGoOnTheInlet) {
  expect_problem(with_inlet("", R"({"shape": )" + kBox + R"(, "velocity": [0, 0, -1]})"),
                 "inlets[0].body", {"unknown key 'velocity'", "goes on the inlet"});
  expect_problem(with_inlet("", R"({"shape": )" + kBox + R"(, "position": [0, 0, 0]})"),
                 "inlets[0].body", {"unknown key 'position'", "places its bodies itself"});
  expect_problem(with_inlet("", R"({"shape": )" + kBox + R"(, "name": "x"})"), "inlets[0].body",
                 {"unknown key 'name'", "names and places"});
  expect_problem(with_inlet("", R"({"density": 1})"), "inlets[0].body",
                 {"missing required key 'shape'"});
}

TEST(ProcessSceneReader, InletCopiesCollideWithABodyName) {
  expect_problem(
      with_inlet("", R"({"shape": )" + kBox + "}",
                 R"("bodies": [{"name": "feed_3", "position": [9, 9, 9], "shape": )" + kBox + "}]"),
      "inlets[0].name", {"makes the body name 'feed_3'", "bodies[0]"});
  // Beyond the count, or not a copy's number as written: no collision.
  for (const char* name : {"feed_10", "feed_03", "feed", "feed_x"}) {
    EXPECT_TRUE(read_text(with_inlet("", R"({"shape": )" + kBox + "}",
                                     std::string(R"("bodies": [{"name": ")") + name +
                                         R"(", "position": [9, 9, 9], "shape": )" + kBox + "}]"))
                    .ok())
        << name;
  }
}

TEST(ProcessSceneReader, InletsAndFillsShareNoName) {
  expect_problem(with_inlet("", R"({"shape": )" + kBox + "}",
                            R"("fill": [{"name": "feed", "count": 1, )"
                            R"("region": {"min": [0, 0, 0], "max": [1, 1, 1]}, )"
                            R"("body": {"shape": )" +
                                kBox + "}}]"),
                 "inlets[0].name", {"used by both fill[0] and inlets[0]", "same names"});
  const std::string inlet = R"({"name": "feed", "region": {"min": [0, 0, 0], "max": [1, 1, 1]}, )"
                            R"("rate": 1, "count": 1, "body": {"shape": )" +
                            kBox + "}}";
  expect_problem(R"({"inlets": [)" + inlet + ", " + inlet + "]}", "inlets[1].name",
                 {"used by both inlets[0] and inlets[1]"});
  const std::string fill = R"({"name": "f", "count": 1, "region": {"min": [0, 0, 0], )"
                           R"("max": [1, 1, 1]}, "body": {"shape": )" +
                           kBox + "}}";
  expect_problem(R"({"fill": [)" + fill + ", " + fill + "]}", "fill[1].name",
                 {"used by both fill[0] and fill[1]"});
}

// ---- Outlets -----------------------------------------------------------------------------

TEST(ProcessSceneReader, OutletRegionMustBeABox) {
  expect_problem(with_body("", R"("outlets": [{"name": "bin", )"
                               R"("region": {"min": [0, 0, 0], "max": [1, 1, 0]}}])"),
                 "outlets[0].region.max", {"must exceed min in every component", "z"});
  expect_problem(with_body("", R"("outlets": [{"name": "bin"}])"), "outlets[0]",
                 {"missing required key 'region'"});
  expect_problem(with_body("", R"("outlets": [{"name": "bin", "region": {"min": [0, 0, 0], )"
                               R"("max": [1, 1, 1], "material": "grain"}}])"),
                 "outlets[0].region", {"unknown key 'material'"});
  expect_problem(with_body("", R"("outlets": {"name": "bin"})"), "outlets",
                 {"must be a list of outlets"});
}

// ---- Sensors -----------------------------------------------------------------------------

TEST(ProcessSceneReader, SensorNamesAreUnique) {
  expect_problem(with_body("", R"("sensors": [)"
                               R"({"name": "s", "type": "region", )"
                               R"("region": {"min": [0, 0, 0], "max": [1, 1, 1]}},)"
                               R"({"name": "s", "type": "force", "bodies": ["a"]}])"),
                 "sensors[1].name", {"used by both sensors[0] and sensors[1]", "unique"});
  expect_problem(with_body("", R"("sensors": [{"name": "a,b", "type": "force", "bodies": ["a"]}])"),
                 "sensors[0].name", {"commas"});
}

TEST(ProcessSceneReader, PlaneSensorNeedsANonZeroNormal) {
  expect_problem(with_body("", R"("sensors": [{"name": "s", "type": "plane", )"
                               R"("point": [0, 0, 0], "normal": [0, 0, 0]}])"),
                 "sensors[0].normal", {"must not be zero"});
  expect_problem(
      with_body("", R"("sensors": [{"name": "s", "type": "plane", "normal": [0, 0, 1]}])"),
      "sensors[0]", {"missing required key 'point'"});
}

TEST(ProcessSceneReader, ForceSensorNamesBodiesOrFillCopies) {
  const std::string fill = R"("fill": [{"name": "seed", "count": 5, )"
                           R"("region": {"min": [2, 2, 2], "max": [4, 4, 4]}, )"
                           R"("body": {"shape": {"type": "box", "size": [0.1, 0.1, 0.1]}}}])";
  EXPECT_TRUE(read_text(with_body("", fill + R"(, "sensors": [{"name": "s", "type": "force", )"
                                             R"("bodies": ["a", "seed_0", "seed_4"]}])"))
                  .ok());
  expect_problem(with_body("", fill + R"(, "sensors": [{"name": "s", "type": "force", )"
                                      R"("bodies": ["a", "seed_5"]}])"),
                 "sensors[0].bodies[1]", {"unknown body 'seed_5'"});
  expect_problem(with_body("", R"("sensors": [{"name": "s", "type": "force", "bodies": ["b2"]}])"),
                 "sensors[0].bodies[0]", {"unknown body 'b2'"});
  expect_problem(R"({"bodies": [{"name": "drum", "position": [0, 0, 0], "shape": )" + kBox +
                     R"(}], "sensors": [{"name": "s", "type": "force", "bodies": ["drun"]}]})",
                 "sensors[0].bodies[0]", {"unknown body 'drun'", "did you mean 'drum'"});
  expect_problem(with_body("", R"("sensors": [{"name": "s", "type": "force", "bodies": []}])"),
                 "sensors[0].bodies", {"must be a non-empty list of body names"});
}

// Named twice, a body's force and mass would be counted twice: refused where it is named again.
TEST(ProcessSceneReader, ForceSensorNamesEachBodyOnce) {
  expect_problem(with_body("", R"("sensors": [{"name": "s", "type": "force", )"
                               R"("bodies": ["a", "a"]}])"),
                 "sensors[0].bodies[1]", {"'a' is already named by sensors[0].bodies[0]", "once"});
}

// Inlet copies come and go: a sensor names them as NAME_<k> (k < count) or all of them, and
// any other bodies, by a prefix ending in '*'; a prefix that names no body is refused.
TEST(ProcessSceneReader, ForceSensorNamesInletCopiesAndPrefixes) {
  const auto with_sensor = [](const std::string& bodies) {
    return with_inlet("", R"({"shape": )" + kBox + "}",
                      R"("sensors": [{"name": "s", "type": "force", "bodies": )" + bodies + "}]");
  };
  for (const std::string ok : {R"(["feed_*"])", R"(["feed_9"])", R"(["f*"])", R"(["*"])",
                               R"(["feed_1*"])", R"(["feed_*", "feed_3"])"})
    EXPECT_TRUE(read_text(with_sensor(ok)).ok()) << ok;
  expect_problem(with_sensor(R"(["feed_10"])"), "sensors[0].bodies[0]", {"unknown body 'feed_10'"});
  expect_problem(with_sensor(R"(["feed_10*"])"), "sensors[0].bodies[0]",
                 {"'feed_10*' names no body", "starts with 'feed_10'"});
  expect_problem(with_sensor(R"(["grain*"])"), "sensors[0].bodies[0]", {"names no body"});
  EXPECT_TRUE(sensor_entry_names("feed_*", "feed_12"));
  EXPECT_FALSE(sensor_entry_names("feed_*", "feeder"));
  EXPECT_FALSE(sensor_entry_names("feed_1", "feed_12"));
}

TEST(ProcessSceneReader, RegionSensorNeedsARegion) {
  expect_problem(with_body("", R"("sensors": [{"name": "s", "type": "region"}])"), "sensors[0]",
                 {"missing required key 'region'"});
}

TEST(ProcessSceneReader, SensorKeysOfAnotherType) {
  expect_problem(with_body("", R"("sensors": [{"name": "s", "type": "plane", "point": [0, 0, 0], )"
                               R"("normal": [0, 0, 1], "bodies": ["a"]}])"),
                 "sensors[0]", {"key 'bodies' does not apply to a plane sensor", "'point'"});
  expect_problem(with_body("", R"("sensors": [{"name": "s", "type": "plain"}])"), "sensors[0].type",
                 {"must be one of", "did you mean \"plane\""});
}

}  // namespace test_process_scene_reader
}  // namespace tem
