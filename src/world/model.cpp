// Building the Model from a SceneDef: blocks and their elements, each body's mass properties
// (eqs. 4-7 with the erratum of eq. 7), walls; and the initial State.
#include "world/model.hpp"

#include "world/inlet_delivery.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <set>
#include <sstream>

#include "world/shape_blocks.hpp"
#include "mesh/mesh_body.hpp"
#include "world/fill.hpp"
#include "world/inlet_delivery.hpp"
#include "mass/mass_properties.hpp"

namespace tem {
namespace {

std::string with_label(const std::string& label, const std::string& text) {
  return label.empty() ? text : label + ": " + text;
}

int material_index(const Model& model, const std::string& name) {
  for (int m = 0; m < model.material_count(); ++m)
    if (model.material_names[m] == name) return m;
  return 0;  // the reader has refused unknown names
}

// The coefficient table: contact.pairs where they name a pair, else the rule (interface.md):
// the smaller friction, the smaller restitution and the larger rolling resistance.
void build_materials(const SceneDef& scene, Model& model) {
  std::vector<PairCoefficients> own{{scene.contact.friction, scene.contact.restitution, 0}};
  for (const MaterialDef& m : scene.materials) {
    model.material_names.push_back(m.name);
    own.push_back({m.friction, m.restitution, m.rolling_resistance});
  }
  const size_t n = own.size();
  model.pairs.resize(n * n);
  for (size_t a = 0; a < n; ++a)
    for (size_t b = 0; b < n; ++b)
      model.pairs[a * n + b] = {std::min(own[a].friction, own[b].friction),
                                std::min(own[a].restitution, own[b].restitution),
                                std::max(own[a].rolling_resistance, own[b].rolling_resistance)};
  for (const MaterialPairDef& p : scene.contact.pairs) {
    const size_t a = material_index(model, p.first), b = material_index(model, p.second);
    PairCoefficients c = model.pairs[a * n + b];
    if (p.friction) c.friction = *p.friction;
    if (p.restitution) c.restitution = *p.restitution;
    if (p.rolling_resistance) c.rolling_resistance = *p.rolling_resistance;
    model.pairs[a * n + b] = model.pairs[b * n + a] = c;
  }
}

// A mesh shape cut approximately, placed in its body's shape frame. Its blocks are convex hulls
// that cover more than the mesh (docs/meshes.md), so the body's mass comes from the mesh's own
// surface integrals instead of from the blocks.
struct ApproximateMesh {
  const ShapeDef* shape;
  Mat3 rotation;  // x_body = rotation * x_mesh + position, as shape_polyhedra() places its blocks
  Vec3 position;
};

void approximate_meshes(const ShapeDef& shape, const Mat3& rotation, const Vec3& position,
                        std::vector<ApproximateMesh>& out) {
  if (shape.type == ShapeType::mesh && shape.mesh &&
      shape.mesh->cutting == MeshCutting::approximate)
    out.push_back({&shape, rotation, position});
  if (shape.type == ShapeType::compound)
    for (const ShapeDef& part : shape.parts)
      approximate_meshes(part, rotation * part.rotation, rotation * part.position + position, out);
}

// The mesh's unit-density surface integrals (in its frame, already scaled by the shape's
// `scale`) for `density`, times a copy's size factor s: volume and mass go as s^3, the centre
// as s, the second moment as s^5.
PlacedMass mesh_mass(const ApproximateMesh& m, Real density, Real s) {
  const MassProperties& unit = m.shape->mesh->surface;
  MassProperties mass;
  mass.volume = unit.volume * s * s * s;
  mass.mass = density * mass.volume;
  mass.center = s * unit.center;
  mass.second_moment = (density * s * s * s * s * s) * unit.second_moment;
  return {mass, m.rotation, s * m.position};
}

}  // namespace

int add_block(Model& model, Block block) {
  if (!model.free_blocks.empty()) {
    const int slot = model.free_blocks.back();
    model.free_blocks.pop_back();
    model.blocks[slot] = std::move(block);
    return slot;
  }
  model.blocks.push_back(std::move(block));
  return static_cast<int>(model.blocks.size() - 1);
}

Body build_body(const BodyDef& def, Model& model, Real scale) {
  if (!(def.density > 0) || !std::isfinite(def.density))
    throw SceneError(def.path + ".density", "must be a positive number");
  Body body;
  body.name = def.name;
  body.density = def.density;
  body.fixed = def.fixed;
  body.start_position = def.position;
  body.start_rotation = def.rotation;
  body.start_velocity = def.velocity;
  body.start_angular_velocity = def.angular_velocity;
  body.material = material_index(model, def.material);
  body.motion = def.motion;
  if (def.motion && def.motion->surface_velocity) {
    const ContactDef& c = model.scene.contact;
    if (c.model == ContactModel::semm_paper)
      throw SceneError(def.path + ".motion.surface_velocity",
                       "a sliding surface moves bodies by friction, which contact.model "
                       "\"semm-paper\" does not have; use \"semm\" or \"penalty\"");
    if (c.model == ContactModel::semm && c.solver == ContactSolver::blocks)
      throw SceneError(def.path + ".motion.surface_velocity",
                       "a sliding surface is solved by contact.solver \"newton\" (the default) or "
                       "\"rows\", not \"blocks\"");
  }
  if (def.removed_at) body.removed_at = *def.removed_at;

  std::vector<PlacedMass> parts;
  std::map<std::string, std::vector<Real>> nonconvex;  // shape path -> how far each sticks out
  // Approximately cut meshes weigh what the mesh does: their blocks add no mass of their own.
  // Exactly cut ones keep their blocks' masses, which are the mesh's to round-off
  // (MeshScene.ExactBodyHasTheMeshsMassProperties) and keep the body's centre the blocks' own.
  std::vector<ApproximateMesh> meshes;
  approximate_meshes(def.shape, Mat3::Identity(), Vec3::Zero(), meshes);
  std::set<std::string> mesh_paths;
  for (const ApproximateMesh& m : meshes) {
    mesh_paths.insert(m.shape->path);
    parts.push_back(mesh_mass(m, def.density, scale));
  }
  for (PlacedPolyhedron& placed : shape_polyhedra(def.shape)) {
    // A copy's size factor scales its blocks before they are built, so that its elements and
    // mass properties are those of the scaled shape, exactly.
    if (scale != 1) {
      for (Vec3& p : placed.polyhedron.points) p *= scale;
      placed.position *= scale;
    }
    int index = -1;
    try {
      index = add_block(model, Block(placed.polyhedron));
    } catch (const GeometryError& e) {
      std::string reason = with_label(placed.label, e.what());
      if (!placed.advice.empty()) reason += "; " + placed.advice;
      throw SceneError(placed.path, reason);
    }
    const Block& block = model.blocks[index];
    if (!block.convex()) nonconvex[placed.path].push_back(block.nonconvexity());
    const Vec3 centre = placed.rotation * block.centroid_in_input() + placed.position;
    if (!mesh_paths.count(placed.path))
      parts.push_back({block_mass_properties(block, def.density), placed.rotation, centre});
    body.blocks.push_back({index, placed.rotation, centre, placed.path});
  }

  for (const auto& [path, amounts] : nonconvex) {
    std::ostringstream w;
    w << path << ": " << amounts.size() << " of its blocks " << (amounts.size() == 1 ? "is" : "are")
      << " not convex (a node lies up to " << *std::max_element(amounts.begin(), amounts.end())
      << " outside a face plane); accepted because allow_nonconvex is set, but contacts on "
         "their re-entrant side can be reported where there is no body (paper §2.2)";
    model.warnings.push_back(w.str());
  }

  const MassProperties total = combine(parts);
  for (BlockInstance& b : body.blocks) b.offset -= total.center;
  body.origin_offset = -total.center;
  body.volume = total.volume;
  body.inertia.mass = total.mass;
  body.inertia.inertia = inertia_from_second_moment(total.second_moment);
  body.inertia.inertia_inv = body.inertia.inertia.inverse();
  body.owns_blocks = scale != 1;
  return body;
}

namespace {

// A prescribed motion so fast that a body it pushes would carry a kinetic energy beyond the range
// of a double is refused here, naming the motion: run, it would make the body it hits
// non-finite, and the message would blame that body.
void check_motion_energies(const Model& model) {
  Real heaviest = 0;
  for (const Body& b : model.bodies) heaviest = std::max(heaviest, b.inertia.mass);
  for (const Body& b : model.inlet_templates) heaviest = std::max(heaviest, b.inertia.mass);
  for (size_t i = 0; i < model.scene.bodies.size() && i < model.bodies.size(); ++i) {
    const BodyDef& def = model.scene.bodies[i];
    if (!def.motion) continue;
    const MotionDef& m = *def.motion;
    const Real reach = body_size(model, model.bodies[i]) +
                       (m.center ? (*m.center - def.position).norm() : Real(0));
    Real speed = m.velocity.stableNorm() + m.angular_velocity.stableNorm() * reach;
    if (m.oscillation)
      speed += m.oscillation->amplitude.stableNorm() * 2 * std::numbers::pi *
               m.oscillation->frequency;
    if (m.surface_velocity) speed += m.surface_velocity->stableNorm();
    if (std::isfinite(0.5 * heaviest * speed * speed)) continue;
    std::ostringstream reason;
    reason << "moves at up to " << speed << " (length units per second): a body of mass "
           << heaviest << " pushed at that speed would carry a kinetic energy beyond the range of "
           << "a double, and the run would stop with that body's state not finite; give a "
           << "motion of a physical speed";
    throw SceneError(def.path + ".motion", reason.str());
  }
}

}  // namespace

Model build_model(const SceneDef& scene) {
  Model model;
  model.scene = scene;
  build_materials(scene, model);
  constexpr Real never = std::numeric_limits<Real>::infinity();
  if (scene.container) {
    const ContainerDef& c = *scene.container;
    const int material = material_index(model, c.material);
    for (int axis = 0; axis < 3; ++axis) {
      const Vec3 n = Vec3::Unit(axis);
      model.walls.push_back({c.min, n, material, never});
      model.walls.push_back({c.max, -n, material, never});
    }
  }
  for (const WallDef& w : scene.walls)
    model.walls.push_back({w.point, w.normal.normalized(), material_index(model, w.material),
                           w.removed_at.value_or(never)});
  for (const BodyDef& def : scene.bodies) model.bodies.push_back(build_body(def, model));
  for (const FillDef& fill : scene.fill) {
    // One template body: its blocks are built once and shared by every copy (copies with a
    // size factor of their own get their own blocks).
    const Body copy = build_body(fill.body, model);
    place_fill(fill, copy, model);
  }
  for (const InletDef& inlet : scene.inlets) {
    Body copy = build_body(inlet.body, model);
    copy.start_velocity = inlet.velocity;
    // The region must hold the largest copy (the sphere the placement keeps clear).
    const Real largest = inlet.body.scale ? inlet.body.scale->max : 1;
    const Real radius = largest * body_size(model, copy);
    const Vec3 room = inlet.region.max - inlet.region.min;
    for (int a = 0; a < 3; ++a) {
      if (room[a] < 2 * radius)
        throw SceneError(inlet.path + ".region",
                         "is too small for one copy: each side must be at least the copy's "
                         "diameter " + std::to_string(2 * radius) + " (the " + "xyz"[a] +
                         " side is " + std::to_string(room[a]) + ")");
    }
    model.inlet_templates.push_back(std::move(copy));
  }
  assign_force_sensors(model);
  model.bodies_come_and_go = !scene.inlets.empty() || !scene.outlets.empty();
  for (const Body& b : model.bodies) {
    model.any_motion = model.any_motion || b.motion.has_value();
    model.bodies_come_and_go = model.bodies_come_and_go || std::isfinite(b.removed_at);
  }
  check_motion_energies(model);
  for (std::string& warning : inlet_warnings(model)) model.warnings.push_back(std::move(warning));
  return model;
}

std::vector<int> force_sensors_naming(const SceneDef& scene, const std::string& name) {
  std::vector<int> watching;
  for (size_t k = 0; k < scene.sensors.size(); ++k) {
    const SensorDef& sensor = scene.sensors[k];
    if (sensor.type != SensorType::force) continue;
    // Once per sensor, also where a name and a prefix both name the body.
    for (const std::string& entry : sensor.bodies)
      if (sensor_entry_names(entry, name)) {
        watching.push_back(static_cast<int>(k));
        break;
      }
  }
  return watching;
}

void assign_force_sensors(Model& model) {
  for (Body& body : model.bodies) body.force_sensors = force_sensors_naming(model.scene, body.name);
}

Real body_size(const Model& model, int body) { return body_size(model, model.bodies[body]); }

Real body_size(const Model& model, const Body& body) {
  Real size = 0;
  for (const BlockInstance& i : body.blocks)
    size = std::max(size, i.offset.norm() + model.blocks[i.block].bounding_radius());
  return size;
}

State initial_state(const Model& model) {
  State state;
  state.bodies.reserve(model.bodies.size());
  for (const Body& body : model.bodies) {
    BodyState s;
    s.g = body.start_rotation;
    s.x = body.start_position - body.start_rotation * body.origin_offset;
    s.v = body.start_velocity;
    s.omega = body.start_rotation.transpose() * body.start_angular_velocity;
    state.bodies.push_back(s);
    state.tags.push_back({state.next_id++, -1, 0, 1});
  }
  state.inlets.resize(model.scene.inlets.size());
  state.sensors.resize(model.scene.sensors.size());
  return state;
}

}  // namespace tem
