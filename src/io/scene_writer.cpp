// SceneDef -> JSON (see scene_writer.hpp). The inverse of scene_reader.cpp key by key; when a
// key is added there, add it here too, or the round-trip test fails.
#include "io/scene_writer.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <optional>
#include <string>

#include "io/scene_reader.hpp"
#include "io/shape_type_names.hpp"

namespace tem {
namespace {

using Json = nlohmann::ordered_json;

Json vec3(const Vec3& v) { return Json::array({v.x(), v.y(), v.z()}); }

// [w, x, y, z] with w >= 0 (q and -q are the same rotation; one form keeps files comparable).
Json quaternion(const Mat3& rotation) {
  Quat q(rotation);
  if (q.w() < 0) q.coeffs() = -q.coeffs();
  return Json::array({q.w(), q.x(), q.y(), q.z()});
}

// z-x-z Euler angles in degrees of a rotation g = Rz(phi) Rx(theta) Rz(psi), theta in
// [0, 180]; at theta = 0 or 180 only phi -/+ psi is defined and psi is taken as 0.
Vec3 euler_zxz_deg_of(const Mat3& g) {
  constexpr Real kDeg = 180.0 / M_PI;
  const Real theta = std::acos(std::clamp(g(2, 2), Real(-1), Real(1)));
  const Real sin_theta = std::hypot(g(0, 2), g(1, 2));
  if (sin_theta < 1e-12) return Vec3(std::atan2(g(1, 0), g(0, 0)) * kDeg, theta * kDeg, 0);
  return Vec3(std::atan2(g(0, 2), -g(1, 2)), theta, std::atan2(g(2, 0), g(2, 1))) * kDeg;
}

// The orientation keys for a rotation. A scene's rotations mostly come from Euler angles in
// whole or decimal degrees; recovering those angles, when the shortest decimal form gives back
// exactly the same matrix, makes the file readable ([10, 80, 10]) and the round trip exact.
// Otherwise a quaternion, which comes back equal to rounding (about 1e-16).
//
// An orientation the scene file gave is written as given while it still makes the rotation:
// a quaternion written from a matrix reads back to a matrix that may differ in the last bit,
// whose own quaternion may differ again, so only the given numbers make written, read and
// written again give the same text (the fuzzer found the drift).
void write_orientation(const Mat3& rotation, const std::vector<Real>& given, Json* j) {
  if (given.size() == 3 &&
      rotation_from_euler_zxz_deg(Vec3(given[0], given[1], given[2])) == rotation) {
    (*j)["euler_zxz_deg"] = Json::array({given[0], given[1], given[2]});
    return;
  }
  if (given.size() == 4 &&
      rotation_from_quaternion(given[0], given[1], given[2], given[3]) == rotation) {
    (*j)["quaternion"] = Json::array({given[0], given[1], given[2], given[3]});
    return;
  }
  const Vec3 angles = euler_zxz_deg_of(rotation);
  for (int digits = 0; digits <= 12; ++digits) {
    const Real scale = std::pow(10.0, digits);
    Vec3 rounded = (angles * scale).array().round() / scale;
    rounded = rounded.unaryExpr([](Real a) { return a == 0 ? Real(0) : a; });  // no -0
    if (rotation_from_euler_zxz_deg(rounded) == rotation) {
      (*j)["euler_zxz_deg"] = Json::array({rounded.x(), rounded.y(), rounded.z()});
      return;
    }
  }
  (*j)["quaternion"] = quaternion(rotation);
}

const char* axis_name(Axis axis) {
  switch (axis) {
    case Axis::x:
      return "x";
    case Axis::y:
      return "y";
    case Axis::z:
      return "z";
  }
  return "z";
}

const char* contact_model_name(ContactModel model) {
  switch (model) {
    case ContactModel::semm:
      return "semm";
    case ContactModel::semm_paper:
      return "semm-paper";
    case ContactModel::penalty:
      return "penalty";
  }
  return "semm";
}

// Only the keys of the shape's own type; a compound's parts also get their pose.
Json shape_to_json(const ShapeDef& shape, bool is_part) {
  Json j;
  j["type"] = std::string(shape_type_name(shape.type));
  if (is_part) {
    j["position"] = vec3(shape.position);
    write_orientation(shape.rotation, shape.orientation_given, &j);
  }
  switch (shape.type) {
    case ShapeType::prism:
      j["sides"] = shape.sides;
      j["radius"] = shape.radius;
      j["height"] = shape.height;
      j["axis"] = axis_name(shape.axis);
      break;
    case ShapeType::ring:
      j["segments"] = shape.segments;
      j["sides"] = shape.sides;
      j["radius"] = shape.radius;
      j["section_radius"] = shape.section_radius;
      // blocks = 0 in a def built in code means one block per segment; say so explicitly.
      j["blocks"] = shape.blocks > 0 ? shape.blocks : shape.segments;
      j["axis"] = axis_name(shape.axis);
      j["allow_nonconvex"] = shape.allow_nonconvex;
      break;
    case ShapeType::box:
      j["size"] = vec3(shape.size);
      break;
    case ShapeType::convex: {
      Json points = Json::array();
      for (const Vec3& p : shape.points) points.push_back(vec3(p));
      j["points"] = std::move(points);
      break;
    }
    case ShapeType::compound: {
      Json blocks = Json::array();
      for (const ShapeDef& part : shape.parts) blocks.push_back(shape_to_json(part, true));
      j["blocks"] = std::move(blocks);
      break;
    }
    case ShapeType::mesh:
      // The file as loaded (an absolute path), so that the scene runs again from anywhere.
      j["file"] = shape.file_path.empty() ? shape.file : shape.file_path;
      j["scale"] = shape.scale;
      j["blocks"] = shape.cutting == MeshCutting::exact ? "exact" : "approximate";
      j["max_blocks"] = shape.max_blocks;
      break;
  }
  return j;
}

Json region_to_json(const RegionDef& region) {
  return Json{{"min", vec3(region.min)}, {"max", vec3(region.max)}};
}

// Granular-process keys of a body or a template: written only when given, so that scenes
// without them write as before; inside each, every default is written.
void write_material(const std::string& material, Json* j) {
  if (!material.empty()) (*j)["material"] = material;
}

void write_scale(const std::optional<ScaleDef>& scale, Json* j) {
  if (scale) (*j)["scale"] = Json{{"min", scale->min}, {"max", scale->max}};
}

void write_removed_at(const std::optional<Real>& removed_at, Json* j) {
  if (removed_at) (*j)["removed_at"] = *removed_at;
}

// An infinite `end` (the default: no end) is left out; JSON has no infinity.
Json motion_to_json(const MotionDef& motion) {
  Json j;
  j["velocity"] = vec3(motion.velocity);
  j["angular_velocity"] = vec3(motion.angular_velocity);
  if (motion.center) j["center"] = vec3(*motion.center);
  if (motion.surface_velocity) j["surface_velocity"] = vec3(*motion.surface_velocity);
  j["start"] = motion.start;
  if (std::isfinite(motion.end)) j["end"] = motion.end;
  if (motion.oscillation) {
    j["oscillation"] = Json{{"amplitude", vec3(motion.oscillation->amplitude)},
                            {"frequency", motion.oscillation->frequency}};
  }
  return j;
}

const char* sensor_type_name(SensorType type) {
  switch (type) {
    case SensorType::plane:
      return "plane";
    case SensorType::force:
      return "force";
    case SensorType::region:
      return "region";
  }
  return "plane";
}

Json sensor_to_json(const SensorDef& sensor) {
  Json j;
  j["name"] = sensor.name;
  j["type"] = sensor_type_name(sensor.type);
  switch (sensor.type) {
    case SensorType::plane:
      j["point"] = vec3(sensor.point);
      j["normal"] = vec3(sensor.normal);
      break;
    case SensorType::force:
      j["bodies"] = sensor.bodies;
      break;
    case SensorType::region:
      j["region"] = region_to_json(sensor.region);
      break;
  }
  return j;
}

Json inlet_to_json(const InletDef& inlet) {
  Json j;
  j["name"] = inlet.name;
  j["region"] = region_to_json(inlet.region);
  j["rate"] = inlet.rate;
  j["count"] = inlet.count;
  j["start"] = inlet.start;
  j["seed"] = inlet.seed;
  j["velocity"] = vec3(inlet.velocity);
  Json body = Json{{"shape", shape_to_json(inlet.body.shape, false)},
                   {"density", inlet.body.density},
                   {"angular_velocity", vec3(inlet.body.angular_velocity)}};
  write_material(inlet.body.material, &body);
  write_scale(inlet.body.scale, &body);
  j["body"] = std::move(body);
  return j;
}

Json body_to_json(const BodyDef& body) {
  Json j;
  j["name"] = body.name;
  j["shape"] = shape_to_json(body.shape, false);
  j["density"] = body.density;
  j["position"] = vec3(body.position);
  write_orientation(body.rotation, body.orientation_given, &j);
  j["velocity"] = vec3(body.velocity);
  j["angular_velocity"] = vec3(body.angular_velocity);
  j["fixed"] = body.fixed;
  write_material(body.material, &j);
  if (body.motion) j["motion"] = motion_to_json(*body.motion);
  write_removed_at(body.removed_at, &j);
  return j;
}

Json fill_to_json(const FillDef& fill) {
  Json j;
  j["name"] = fill.name;
  j["count"] = fill.count;
  j["region"] = Json{{"min", vec3(fill.region_min)}, {"max", vec3(fill.region_max)}};
  j["seed"] = fill.seed;
  Json body = Json{{"shape", shape_to_json(fill.body.shape, false)},
                   {"density", fill.body.density},
                   {"velocity", vec3(fill.body.velocity)},
                   {"angular_velocity", vec3(fill.body.angular_velocity)},
                   {"fixed", fill.body.fixed}};
  write_material(fill.body.material, &body);
  write_scale(fill.body.scale, &body);
  j["body"] = std::move(body);
  return j;
}

// Like dump(2), but a list of plain values stays on one line: "position": [0.5, 0.5, 0.7]
// reads better than one number per line.
std::string indented(const Json& j, int depth) {
  const bool is_list = j.is_array();
  if (!j.is_structured() || j.empty()) return j.dump();
  if (is_list &&
      std::none_of(j.begin(), j.end(), [](const Json& e) { return e.is_structured(); })) {
    std::string out = "[";
    for (std::size_t i = 0; i < j.size(); ++i) out += (i ? ", " : "") + j[i].dump();
    return out + "]";
  }
  const std::string inner(2 * (depth + 1), ' ');
  std::string out = is_list ? "[\n" : "{\n";
  bool first = true;
  for (const auto& [key, value] : j.items()) {
    out += first ? "" : ",\n";
    first = false;
    out += inner;
    if (!is_list) out += Json(key).dump() + ": ";
    out += indented(value, depth + 1);
  }
  return out + "\n" + std::string(2 * depth, ' ') + (is_list ? "]" : "}");
}

}  // namespace

Json scene_to_json(const SceneDef& scene) {
  Json j;
  if (!scene.materials.empty()) {
    Json materials = Json::object();
    for (const MaterialDef& m : scene.materials) {
      materials[m.name] = Json{{"friction", m.friction},
                               {"restitution", m.restitution},
                               {"rolling_resistance", m.rolling_resistance}};
    }
    j["materials"] = std::move(materials);
  }
  j["gravity"] = vec3(scene.gravity);
  j["time_step"] = scene.time_step;
  j["duration"] = scene.duration;
  j["integrator"] = scene.integrator == IntegratorKind::paper ? "paper" : "default";
  j["contact"] = Json{{"model", contact_model_name(scene.contact.model)},
                      {"friction", scene.contact.friction},
                      {"restitution", scene.contact.restitution},
                      {"stiffness", scene.contact.stiffness},
                      {"damping", scene.contact.damping},
                      {"law", scene.contact.law == PenaltyLaw::hertz ? "hertz" : "linear"},
                      {"tangential_stiffness", scene.contact.tangential_stiffness},
                      {"normals", scene.contact.normals == PatchNormals::paper ? "paper" : "faces"},
                      {"points", scene.contact.points == PatchPoints::one ? "one" : "corners"},
                      {"tolerance", scene.contact.tolerance},
                      {"max_sweeps", scene.contact.max_sweeps},
                      {"substeps", scene.contact.substeps},
                      {"sweep_order", scene.contact.colour_sweeps ? "colours" : "patches"},
                      {"solver", scene.contact.solver == ContactSolver::blocks   ? "blocks"
                                 : scene.contact.solver == ContactSolver::newton ? "newton"
                                                                                 : "rows"}};
  if (scene.contact.margin)
    j["contact"]["margin"] = *scene.contact.margin;
  else
    j["contact"]["margin"] = "auto";
  // Written only where they are not the default: a scene of the defaults writes what it wrote
  // before the keys existed, so that its checkpoints' fingerprints still match (checkpoint.hpp).
  if (!scene.contact.pair_cache) j["contact"]["pair_cache"] = false;
  if (scene.contact.max_substeps > 0) {
    j["contact"]["max_substeps"] = scene.contact.max_substeps;
    j["contact"]["substep_motion"] = scene.contact.substep_motion;
  }
  if (scene.contact.conjugate_gradients) j["contact"]["acceleration"] = "conjugate_gradients";
  if (!scene.contact.pairs.empty()) {
    Json pairs = Json::array();
    for (const MaterialPairDef& p : scene.contact.pairs) {
      Json pair = Json{{"materials", Json::array({p.first, p.second})}};
      if (p.friction) pair["friction"] = *p.friction;
      if (p.restitution) pair["restitution"] = *p.restitution;
      if (p.rolling_resistance) pair["rolling_resistance"] = *p.rolling_resistance;
      pairs.push_back(std::move(pair));
    }
    j["contact"]["pairs"] = std::move(pairs);
  }
  if (scene.container) {
    j["container"] = Json{{"min", vec3(scene.container->min)}, {"max", vec3(scene.container->max)}};
    write_material(scene.container->material, &j["container"]);
  }
  Json walls = Json::array();
  for (const WallDef& wall : scene.walls) {
    Json w = Json{{"point", vec3(wall.point)}, {"normal", vec3(wall.normal)}};
    write_material(wall.material, &w);
    write_removed_at(wall.removed_at, &w);
    walls.push_back(std::move(w));
  }
  j["walls"] = std::move(walls);
  Json bodies = Json::array();
  for (const BodyDef& body : scene.bodies) bodies.push_back(body_to_json(body));
  j["bodies"] = std::move(bodies);
  if (!scene.fill.empty()) {
    Json fills = Json::array();
    for (const FillDef& fill : scene.fill) fills.push_back(fill_to_json(fill));
    j["fill"] = std::move(fills);
  }
  if (!scene.inlets.empty()) {
    Json inlets = Json::array();
    for (const InletDef& inlet : scene.inlets) inlets.push_back(inlet_to_json(inlet));
    j["inlets"] = std::move(inlets);
  }
  if (!scene.outlets.empty()) {
    Json outlets = Json::array();
    for (const OutletDef& outlet : scene.outlets)
      outlets.push_back(Json{{"name", outlet.name}, {"region", region_to_json(outlet.region)}});
    j["outlets"] = std::move(outlets);
  }
  if (!scene.sensors.empty()) {
    Json sensors = Json::array();
    for (const SensorDef& sensor : scene.sensors) sensors.push_back(sensor_to_json(sensor));
    j["sensors"] = std::move(sensors);
  }
  j["output"] = Json{{"interval", scene.output.interval},
                     {"checkpoint_interval", scene.output.checkpoint_interval},
                     {"paraview", scene.output.paraview}};
  // Only when on: a scene without it keeps its text, so its checkpoints' fingerprint.
  if (scene.sleep)
    j["sleep"] = Json{{"speed", scene.sleep->speed}, {"time", scene.sleep->time}};
  return j;
}

std::string write_scene_text(const SceneDef& scene) {
  return indented(scene_to_json(scene), 0) + "\n";
}

bool write_scene_file(const SceneDef& scene, const std::string& filename, std::string* error) {
  std::ofstream out(filename, std::ios::binary | std::ios::trunc);
  if (out) out << write_scene_text(scene);
  out.close();
  if (!out) {
    if (error) *error = "cannot write " + filename;
    return false;
  }
  return true;
}

}  // namespace tem
