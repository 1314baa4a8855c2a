// What the public API gives beyond stepping, that `tem check`, `tem info`, `tem mesh`,
// `tem contacts` and `tem run`'s summary are built on (tem/scene_report.hpp,
// tem/mesh_report.hpp, Simulation::warnings, run_statistics, write_contacts_csv): closed-form
// mass properties, the warnings a start earns, the solve's counts, a mesh cube's figures.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "support/tem_process.hpp"
#include "tem/mesh_report.hpp"
#include "tem/scene_report.hpp"
#include "tem/simulation.hpp"

namespace tem {
namespace test_public_reports {

using testing_support::temp_path;

const std::string kScenes = std::string(TEM_SOURCE_DIR) + "/tests/scenes/";

std::string write_file(const std::string& tag, const std::string& text) {
  // The tag's extension last: the mesh reader goes by it.
  const std::size_t dot = tag.rfind('.');
  const std::string path = temp_path(tag.substr(0, dot)) + tag.substr(dot);
  std::ofstream(path) << text;
  return path;
}

bool any_contains(const std::vector<std::string>& lines, const std::string& part) {
  for (const std::string& line : lines)
    if (line.find(part) != std::string::npos) return true;
  return false;
}

// A 0.4 x 0.2 x 0.1 box of density 2 turned 90 degrees about z: its world inertia is the body
// one with x and y swapped; beside it, two fill copies and an inlet of five.
TEST(PublicReports, SceneReportGivesClosedFormMassPropertiesAndTheSceneSize) {
  const std::string scene = write_file("report.json", R"({"time_step": 1e-3, "duration": 0.5,
    "container": {"min": [0, 0, 0], "max": [4, 4, 4]},
    "bodies": [{"name": "slab", "shape": {"type": "box", "size": [0.4, 0.2, 0.1]},
                "density": 2.0, "position": [1, 1, 0.5], "euler_zxz_deg": [90, 0, 0]}],
    "fill": [{"name": "grain", "count": 2, "seed": 3, "region": {"min": [2, 2, 2], "max": [3.5, 3.5, 3.5]},
              "body": {"shape": {"type": "box", "size": [0.1, 0.1, 0.1]}}}],
    "inlets": [{"name": "feed", "count": 5, "rate": 100, "region": {"min": [0.5, 2, 3],
                "max": [1.5, 3, 3.8]}, "body": {"shape": {"type": "box", "size": [0.1, 0.1, 0.1]}}}]})");
  const SceneReport report = report_scene(scene);
  ASSERT_EQ(report.bodies.size(), 3u);  // the slab, then the fill's two copies
  const BodyReport& slab = report.bodies[0];
  EXPECT_EQ(slab.name, "slab");
  const Real m = 2.0 * 0.4 * 0.2 * 0.1;
  EXPECT_NEAR(slab.volume, 0.4 * 0.2 * 0.1, 1e-15);
  EXPECT_NEAR(slab.mass, m, 1e-15);
  EXPECT_NEAR((slab.center_of_mass - Vec3(1, 1, 0.5)).norm(), 0, 1e-15);
  // Body axes: Ixx = m (b^2 + c^2) / 12 with b = 0.2, c = 0.1; Iyy = m (a^2 + c^2) / 12.
  const Real ixx = m * (0.04 + 0.01) / 12, iyy = m * (0.16 + 0.01) / 12,
             izz = m * (0.16 + 0.04) / 12;
  EXPECT_NEAR(slab.inertia(0, 0), iyy, 1e-14 * iyy);  // turned: world x is the body's y
  EXPECT_NEAR(slab.inertia(1, 1), ixx, 1e-14 * iyy);
  EXPECT_NEAR(slab.inertia(2, 2), izz, 1e-14 * iyy);
  EXPECT_NEAR(std::abs(slab.inertia(0, 1)), 0, 1e-14 * iyy);
  EXPECT_EQ(slab.blocks, 1);
  EXPECT_EQ(slab.nodes, 8);
  EXPECT_EQ(slab.elements, 12);  // a box's six faces, two triangles each
  EXPECT_FALSE(slab.mesh.has_value());
  EXPECT_EQ(report.walls, 6);  // the container's faces
  EXPECT_EQ(report.inlets, 1);
  EXPECT_EQ(report.inlet_copies, 5);
  EXPECT_EQ(report.duration, 0.5);
  EXPECT_EQ(report.time_step, 1e-3);
  EXPECT_THROW(report_scene(kScenes + "bad/no_such_scene.json"), SceneLoadError);
}

// The penalty contact's stable limit is a tenth of 2 pi sqrt(m / k) of the lightest body; the
// overlaps at the start are warned of where a simulation starts, not where it resumes.
TEST(PublicReports, WarningsSayWhatTheStartAndTheTimeStepEarn) {
  const Simulation penalty = Simulation::load(kScenes + "penalty_coarse.json");
  const Real limit = 0.1 * 2 * std::numbers::pi * std::sqrt(0.2 * 0.2 * 0.1 / 4000.0);
  std::ostringstream expected;
  expected << "time_step 0.001 is above the penalty contact's stable limit " << limit;
  EXPECT_TRUE(any_contains(penalty.warnings(), expected.str())) << expected.str();
  EXPECT_TRUE(any_contains(report_scene(kScenes + "penalty_coarse.json").warnings,
                           expected.str()));

  Simulation fresh = Simulation::load(kScenes + "overlapping_start.json");
  EXPECT_TRUE(any_contains(fresh.warnings(), "at the start"));
  const std::string checkpoint = temp_path("overlap.bin");
  fresh.step(2);
  fresh.write_checkpoint(checkpoint);
  const Simulation resumed = Simulation::resume(kScenes + "overlapping_start.json", checkpoint);
  EXPECT_FALSE(any_contains(resumed.warnings(), "at the start"));
  std::filesystem::remove(checkpoint);
}

// A box 1e-3 into the floor: one patch of four corner points each step, found before any step
// by write_contacts_csv and counted by run_statistics.
TEST(PublicReports, ContactsBeforeAStepAndTheSolvesCounts) {
  Simulation sim = Simulation::from_json(R"({"time_step": 1e-3, "duration": 1,
    "contact": {"model": "semm", "friction": 0.3, "restitution": 0.0},
    "container": {"min": [0, 0, 0], "max": [10, 10, 1]},
    "bodies": [{"name": "box", "shape": {"type": "box", "size": [0.2, 0.2, 0.1]},
                "position": [5, 5, 0.049]}]})");
  std::ostringstream csv;
  EXPECT_EQ(sim.write_contacts_csv(csv), 1u);
  EXPECT_EQ(sim.step_count(), 0);
  std::istringstream lines(csv.str());
  std::string header, row, more;
  std::getline(lines, header);
  std::getline(lines, row);
  EXPECT_EQ(header, "time,body_a,body_b,px,py,pz,nx,ny,nz,depth,fn,ft");
  // time, body_a, body_b, the point, the normal from the box into the floor, the depth.
  std::vector<std::string> cells;
  std::istringstream fields(row);
  for (std::string cell; std::getline(fields, cell, ',');) cells.push_back(cell);
  ASSERT_EQ(cells.size(), 12u) << row;
  EXPECT_EQ(cells[0] + "," + cells[1] + "," + cells[2], "0,box,wall");
  EXPECT_NEAR(std::stod(cells[3]), 5, 1e-12);
  EXPECT_NEAR(std::stod(cells[4]), 5, 1e-12);
  EXPECT_EQ(cells[6] + "," + cells[7] + "," + cells[8], "0,0,-1");
  EXPECT_NEAR(std::stod(cells[9]), 1e-3, 1e-12);
  EXPECT_FALSE(std::getline(lines, more));

