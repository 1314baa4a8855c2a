// The `tem` program as a user runs it (TEM_BINARY): `info --json` against closed forms,
// `check` on good scenes, on every broken scene of tests/scenes/bad/ and on scenes only the
// core can reject (geometry), `--version` and help. Every run is a few milliseconds.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "io/scene_reader.hpp"
#include "support/tem_process.hpp"

namespace tem {
namespace test_cli {

using testing_support::contains;
using testing_support::run_tem;
using testing_support::slurp;
using testing_support::TemRun;

const std::string kSource = TEM_SOURCE_DIR;

Vec3 vec3(const nlohmann::json& j) { return Vec3(j[0], j[1], j[2]); }

Mat3 mat3(const nlohmann::json& j) {
  Mat3 m;
  for (int r = 0; r < 3; ++r) m.row(r) = vec3(j[r]).transpose();
  return m;
}

// Volume of a regular hexagonal prism of circumradius r and height h: (3 sqrt(3) / 2) r^2 h.
Real hexagonal_prism_volume(Real r, Real h) { return 1.5 * std::sqrt(3.0) * r * r * h; }

// Inertia of a regular n-gon prism (n >= 3) of mass m about its centroid: the polygon's second
// moment is isotropic in its plane, (m / 24) r^2 (1 + 2 cos^2(pi / n)) per in-plane axis, which
// for the hexagon gives 5/24 m r^2; about the symmetry axis twice that.
void hexagonal_prism_inertia(Real m, Real r, Real h, Real* axial, Real* transverse) {
  *axial = 5.0 / 12.0 * m * r * r;
  *transverse = 5.0 / 24.0 * m * r * r + m * h * h / 12.0;
}

struct InfoBody {
  std::string name;
  Real volume, mass;
  Vec3 center;
  Mat3 inertia;
};

std::vector<InfoBody> info_json(const std::string& scene, std::string* raw_out = nullptr) {
  const TemRun run = run_tem("info --json '" + scene + "'");
  EXPECT_EQ(run.status, 0) << run.err;
  if (raw_out) *raw_out = run.out;
  std::vector<InfoBody> bodies;
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(run.out);  // throws unless stdout is exactly one JSON value
  } catch (const std::exception& e) {
    ADD_FAILURE() << "stdout is not one JSON object: " << e.what() << "\n" << run.out;
    return bodies;
  }
  EXPECT_EQ(j.size(), 1u);
  for (const auto& b : j.at("bodies")) {
    bodies.push_back({b.at("name"), b.at("volume"), b.at("mass"), vec3(b.at("center_of_mass")),
                      mat3(b.at("inertia"))});
  }
  return bodies;
}

TEST(Cli, InfoJsonOfThePaperCoin) {
  const std::string scene = kSource + "/scenes/paper/coin.json";
  const SceneReadResult def = read_scene_file(scene);
  ASSERT_TRUE(def.ok());
  const BodyDef& coin = def.scene.bodies.at(0);
  std::string out;
  const std::vector<InfoBody> bodies = info_json(scene, &out);
  ASSERT_EQ(bodies.size(), 1u);
  const InfoBody& b = bodies[0];
  EXPECT_EQ(b.name, "coin");

  const Real r = coin.shape.radius, h = coin.shape.height;
  const Real volume = hexagonal_prism_volume(r, h);
  EXPECT_NEAR(b.volume, volume, 1e-12 * volume);
  EXPECT_NEAR(b.mass, coin.density * b.volume, 1e-14 * b.mass);
  // A prism's centre of mass is the origin of its frame, which `position` places.
  EXPECT_LE((b.center - coin.position).norm(), 1e-12);

  // Inertia in world axes at the initial pose: g A g^T, symmetry axis along body y.
  Real axial, transverse;
  hexagonal_prism_inertia(b.mass, r, h, &axial, &transverse);
  const Mat3 body_inertia = Vec3(transverse, axial, transverse).asDiagonal();
  const Mat3 expected = coin.rotation * body_inertia * coin.rotation.transpose();
  EXPECT_LE((b.inertia - expected).norm(), 1e-12 * expected.norm()) << "got\n"
                                                                    << b.inertia << "\nexpected\n"
                                                                    << expected;

  // Full precision: numbers read back from the text as written, with up to 17 digits.
  EXPECT_TRUE(contains(out, "\"volume\":"));
  EXPECT_EQ(out.back(), '\n');
}

TEST(Cli, InfoJsonOfThePaperRingAndColumn) {
  const std::string scene = kSource + "/scenes/paper/ring_column.json";
  const SceneReadResult def = read_scene_file(scene);
  ASSERT_TRUE(def.ok());
  const std::vector<InfoBody> bodies = info_json(scene);
  ASSERT_EQ(bodies.size(), 2u);
  EXPECT_EQ(bodies[0].name, "ring");
  EXPECT_EQ(bodies[1].name, "column");
  for (std::size_t i = 0; i < 2; ++i) {
    SCOPED_TRACE(bodies[i].name);
    const BodyDef& d = def.scene.bodies[i];
    EXPECT_GT(bodies[i].volume, 0);
    EXPECT_NEAR(bodies[i].mass, d.density * bodies[i].volume, 1e-14 * bodies[i].mass);
    // Both shapes are symmetric about their frame's origin.
    EXPECT_LE((bodies[i].center - d.position).norm(), 1e-12);
    const Mat3& inertia = bodies[i].inertia;
    EXPECT_LE((inertia - inertia.transpose()).norm(), 1e-12 * inertia.norm());
    EXPECT_GT(inertia.ldlt().vectorD().minCoeff(), 0);
  }
  const BodyDef& column = def.scene.bodies[1];
  const Real volume = hexagonal_prism_volume(column.shape.radius, column.shape.height);
  EXPECT_NEAR(bodies[1].volume, volume, 1e-12 * volume);
}

TEST(Cli, InfoPrintsATable) {
  const TemRun run = run_tem("info '" + kSource + "/scenes/paper/coin.json'");
  EXPECT_EQ(run.status, 0) << run.err;
  for (const char* part :
       {"coin", "blocks 1", "volume", "mass", "centre of mass", "inertia", "principal moments"}) {
    EXPECT_TRUE(contains(run.out, part)) << part << " missing in\n" << run.out;
  }
}

TEST(Cli, CheckAcceptsGoodScenes) {
  for (const std::string scene :
       {"scenes/paper/coin.json", "scenes/paper/ring_column.json", "tests/scenes/full.json"}) {
    const TemRun run = run_tem("check '" + kSource + "/" + scene + "'");
    EXPECT_EQ(run.status, 0) << scene << "\n" << run.err;
    EXPECT_TRUE(contains(run.out, scene + ": ok (")) << run.out;
  }
}

// The same table as the reader's test: every broken scene, through the program.
TEST(Cli, CheckRejectsEveryBrokenScene) {
  std::ifstream table(kSource + "/tests/scenes/bad/expected.tsv");
  ASSERT_TRUE(table);
  std::map<std::string, std::vector<std::pair<std::string, std::string>>> expected;
  std::string line;
  while (std::getline(table, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    std::string file, path, fragment;
    std::getline(fields, file, '\t');
    std::getline(fields, path, '\t');
    std::getline(fields, fragment);
    expected[file].push_back({path, fragment});
  }
  ASSERT_GE(expected.size(), 30u);
  for (const auto& [file, problems] : expected) {
    SCOPED_TRACE(file);
    const std::string scene = kSource + "/tests/scenes/bad/" + file;
    const TemRun run = run_tem("check '" + scene + "'");
    EXPECT_EQ(run.status, 1);
    EXPECT_TRUE(run.out.empty()) << run.out;
    for (const auto& [path, fragment] : problems) {
      // "FILE: PATH: reason", or "FILE: reason" for problems with the file itself.
      const std::string prefix = scene + ": " + (path == "-" ? "" : path + ": ");
      bool found = false;
      std::istringstream lines(run.err);
      for (std::string message; std::getline(lines, message);) {
        found = found || (message.rfind(prefix, 0) == 0 && contains(message, fragment));
      }
      EXPECT_TRUE(found) << "expected a line " << prefix << "..." << fragment << "...\n" << run.err;
    }
  }
}

// Scenes the reader accepts but the core cannot build: the message still names the shape.
TEST(Cli, CheckReportsGeometricProblemsWithTheirPath) {
  const std::pair<const char*, const char*> cases[] = {
      {"coplanar_points.json", "bodies[0].shape"},
      {"interior_point.json", "bodies[0].shape"},
      {"ring_nonconvex_blocks.json", "bodies[0].shape"},
      {"fill_too_dense.json", "fill[0].count: only "},
      {"inlet_too_small.json", "inlets[0].region: is too small for one copy"}};
  for (const auto& [file, where] : cases) {
    SCOPED_TRACE(file);
    const std::string scene = kSource + "/tests/scenes/bad_geometry/" + file;
    ASSERT_TRUE(read_scene_file(scene).ok());
    const TemRun run = run_tem("check '" + scene + "'");
    EXPECT_EQ(run.status, 1);
    EXPECT_TRUE(contains(run.err, scene + ": " + where)) << run.err;
  }
}

TEST(Cli, InfoOnABrokenSceneFailsWithNothingOnStdout) {
  const std::string scene = kSource + "/tests/scenes/bad/zero_height.json";
  const TemRun run = run_tem("info --json '" + scene + "'");
  EXPECT_EQ(run.status, 1);
  EXPECT_TRUE(run.out.empty()) << run.out;
  EXPECT_TRUE(contains(run.err, scene + ": bodies[0].shape.height: must be a positive number"))
      << run.err;
}

TEST(Cli, MissingFileSaysSo) {
  for (const std::string command : {"check", "info"}) {
    const TemRun run = run_tem(command + " no_such_scene.json");
    EXPECT_EQ(run.status, 1);
    EXPECT_TRUE(contains(run.err, "no_such_scene.json: no such file")) << run.err;
  }
}

TEST(Cli, Version) {
  const TemRun run = run_tem("--version");
  EXPECT_EQ(run.status, 0);
  EXPECT_EQ(run.out, std::string("tem ") + TEM_VERSION + "\n");
}

TEST(Cli, HelpListsTheCommands) {
  for (const std::string args : {"help", "--help"}) {
    const TemRun run = run_tem(args);
    EXPECT_EQ(run.status, 0) << args;
    EXPECT_TRUE(contains(run.out, "info")) << run.out;
    EXPECT_TRUE(contains(run.out, "check")) << run.out;
  }
}

TEST(Cli, BadCommandLinesAreUsageErrors) {
  EXPECT_EQ(run_tem("").status, 2);
  EXPECT_EQ(run_tem("frobnicate").status, 2);
  EXPECT_EQ(run_tem("info").status, 2);  // no scene file
  EXPECT_EQ(run_tem("check a.json b.json").status, 2);
}

// `tem contacts`: a cube pushed 0.003 into the wall x = 0 and 0.005 into the floor, with a lid
// resting 0.001 deep on it: three patches as contacts.csv rows, normals from body_a into body_b,
// the depths as placed, forces 0 (none computed).
TEST(Cli, ContactsOfTheInitialState) {
  const std::string scene = kSource + "/tests/scenes/cube_in_corner.json";
  const TemRun run = run_tem("contacts '" + scene + "'");
  ASSERT_EQ(run.status, 0) << run.err;
  std::istringstream lines(run.out);
  std::string header;
  std::getline(lines, header);
  EXPECT_EQ(header, "time,body_a,body_b,px,py,pz,nx,ny,nz,depth,fn,ft");
  std::vector<std::vector<std::string>> rows;
  for (std::string line; std::getline(lines, line);) {
    std::vector<std::string> cells;
    std::istringstream row(line);
    for (std::string cell; std::getline(row, cell, ',');) cells.push_back(cell);
    ASSERT_EQ(cells.size(), 12u) << line;
    rows.push_back(cells);
  }
  ASSERT_EQ(rows.size(), 3u) << run.out;
  auto normal = [](const std::vector<std::string>& r) {
    return Vec3(std::stod(r[6]), std::stod(r[7]), std::stod(r[8]));
  };
  // Body pairs first, then walls in the container's order (x = 0 is wall 0, z = 0 wall 4).
  EXPECT_EQ(rows[0][1] + "," + rows[0][2], "cube,lid");
  EXPECT_LT((normal(rows[0]) - Vec3(0, 0, 1)).norm(), 1e-12);
  EXPECT_NEAR(std::stod(rows[0][9]), 0.001, 1e-12);
  EXPECT_EQ(rows[1][1] + "," + rows[1][2], "cube,wall");
  EXPECT_LT((normal(rows[1]) - Vec3(-1, 0, 0)).norm(), 1e-12);
  EXPECT_NEAR(std::stod(rows[1][9]), 0.003, 1e-12);
  EXPECT_EQ(rows[2][1] + "," + rows[2][2], "cube,wall");
  EXPECT_LT((normal(rows[2]) - Vec3(0, 0, -1)).norm(), 1e-12);
  EXPECT_NEAR(std::stod(rows[2][9]), 0.005, 1e-12);
  for (const auto& r : rows) {
    EXPECT_EQ(r[0], "0");
    EXPECT_EQ(r[10], "0");
    EXPECT_EQ(r[11], "0");
  }

  // --out writes the same rows to a file.
  const std::string file = testing::TempDir() + "tem_contacts_" + std::to_string(getpid());
  const TemRun to_file = run_tem("contacts '" + scene + "' --out '" + file + "'");
  EXPECT_EQ(to_file.status, 0) << to_file.err;
  EXPECT_EQ(slurp(file), run.out);
  std::filesystem::remove(file);
}

// `tem run`: a box dropped 1 cm onto the floor for 0.05 s, output every 0.01 s: the four files
// with the interface's headers, one row per body per output time (t = 0 and 5 more), the same
// bytes on a second run, and a scene.json that reads back.
TEST(Cli, RunWritesTheResultFiles) {
  const std::string scene = kSource + "/tests/scenes/drop_box.json";
  const std::string dir = testing::TempDir() + "tem_run_" + std::to_string(getpid());
  const TemRun run = run_tem("run '" + scene + "' --out '" + dir + "' --contacts");
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_TRUE(contains(run.err, "steps/s")) << run.err;
  using testing_support::lines;
  const auto bodies = lines(slurp(dir + "/bodies.csv"));
  const auto energy = lines(slurp(dir + "/energy.csv"));
  const auto contacts = lines(slurp(dir + "/contacts.csv"));
  ASSERT_EQ(bodies.size(), 7u);
  EXPECT_EQ(bodies[0], "time,body,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz");
  EXPECT_EQ(bodies[1].substr(0, 6), "0,box,");
  ASSERT_EQ(energy.size(), 7u);
  EXPECT_EQ(energy[0], "time,kinetic,potential,total,contacts,max_depth");  // no motion
  EXPECT_EQ(energy[2].substr(0, 5), "0.01,");  // the decimal time, not 100 * 1e-4
  EXPECT_EQ(energy.back().substr(0, 5), "0.05,");
  ASSERT_GE(contacts.size(), 2u);  // it lands within 0.05 s
  EXPECT_EQ(contacts[0], "time,body_a,body_b,px,py,pz,nx,ny,nz,depth,fn,ft");
  EXPECT_EQ(contacts[1].find(",box,wall,") != std::string::npos, true) << contacts[1];
  const SceneReadResult again = read_scene_file(dir + "/scene.json");
  EXPECT_TRUE(again.ok());

  const std::string dir2 = dir + "_again";
  const TemRun second = run_tem("run '" + scene + "' --out '" + dir2 + "' --hash");
  ASSERT_EQ(second.status, 0);
  EXPECT_EQ(slurp(dir2 + "/bodies.csv"), slurp(dir + "/bodies.csv"));
  // --hash: the last line, 16 hex digits, the same on a third run.
  const auto hash_line = [&](const TemRun& r) {
    const auto all = lines(r.out);
    return all.empty() ? std::string() : all.back();
  };
  EXPECT_EQ(hash_line(second).substr(0, 6), "hash: ");
  EXPECT_EQ(hash_line(second).size(), 6u + 16u);
  EXPECT_EQ(hash_line(run_tem("run '" + scene + "' --out '" + dir2 + "' --hash")),
            hash_line(second));
  std::filesystem::remove_all(dir2);
  std::filesystem::remove_all(dir);
  std::filesystem::remove_all(dir2);
}

// A new run into a folder that holds an earlier run's results: the earlier run's files that the
// new run does not write (here contacts.csv, sensors.csv, ParaView frames) are removed and
// named, so none passes for the new run's; a file TEM did not write (a user's notes.csv, a
// contacts.csv of another header) stays.
TEST(Cli, ANewRunRemovesAnEarlierRunsFilesItDoesNotWrite) {
  const std::string dir = testing::TempDir() + "tem_stale_" + std::to_string(getpid());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir + "/out");
  const std::string box = R"("time_step": 1e-3, "duration": 0.02,
      "walls": [{"point": [0, 0, 0], "normal": [0, 0, 1]}],
      "bodies": [{"name": "box", "shape": {"type": "box", "size": [1, 1, 1]},
                  "position": [0, 0, 0.6]}])";
  std::ofstream(dir + "/first.json")
      << "{" << box << R"(, "output": {"interval": 0.01, "paraview": true},
          "sensors": [{"name": "s", "type": "force", "bodies": ["box"]}]})";
  std::ofstream(dir + "/second.json") << "{" << box << "}";
  const std::string out = " --out '" + dir + "/out'";
  const TemRun first = run_tem("run '" + dir + "/first.json'" + out + " --contacts");
  ASSERT_EQ(first.status, 0) << first.err;
  EXPECT_TRUE(contains(first.err, "(bodies.csv, energy.csv, contacts.csv, sensors.csv, scene.json, "
                                  "checkpoint.bin, tem.pvd and paraview/ for ParaView)"))
      << first.err;
  std::ofstream(dir + "/out/notes.csv") << "time,body\n";
  ASSERT_TRUE(std::filesystem::exists(dir + "/out/paraview"));
  const TemRun second = run_tem("run '" + dir + "/second.json'" + out);
  ASSERT_EQ(second.status, 0) << second.err;
  EXPECT_TRUE(contains(second.err, "removed an earlier run's files from")) << second.err;
  EXPECT_TRUE(contains(second.err, "contacts.csv, sensors.csv, tem.pvd, paraview/ (6 frame files)"))
      << second.err;
  for (const char* gone : {"contacts.csv", "sensors.csv", "tem.pvd", "paraview"})
    EXPECT_FALSE(std::filesystem::exists(dir + "/out/" + gone)) << gone;
  EXPECT_TRUE(std::filesystem::exists(dir + "/out/notes.csv"));
  // Run again: nothing of an earlier run is left to remove, and nothing is said; a contacts.csv
  // TEM did not write (another header) is kept.
  std::ofstream(dir + "/out/contacts.csv") << "time,a,b\n";
  const TemRun third = run_tem("run '" + dir + "/second.json'" + out);
  ASSERT_EQ(third.status, 0) << third.err;
  EXPECT_FALSE(contains(third.err, "removed")) << third.err;
  EXPECT_EQ(slurp(dir + "/out/contacts.csv"), "time,a,b\n");
  std::filesystem::remove_all(dir);
}

