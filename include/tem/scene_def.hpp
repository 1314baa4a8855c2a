// The scene as plain definitions with defaults, one field per key of the scene file
// (docs/scene_format.md). The JSON reader in src/io fills these; the core builds a Model from
// them and never sees JSON. Every def remembers its JSON path so that errors found later (a
// degenerate block, say) can still name where in the file the problem is.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "tem/process_def.hpp"
#include "tem/types.hpp"

namespace tem {

enum class ShapeType { prism, ring, box, convex, compound, mesh };
// How a mesh shape is cut into convex blocks: exactly (the blocks' union is the mesh) or
// approximately (few blocks, each the convex hull of a part of the mesh).
enum class MeshCutting { exact, approximate };

// A mesh shape once read, checked and cut (src/mesh/mesh_body.hpp); shared by every body, and
// every copy made by `fill`, that uses the same file with the same settings.
struct MeshBody;
enum class Axis { x, y, z };
enum class IntegratorKind { default_, paper };
enum class ContactModel { semm, semm_paper, penalty };
// How a patch's normal and depth are found (method.md §5): the paper's node/edge-normal rule, or
// from the faces the features went through (the default).
enum class PatchNormals { paper, faces };
// Where a patch's force acts: one point (the paper), or its extreme overlap corners.
enum class PatchPoints { one, corners };
// The default SEMM's solver: one scalar row per contact point (fast; the default), each
// patch's normal impulses solved together as one block (Lawson-Hanson), or Newton's method on
// the bodies' velocities (src/forces/semm_newton/).
enum class ContactSolver { rows, blocks, newton };
// The penalty model's normal law: F = k d (linear) or F = k d^(3/2) (Hertz).
enum class PenaltyLaw { linear, hertz };

struct ShapeDef {
  ShapeType type = ShapeType::box;
  std::string path;  // JSON path of this shape, e.g. "bodies[1].shape"

  // prism: regular `sides`-gon of circumradius `radius`, extruded by `height` along `axis`.
  // ring: `segments`-gon centre line of circumradius `radius`, `sides`-gon section of
  //       circumradius `section_radius`, split into `blocks` blocks, symmetry axis `axis`.
  int sides = 6;
  Real radius = 0;
  Real height = 0;
  int segments = 16;
  Real section_radius = 0;
  int blocks = 0;                // 0: one block per segment
  bool allow_nonconvex = false;  // accept (and report) non-convex blocks, e.g. the paper's ring
  Axis axis = Axis::z;

  Vec3 size = Vec3::Zero();  // box edge lengths
  std::vector<Vec3> points;  // convex: the block is the convex hull of these points

  // mesh: a closed triangle mesh from `file` (as written: relative to the scene file, or
  // absolute), every vertex multiplied by `scale`, cut into convex blocks by `cutting` (at most
  // `max_blocks` when approximate). The reader resolves `file_path` and fills `mesh`.
  std::string file;
  std::string file_path;
  Real scale = 1.0;
  MeshCutting cutting = MeshCutting::approximate;
  int max_blocks = 32;
  std::shared_ptr<const MeshBody> mesh;