  sim.step(20);
  const RunStatistics s = sim.run_statistics();
  EXPECT_EQ(s.steps, 20);
  EXPECT_EQ(s.patches, 20);
  EXPECT_EQ(s.points, 80);
  EXPECT_GE(s.solver_iterations, 20);  // at least one iteration a step
  EXPECT_GE(s.max_solver_iterations, 1);
  EXPECT_EQ(s.unconverged_steps, 0);
  EXPECT_GT(s.forces, 0);
  EXPECT_EQ(s.sleeping_bodies, 0);
}

// The median of the solver's iterations over the steps, against the counts of each step read
// one step at a time (a box that falls, lands and comes to rest: no iterations in the air, some
// at the landing, few at rest).
TEST(PublicReports, MedianOfTheSolversIterations) {
  Simulation sim = Simulation::from_json(R"({"time_step": 1e-3, "duration": 1,
    "contact": {"model": "semm", "friction": 0.3, "solver": "newton"},
    "container": {"min": [0, 0, 0], "max": [10, 10, 1]},
    "bodies": [{"name": "box", "shape": {"type": "box", "size": [0.2, 0.2, 0.1]},
                "position": [5, 5, 0.2]}]})");
  std::vector<long long> counts;
  long long before = 0;
  for (int k = 0; k < 301; ++k) {
    sim.step(1);
    const long long now = sim.run_statistics().solver_iterations;
    counts.push_back(now - before);
    before = now;
  }
  std::vector<long long> sorted = counts;
  std::sort(sorted.begin(), sorted.end());
  ASSERT_LT(sorted.front(), sorted.back());  // the counts differ from step to step
  EXPECT_EQ(sim.run_statistics().median_solver_iterations, sorted[150]);
  sim.step(1);  // 302 steps: the lower of the two middle ones
  counts.push_back(sim.run_statistics().solver_iterations - before);
  std::sort(counts.begin(), counts.end());
  EXPECT_EQ(sim.run_statistics().median_solver_iterations, counts[150]);
}