// --threads: a negative count is a usage error that says what is allowed (not CLI11's range of
// 300-digit bounds); more threads than cores run, with a warning.
TEST(Cli, ThreadsOptionSaysWhatItTakes) {
  const std::string scene = kSource + "/tests/scenes/drop_box.json";
  const std::string dir = testing::TempDir() + "tem_threads_opt_" + std::to_string(getpid());
  const TemRun negative = run_tem("run '" + scene + "' --out '" + dir + "' --threads -1");
  EXPECT_EQ(negative.status, 2);
  EXPECT_TRUE(contains(negative.err, "--threads: must be 0 (one thread per core) or a number of "
                                     "threads, got -1"))
      << negative.err;
  EXPECT_LT(negative.err.size(), 200u) << negative.err;
  const TemRun many = run_tem("run '" + scene + "' --out '" + dir + "' --threads 10000");
  EXPECT_EQ(many.status, 0) << many.err;
  EXPECT_TRUE(contains(many.err, "--threads 10000 is more than this machine's")) << many.err;
  std::filesystem::remove_all(dir);
}

// A penalty scene whose time step is above the contact's stable limit runs, with a warning that
// says so and what limit to use.
TEST(Cli, RunWarnsOfAPenaltyTimeStepAboveItsLimit) {
  const std::string scene = kSource + "/tests/scenes/penalty_coarse.json";
  const std::string dir = testing::TempDir() + "tem_pen_" + std::to_string(getpid());
  const TemRun run = run_tem("run '" + scene + "' --out '" + dir + "'");
  EXPECT_EQ(run.status, 0) << run.err;
  EXPECT_TRUE(contains(run.err, "warning: time_step")) << run.err;
  std::filesystem::remove_all(dir);
}