  // compound: parts, each a shape placed in this shape's frame by `position` and `rotation`.
  std::vector<ShapeDef> parts;
  Vec3 position = Vec3::Zero();  // pose of this shape inside a compound
  Mat3 rotation = Mat3::Identity();
  // The orientation as the scene file gave it: euler_zxz_deg (3 numbers) or quaternion (4);
  // empty if it gave none. Written back as given while it still makes `rotation`, so that a
  // scene written, read and written again gives the same text.
  std::vector<Real> orientation_given;
};

struct BodyDef {
  std::string name;
  std::string path;  // "bodies[i]"
  ShapeDef shape;
  Real density = 1.0;
  Vec3 position = Vec3::Zero();          // world position of the body frame's origin
  Mat3 rotation = Mat3::Identity();      // body frame to world (from euler_zxz_deg or quaternion)
  std::vector<Real> orientation_given;   // as ShapeDef::orientation_given
  Vec3 velocity = Vec3::Zero();          // of the centre of mass, world axes
  Vec3 angular_velocity = Vec3::Zero();  // world axes
  bool fixed = false;
  // Granular processes (process_def.hpp): the body's material ("" for contact.friction and
  // contact.restitution), its prescribed motion, and the time it is taken away (a gate).
  std::string material;
  std::optional<MotionDef> motion;
  std::optional<Real> removed_at;
  // A template's size factor drawn per copy (fill and inlet bodies only): uniform in
  // [min, max]; absent: every copy the template's own size.
  std::optional<ScaleDef> scale;
};

// Particle insertion (docs/scene_format.md, `fill`): `count` copies of one body, named
// `name_0`, `name_1`, ..., at random positions in `region` and random orientations (uniform over
// all rotations), from a seeded generator, placed so that no two bodies' bounding spheres (and
// no body and the region's sides) overlap. The copies share the template's blocks.
struct FillDef {
  std::string path;  // "fill[i]"
  std::string name;
  int count = 0;
  Vec3 region_min = Vec3::Zero(), region_max = Vec3::Zero();
  std::uint64_t seed = 1;
  BodyDef body;  // the template: shape, density, velocity, angular_velocity, fixed, scale
};

// Bodies created during the run (docs/processes.md): copies of `body` placed in `region` where
// they overlap nothing, `rate` per second from `start` on, `count` in all, named `name_<k>`.
// Each copy starts with `velocity` (world axes) and, with body.scale, a size factor of its own.
// A copy that finds no room waits for the next step.
struct InletDef {
  std::string path;  // "inlets[i]"
  std::string name;
  RegionDef region;
  Real rate = 0;  // bodies per second
  int count = 0;
  Real start = 0;
  std::uint64_t seed = 1;
  Vec3 velocity = Vec3::Zero();
  BodyDef body;  // the template: shape, density, material, scale (no name or pose)
};

struct ContactDef {
  ContactModel model = ContactModel::semm;
  Real friction = 0.3;
  Real restitution = 0.0;
  Real stiffness = 0.0;  // penalty: normal spring constant (0: not given)
  Real damping = 0.0;    // penalty: normal dashpot constant
  PenaltyLaw law = PenaltyLaw::linear;  // penalty: normal law
  Real tangential_stiffness = 0.0;      // penalty: tangential spring (the reader fills 2/7 k)
  // Both default to the paper's choice under semm-paper and to the project's otherwise; the
  // reader fills them in, so a SceneDef always says which is used.
  PatchNormals normals = PatchNormals::faces;
  PatchPoints points = PatchPoints::corners;
  // When the contact solver (default SEMM and the overlap correction) stops: Newton (the default
  // solver) once the momentum its impulses fail to give is at most `tolerance` of their own; the
  // rows solver's sweeps once no impulse changes by more than `tolerance` of the largest, or after
  // `max_sweeps` (which Newton reads only for the islands it leaves to the rows and for the
  // overlap correction).
  Real tolerance = 1e-9;
  int max_sweeps = 500;
  // The order of the solver's sweeps: patch by patch as detected (the default, fastest on one
  // thread), or by colours, patches of one colour sharing no body, which lets threads share the
  // sweeps (results then differ from patch order in the last digits, but not between thread
  // counts).
  bool colour_sweeps = false;
  // Contact before overlap (contact_margins.hpp): the pair gap under which separated blocks
  // already make contact points; empty for "auto" (from the bodies' sizes and motion, the
  // default), 0 for none (contact only after overlap).
  std::optional<Real> margin;
  // SEMM's solver: Newton's method on the primal problem (the default: its iterations do not grow
  // with a pile's height), the scalar rows' Gauss-Seidel sweeps, or patch blocks.
  ContactSolver solver = ContactSolver::newton;
  // The rows solver's sweeps with nonsmooth nonlinear conjugate gradients (semm_rows.cpp): each
  // sweep's change taken as a gradient step and the impulses moved further along a direction
  // that remembers the sweeps before, so that weight reaches the floor of a tall stack in fewer
  // sweeps (in piles, with friction, it takes more: docs/benchmarks.md). false: plain projected
  // Gauss-Seidel.
  bool conjugate_gradients = false;
  // Sub-steps of a step (contact_margins.hpp, refreshed_patches.hpp): contacts are detected once per
  // step, then solved and integrated this many times at time_step / substeps, each sub-step
  // rebuilding the detected patches from their features. 1: one solve per detection, as before.
  int substeps = 1;
  // Above substeps: the step takes as many more sub-steps, up to this many, as keep each
  // contact's relative motion within one sub-step under substep_motion of the smaller body's
  // size (src/simulation/substep_count.hpp). 0 (the default): always `substeps`.
  int max_substeps = 0;
  Real substep_motion = 0.015;
  // With contact before overlap: a block pair that has barely moved since its last separating-
  // axis search takes last step's features again (src/contact/pair_cache.hpp); false: every
  // pair is searched at every step. Not used over MPI ranks.
  bool pair_cache = true;
  // Coefficients of named pairs of materials (process_def.hpp), overriding the rule for pairs
  // without an entry.
  std::vector<MaterialPairDef> pairs;
};

// Bodies at rest fall asleep (src/simulation/sleep.hpp, docs/method.md "Sleep"): an island of
// bodies in contact whose every body has moved slower than `speed` (|v| + |omega| * its size)
// for `time` seconds stops being integrated and tested for contact until something wakes it.
struct SleepDef {
  Real speed = 0;  // scene units of length per second
  Real time = 0;   // seconds
};

struct WallDef {
  // A constructor, so that {point, normal} still makes a wall without a warning about the
  // fields that came later.
  WallDef(const Vec3& p = Vec3::Zero(), const Vec3& n = Vec3::UnitZ()) : point(p), normal(n) {}
  Vec3 point = Vec3::Zero();
  Vec3 normal = Vec3::UnitZ();  // unit, pointing into the space where bodies live
  std::string material;         // "" : contact.friction and contact.restitution
  std::optional<Real> removed_at;  // the wall takes part until then
};

struct ContainerDef {
  ContainerDef(const Vec3& lo = Vec3::Zero(), const Vec3& hi = Vec3::Ones()) : min(lo), max(hi) {}
  Vec3 min = Vec3::Zero();
  Vec3 max = Vec3::Ones();
  std::string material;  // of its six faces
};

struct OutputDef {
  Real interval = 0.01;
  Real checkpoint_interval = 0.0;  // 0: no checkpoints
  bool paraview = false;
};

// Earth's gravity in the paper's units (cm/s^2); the paper's own runs use 98.0.
inline constexpr Real earth_gravity_cgs = 980.665;
inline constexpr Real paper_gravity_cgs = 98.0;

struct SceneDef {
  std::string source;  // file name, for messages
  Vec3 gravity{0, 0, -earth_gravity_cgs};
  Real time_step = 1e-5;
  Real duration = 1.0;
  IntegratorKind integrator = IntegratorKind::default_;
  ContactDef contact;
  std::optional<ContainerDef> container;
  std::vector<WallDef> walls;
  std::vector<BodyDef> bodies;
  std::vector<FillDef> fill;  // bodies made by insertion, after `bodies`
  OutputDef output;
  // Granular processes (process_def.hpp).
  std::vector<MaterialDef> materials;  // in name order
  std::vector<InletDef> inlets;
  std::vector<OutletDef> outlets;
  std::vector<SensorDef> sensors;
  // Sleep of bodies at rest; absent (the default): every body is integrated every step.
  std::optional<SleepDef> sleep;
};

// The time one solve and one integration cover: the time step, or its part with sub-steps (with
// contact.max_substeps, at the step's fewest sub-steps; a step's own count is the Workspace's).
inline Real substep_time(const SceneDef& scene) {
  return scene.time_step / scene.contact.substeps;
}

// A problem in a scene that names where: `path` is the JSON path (e.g. "bodies[1].shape.radius").
class SceneError : public std::runtime_error {
 public:
  SceneError(std::string path, std::string reason)
      : std::runtime_error(path + ": " + reason),
        path_(std::move(path)),
        reason_(std::move(reason)) {}
  const std::string& path() const { return path_; }
  const std::string& reason() const { return reason_; }

 private:
  std::string path_;
  std::string reason_;
};

// Rotation matrices of the scene's orientation conventions.
Mat3 rotation_x(Real angle);
Mat3 rotation_z(Real angle);
// Goldstein z-x-z Euler angles (radians): g = Rz(phi) Rx(theta) Rz(psi), body to world.
Mat3 euler_zxz(Real phi, Real theta, Real psi);

}  // namespace tem
