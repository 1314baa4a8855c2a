// A scene read and built but not simulated: what it holds, its warnings and each body's mass
// properties at its start, as `tem check` and `tem info` print them.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "tem/simulation.hpp"  // SceneLoadError
#include "tem/types.hpp"

namespace tem {

// A body made from one mesh shape, checked against the mesh's own surface integrals. Exact
// cutting: the body's volume, centre and inertia come from its blocks and equal the mesh's to
// rounding. Approximate: they are the mesh's own (the blocks cover more than the mesh and only
// shape the contacts), and blocks_volume says by how much the blocks cover more.
struct MeshBodyCheck {
  std::string file;
  bool exact = false;  // cut exactly (blocks whose union is the mesh) or approximately
  int faces = 0;
  int blocks = 0;
  Real mesh_volume = 0;
  Real blocks_volume = 0;
  Real volume_error = 0;   // |V_body - V_mesh| / V_mesh
  Real centre_error = 0;   // |c_body - c_mesh| / the body's size
  Real inertia_error = 0;  // largest entry of |J_body - J_mesh| / largest entry of J_mesh
};

struct BodyReport {
  std::string name;
  bool fixed = false;
  int blocks = 0, nodes = 0, elements = 0;
  Real volume = 0;
  Real mass = 0;
  Vec3 center_of_mass = Vec3::Zero();  // world, at the start
  Mat3 inertia = Mat3::Zero();         // about the centre of mass, world axes, at the start
  std::optional<MeshBodyCheck> mesh;   // a body of one mesh shape
};

struct SceneReport {
  // As Simulation::warnings() of the scene loaded fresh: accepted defects, then bodies that
  // overlap deeply at the start.
  std::vector<std::string> warnings;
  std::vector<BodyReport> bodies;  // the scene's bodies, then the copies of each fill
  int blocks = 0;                  // distinct convex blocks the bodies are made of
  int walls = 0;                   // the container's faces and the scene's walls
  int inlets = 0;
  long long inlet_copies = 0;  // bodies still to come from the inlets, summed over them
  Real duration = 0, time_step = 0;
};

// Reads and builds the scene in `scene_file`. Bad input throws SceneLoadError
// (tem/simulation.hpp) with every problem found, one per line.
SceneReport report_scene(const std::string& scene_file);

}  // namespace tem