// Bodies placed into each other or into a wall are named, by `check` and by `run`, deepest
// first; bodies that merely touch (1e-4 of their size) are not.
TEST(Cli, DeepInitialOverlapIsNamed) {
  const std::string scene = kSource + "/tests/scenes/overlapping_start.json";
  const TemRun check = run_tem("check '" + scene + "'");
  EXPECT_EQ(check.status, 0) << check.err;
  const auto warnings = testing_support::lines(check.err);
  ASSERT_EQ(warnings.size(), 2u) << check.err;
  EXPECT_TRUE(contains(warnings[0], "warning: bodies 'lower' and 'upper' overlap by 0.05 ("))
      << warnings[0];
  EXPECT_TRUE(contains(warnings[1], "warning: body 'sunk' and the container's z min face overlap "
                                    "by 0.02 ("))
      << warnings[1];
  const std::string dir = testing::TempDir() + "tem_overlap_" + std::to_string(getpid());
  const TemRun run = run_tem("run '" + scene + "' --out '" + dir + "'");
  EXPECT_EQ(run.status, 0) << run.err;
  EXPECT_TRUE(contains(run.err, "warning: bodies 'lower' and 'upper' overlap")) << run.err;
  EXPECT_FALSE(contains(run.err, "touching")) << run.err;
  std::filesystem::remove_all(dir);
}

