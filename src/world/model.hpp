// The Model: everything about a simulation that never changes after loading (shapes, blocks,
// elements, mass properties, walls, settings), built from a SceneDef. The State (dynamics/
// body_state.hpp) holds what a step changes.
#pragma once

#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "dynamics/body_state.hpp"
#include "geometry/block.hpp"
#include "tem/scene_def.hpp"

namespace tem {

// One block placed in a body: x_body = rotation * x_block + offset, body frame origin at the
// body's centre of mass (B^c and t^c of eq. 7).
struct BlockInstance {
  int block;  // index into Model::blocks
  Mat3 rotation;
  Vec3 offset;
  std::string path;  // JSON path of the shape that made it
};

struct Body {
  std::string name;
  Real density = 1;
  Real volume = 0;
  RigidInertia inertia;  // mass, A and A^-1 in body axes about the centre of mass
  std::vector<BlockInstance> blocks;
  // Where the scene's body-frame origin lies in the body frame (the centre of mass is the
  // origin here): the scene's `position` places that point.
  Vec3 origin_offset = Vec3::Zero();
  bool fixed = false;
  // How it starts (initial_state): the world position of the scene's body-frame origin, the
  // attitude (body to world), the velocity of the centre of mass and the angular velocity, both
  // in world axes. From the body's scene entry, or chosen by its fill.
  Vec3 start_position = Vec3::Zero();
  Mat3 start_rotation = Mat3::Identity();
  Vec3 start_velocity = Vec3::Zero();
  Vec3 start_angular_velocity = Vec3::Zero();
  // Granular processes: the body's material (an index into Model::material_names; 0 is none),
  // its prescribed motion (a kinematic body: `fixed` is false and it is never pushed), and the
  // time it is taken away (infinity: never).
  int material = 0;
  std::optional<MotionDef> motion;
  Real removed_at = std::numeric_limits<Real>::infinity();
  // Force sensors (indices into scene.sensors) that count this body's contact force.
  std::vector<int> force_sensors;
  // Whether its blocks are its own (a copy with a size factor), to be freed when it leaves.
  bool owns_blocks = false;
  // Bodies that move only as they are told: fixed ones and those with a prescribed motion.
  bool driven() const { return fixed || motion.has_value(); }
};

struct Wall {
  Vec3 point;
  Vec3 normal;  // unit, into the space where bodies live
  int material = 0;
  Real removed_at = std::numeric_limits<Real>::infinity();  // takes part while time < this
};

// The contact coefficients of a pair of materials.
struct PairCoefficients {
  Real friction = 0;
  Real restitution = 0;
  Real rolling_resistance = 0;
};

// What never changes after loading, and the live bodies' constant data.
//
// Bodies come and go during a run (inlets, outlets, removal at a time: src/process/). Their
// constant data (blocks, inertia, material, name) stays here in `bodies`, parallel to the
// State's, because every stage reads it by body index; the population stage (the only code
// that changes it) keeps the two aligned, and State::tags says who each body is, so a checkpoint
// rebuilds `bodies` from the scene and the State alone (docs/processes.md).
struct Model {
  SceneDef scene;  // the definitions it was built from, defaults filled in
  std::vector<Block> blocks;
  std::vector<int> free_blocks;       // slots of `blocks` left by copies that have gone
  // The live bodies: at the start the scene's `bodies`, then those of each `fill`; then as
  // inlets add and outlets remove them.
  std::vector<Body> bodies;
  std::vector<Body> inlet_templates;  // one per inlet: the copy at size factor 1
  // Counts changes of `bodies`: caches keyed on the bodies (the broad phase's) rebuild when it
  // moves.
  long long population_version = 0;
  bool any_motion = false;  // some body has a prescribed motion
  // Bodies can come or go: the scene has inlets, outlets or a body with removed_at.
  bool bodies_come_and_go = false;
  std::vector<Wall> walls;            // the container's six inner faces, then the scene's `walls`
  std::vector<std::string> warnings;  // accepted defects, e.g. a non-convex block allowed
  // Materials: index 0 stands for "no material" (contact.friction, contact.restitution, no
  // rolling resistance), then the scene's materials in name order. `pairs` holds the
  // coefficients of every pair, material_count() squared, symmetric.
  std::vector<std::string> material_names{""};
  std::vector<PairCoefficients> pairs;
  int material_count() const { return static_cast<int>(material_names.size()); }
  const PairCoefficients& coefficients(int material_a, int material_b) const {
    return pairs[static_cast<size_t>(material_a) * material_names.size() + material_b];
  }
};

// Builds blocks, elements and mass properties. Throws SceneError naming the JSON path of the
// shape or body at fault.
Model build_model(const SceneDef& scene);

// One body from its def, its blocks added to model.blocks, every length multiplied by `scale`
// (a copy's size factor: 1 leaves the shape as it is, bit for bit).
Body build_body(const BodyDef& def, Model& model, Real scale = 1);
// Puts a block into a free slot of model.blocks, or at the end; its index.
int add_block(Model& model, Block block);
// Fills each body's force_sensors from the scene's sensors.
void assign_force_sensors(Model& model);
// The force sensors (indices into scene.sensors) that name a body called `name`, each once.
std::vector<int> force_sensors_naming(const SceneDef& scene, const std::string& name);

// The block of a body's `instance`-th block instance.
inline const Block& block_of(const Model& model, int body, int instance) {
  return model.blocks[model.bodies[body].blocks[instance].block];
}

// A body's size: the largest distance from its centre of mass that any of its nodes can have
// (block offset + block bounding radius). Contact tolerances are fractions of it.
Real body_size(const Model& model, int body);
Real body_size(const Model& model, const Body& body);

// The state at time 0: the scene's poses and velocities, centres of mass in world space.
State initial_state(const Model& model);

}  // namespace tem
