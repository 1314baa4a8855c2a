// Reading a scene file (JSON, docs/scene_format.md) into a SceneDef.
//
// The reader is meant for people editing scene files by hand, so it never stops at the first
// mistake and never throws for bad input: it walks the whole document, collects every problem
// with the JSON path where it lies (`bodies[1].shape.radius`) and a reason in plain words, and
// leaves the defaults in place wherever a value was bad. Geometric problems that need the
// shapes built (a degenerate point cloud, a non-convex block) are left to build_model().
#pragma once

#include <string>
#include <vector>

#include "tem/scene_def.hpp"

namespace tem {

struct SceneProblem {
  // JSON path of the offending value: `time_step`, `bodies[1].shape.radius`, `(root)` for the
  // document as a whole; empty for problems with the file itself (missing, syntax error).
  std::string path;
  std::string message;
};

struct SceneReadResult {
  SceneDef scene;  // complete only when ok(); otherwise defaults stand in for bad values
  std::vector<SceneProblem> problems;
  bool ok() const { return problems.empty(); }
};

// Reads and validates a scene file, then loads its meshes (load_scene_meshes). `scene.source` is
// set to `filename`.
SceneReadResult read_scene_file(const std::string& filename);

// Same, from text already in memory, without touching any file: mesh shapes are parsed but not
// loaded. `source_name` goes into `scene.source`.
SceneReadResult read_scene_text(const std::string& text, const std::string& source_name);

// For a scene read without problems: reads, checks and cuts the file of every mesh shape (each
// relative to the directory of `scene.source`, the working directory when it has none) and
// fills its `file_path` and `mesh`. A mesh's problem is reported at `...shape.file`, its message
// naming the file, the face or vertex and why.
void load_scene_meshes(SceneReadResult& result);

// One line for the user: "FILE: PATH: reason", or "FILE: reason" when the path is empty.
std::string format_problem(const std::string& source_name, const SceneProblem& problem);

// Orientation conventions of the scene file. Angles in degrees; quarter turns are exact, so an
// axis-aligned pose written as 90 degrees gives exactly axis-aligned faces.
Mat3 rotation_from_euler_zxz_deg(const Vec3& angles_deg);
// [w, x, y, z] of a unit quaternion (rounding off its norm is removed), body to world.
Mat3 rotation_from_quaternion(Real w, Real x, Real y, Real z);

}  // namespace tem