// A state that stops being finite (here: an angular velocity of 1e300 rad/s, valid input that
// overflows the integrator) ends the run with status 3, a message naming the body and the step,
// and the rows written before it intact.
TEST(Cli, NonFiniteStateStopsTheRunNamingBodyAndStep) {
  const std::string scene = kSource + "/tests/scenes/blows_up.json";
  const std::string dir = testing::TempDir() + "tem_nonfinite_" + std::to_string(getpid());
  const TemRun run = run_tem("run '" + scene + "' --out '" + dir + "'");
  EXPECT_EQ(run.status, 3) << run.err;
  EXPECT_TRUE(contains(run.err, "the state of body 'spinner' stopped being finite at step 1 "))
      << run.err;
  const auto bodies = testing_support::lines(slurp(dir + "/bodies.csv"));
  ASSERT_EQ(bodies.size(), 3u);  // header and the two bodies at t = 0
  EXPECT_EQ(bodies[2].substr(0, 10), "0,spinner,");
  std::filesystem::remove_all(dir);
}

// The narrow phase shared among threads gives the same bytes as one thread: 40 coins poured into
// a box (tests/scenes/small_pile.json, over a hundred pairs per step once they land, several
// runs of pairs per thread).
TEST(Cli, ThreadsGiveBitIdenticalResults) {
  const std::string scene = kSource + "/tests/scenes/small_pile.json";
  const std::string dir = testing::TempDir() + "tem_threads_" + std::to_string(getpid());
  const TemRun one = run_tem("run '" + scene + "' --out '" + dir + "_1' --hash --threads 1");
  const TemRun two = run_tem("run '" + scene + "' --out '" + dir + "_2' --hash --threads 2");
  ASSERT_EQ(one.status, 0) << one.err;
  ASSERT_EQ(two.status, 0) << two.err;
  EXPECT_EQ(testing_support::lines(one.out).back(), testing_support::lines(two.out).back());
  const std::string bodies = slurp(dir + "_1/bodies.csv");
  EXPECT_TRUE(bodies == slurp(dir + "_2/bodies.csv"));
  EXPECT_GT(testing_support::lines(bodies).size(), 40u * 9);
  // The coins do land: contact patches in the last rows.
  std::istringstream last(testing_support::lines(slurp(dir + "_1/energy.csv")).back());
  std::string field;
  for (int column = 0; column < 5; ++column) std::getline(last, field, ',');  // `contacts`
  EXPECT_GT(std::stoi(field), 20);
  std::filesystem::remove_all(dir + "_1");
  std::filesystem::remove_all(dir + "_2");
}

}  // namespace test_cli
}  // namespace tem