// A unit cube mesh scaled by 2: volume 8, one block when cut exactly; an open one is refused.
TEST(PublicReports, MeshReportOfACube) {
  const std::string cube = R"(v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 0 0 1
v 1 0 1
v 1 1 1
v 0 1 1
f 1 3 2
f 1 4 3
f 5 6 7
f 5 7 8
f 1 2 6
f 1 6 5
f 2 3 7
f 2 7 6
f 3 4 8
f 3 8 7
f 4 1 5
f 4 5 8
)";
  const std::string file = write_file("cube.obj", cube);
  const std::string vtu = temp_path("cube_blocks") + ".vtu";
  const MeshReport r = report_mesh(file, MeshCutting::exact, 32, 2.0, vtu);
  EXPECT_EQ(r.vertices, 8);
  EXPECT_EQ(r.faces, 12);
  EXPECT_TRUE(r.closed);
  EXPECT_FALSE(r.turned);
  EXPECT_NEAR(r.volume, 8, 1e-12);
  EXPECT_EQ(r.blocks, 1);
  EXPECT_NEAR(r.blocks_volume, 8, 1e-12);
  EXPECT_NEAR(r.smallest_block_volume, 8, 1e-12);
  EXPECT_NEAR(r.diagonal, 2 * std::sqrt(3.0), 1e-12);
  EXPECT_EQ(r.reflex_edges, 0);
  EXPECT_TRUE(std::filesystem::file_size(vtu) > 0);

  const std::string open = write_file("open_cube.obj", cube.substr(0, cube.rfind("f 4 1 5")));
  EXPECT_THROW(report_mesh(open, MeshCutting::approximate, 8, 1.0), MeshLoadError);
  for (const std::string& f : {file, vtu, open}) std::filesystem::remove(f);
}

}  // namespace test_public_reports
}  // namespace tem
