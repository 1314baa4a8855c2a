// JSON scene file -> SceneDef, collecting every problem with its JSON path.
//
// Reading one JSON value of each kind with its path, and the wording of generic messages, is
// json_reader.hpp's job; this file knows the scene format. Layout: rotations from degrees; then
// one function per object of the scene format (scene, contact, container, walls, body, shape,
// output), each checking its keys against the list of allowed keys first so that typos are
// caught everywhere. Cross-field checks (a ring's section radius against its radius, say) run
// only when both fields were valid on their own, so one mistake yields one message.
#include "io/scene_reader.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <string_view>
#include <utility>

#include "contact/contact_margins.hpp"
#include "io/json_reader.hpp"
#include "io/process_reader.hpp"
#include "io/shape_type_names.hpp"

namespace tem {
namespace {

using json::Bound;
using json::child;
using json::closest;
using json::contains;
using json::describe;
using json::element;
using json::format_number;
using json::in_quotes;
using json::join_quoted;
using json::Json;
using json::KeyList;
using json::Reader;

// Limits that keep a typo from asking for a gigantic mesh or a run that never ends.
constexpr int kMaxPolygonSides = 1000;
constexpr double kMaxSteps = 1e9;
constexpr int kMaxCompoundDepth = 8;
constexpr int kMaxMeshBlocks = 10000;
constexpr Real kQuaternionNormTolerance = 1e-6;

// Problems found by the JSON layer become SceneProblems, in the order they are found.
json::ProblemSink into(std::vector<SceneProblem>* problems) {
  return [problems](std::string path, std::string message) {
    problems->push_back({std::move(path), std::move(message)});
  };
}

// ---- Rotations from degrees ----------------------------------------------------------------

// cos and sin of an angle in degrees, exact at multiples of 90 degrees: cos(pi/2) in floating
// point is 6e-17, which would tilt a box meant to rest flat.
std::pair<Real, Real> cos_sin_deg(Real degrees) {
  const Real turns = std::fmod(degrees, 360.0);
  const Real quarter = turns / 90.0;
  if (quarter == std::floor(quarter)) {
    static constexpr Real kCos[] = {1, 0, -1, 0}, kSin[] = {0, 1, 0, -1};
    const int k = (static_cast<int>(quarter) % 4 + 4) % 4;
    return {kCos[k], kSin[k]};
  }
  const Real radians = turns * (M_PI / 180.0);
  return {std::cos(radians), std::sin(radians)};
}

Mat3 rotation_x_cs(Real c, Real s) {
  Mat3 r;
  r << 1, 0, 0,  //
      0, c, -s,  //
      0, s, c;
  return r;
}

Mat3 rotation_z_cs(Real c, Real s) {
  Mat3 r;
  r << c, -s, 0,  //
      s, c, 0,    //
      0, 0, 1;
  return r;
}

// ---- Scene sections ----------------------------------------------------------------------

const KeyList kSceneKeys = {"gravity",   "time_step", "duration", "integrator", "contact",
                            "container", "walls",     "bodies",   "fill",       "output",
                            "materials", "inlets",    "outlets",  "sensors",    "sleep"};
const KeyList kContactKeys = {"model",        "friction",      "restitution",
                              "stiffness",    "damping",       "normals",
                              "points",       "law",           "tangential_stiffness",
                              "tolerance",    "max_sweeps",    "sweep_order",
                              "margin",       "solver",        "pairs",
                              "substeps",     "pair_cache",    "acceleration",
                              "max_substeps", "substep_motion"};
const KeyList kContainerKeys = {"min", "max", "material"};
const KeyList kRegionKeys = {"min", "max"};
const KeyList kWallKeys = {"point", "normal", "material", "removed_at"};
const KeyList kOutputKeys = {"interval", "checkpoint_interval", "paraview"};
const KeyList kSleepKeys = {"speed", "time"};
const KeyList kBodyKeys = {"name",          "shape",      "density",  "position",
                           "euler_zxz_deg", "quaternion", "velocity", "angular_velocity",
                           "fixed",         "material",   "motion",   "removed_at"};
const KeyList kPoseKeys = {"position", "euler_zxz_deg", "quaternion"};
const KeyList kFillKeys = {"name", "count", "region", "seed", "body"};
const KeyList kFillBodyKeys = {"shape", "density",  "velocity", "angular_velocity",
                               "fixed", "material", "scale"};
const KeyList kInletKeys = {"name", "region", "rate", "count", "start", "seed", "velocity", "body"};
const KeyList kInletBodyKeys = {"shape", "density", "material", "scale", "angular_velocity"};
// A fill larger than this is a typo, and would take minutes to place.
constexpr int kMaxFillCount = 10'000'000;

// Keys a shape of each type takes, besides `type` (and the pose keys of a compound's part).
const KeyList& shape_keys(ShapeType type) {
  static const std::map<ShapeType, KeyList> keys = {
      {ShapeType::prism, {"sides", "radius", "height", "axis"}},
      {ShapeType::ring,
       {"segments", "sides", "radius", "section_radius", "blocks", "axis", "allow_nonconvex"}},
      {ShapeType::box, {"size"}},
      {ShapeType::convex, {"points"}},
      {ShapeType::compound, {"blocks"}},
      {ShapeType::mesh, {"file", "scale", "blocks", "max_blocks"}}};
  return keys.at(type);
}

class SceneReader {
 public:
  explicit SceneReader(std::vector<SceneProblem>* problems) : r_(into(problems)) {}

  void read_scene(const Json& root, SceneDef* scene) {
    if (!r_.object(root, "")) return;
    r_.check_keys(root, "", kSceneKeys);
    read_gravity(root, scene);
    const bool step_ok = r_.read_number(root, "", "time_step", &scene->time_step, Bound::positive);
    const bool duration_ok =
        r_.read_number(root, "", "duration", &scene->duration, Bound::positive);
    // Only judge the pair when neither was bad (a default standing in for a bad value would
    // give a second, misleading message).
    const bool step_bad = Reader::get(root, "time_step") && !step_ok;
    const bool duration_bad = Reader::get(root, "duration") && !duration_ok;
    if (!step_bad && !duration_bad) check_step_count(*scene);
    if (const Json* j = Reader::get(root, "integrator")) {
      if (auto kind = r_.choice<IntegratorKind>(
              *j, "integrator",
              {{"default", IntegratorKind::default_}, {"paper", IntegratorKind::paper}})) {
        scene->integrator = *kind;
      }
    }
    // Materials first: bodies, walls and pairs name them (checked at the end).
    if (const Json* j = Reader::get(root, "materials"))
      p_.read_materials(*j, "materials", &scene->materials);
    if (const Json* j = Reader::get(root, "contact")) read_contact(*j, "contact", &scene->contact);
    // Sub-steps carry the points of contact before overlap through the step
    // (refreshed_patches.hpp); the other modes have no points to carry.
    if (!contact_before_overlap(*scene)) {
      const ContactDef& c = scene->contact;
      for (const auto& [key, count] : {std::pair{"contact.max_substeps", c.max_substeps},
                                       std::pair{"contact.substeps", c.substeps}}) {
        if (count > 1)
          r_.fail(key,
                  "must be 1 unless contact is made before overlap (model \"semm\" with face "
                  "normals, corner points, the default integrator and a margin other than 0), "
                  "got " +
                      std::to_string(count));
      }
    }
    // Conjugate gradients accelerate the rows solver's sweeps; the other solvers have none.
    if (scene->contact.conjugate_gradients && (scene->contact.model != ContactModel::semm ||
                                               scene->contact.solver != ContactSolver::rows))
      r_.fail("contact.acceleration",
              "\"conjugate_gradients\" needs model \"semm\" with solver \"rows\" (it "
              "accelerates that solver's sweeps; the default solver is \"newton\"): add "
              "\"solver\": \"rows\" to contact, or remove the acceleration");
    if (const Json* j = Reader::get(root, "container")) {
      ContainerDef container;
      if (read_container(*j, "container", &container)) scene->container = container;
    }
    if (const Json* j = Reader::get(root, "walls")) read_walls(*j, "walls", &scene->walls);
    const Json* fill = Reader::get(root, "fill");
    if (fill) read_fills(*fill, "fill", scene);
    // Bodies may come from fills alone, but a scene needs some: an empty `fill` list makes
    // none, so `bodies` is then required (the fuzzer found such a scene accepted, and written
    // back as one that is not).
    const Json* inlets = Reader::get(root, "inlets");
    if (inlets) read_inlets(*inlets, "inlets", scene);
    const bool fills_bodies = (fill && fill->is_array() && !fill->empty()) ||
                              (inlets && inlets->is_array() && !inlets->empty());
    if (const Json* j = fills_bodies ? Reader::get(root, "bodies") : r_.need(root, "", "bodies"))
      read_bodies(*j, "bodies", &scene->bodies, /*may_be_empty=*/fills_bodies);
    if (const Json* j = Reader::get(root, "output")) read_output(*j, "output", &scene->output);
    if (const Json* j = Reader::get(root, "sleep")) read_sleep(*j, "sleep", scene);
    if (const Json* j = Reader::get(root, "outlets"))
      p_.read_outlets(*j, "outlets", &scene->outlets);
    if (const Json* j = Reader::get(root, "sensors"))
      p_.read_sensors(*j, "sensors", &scene->sensors);
    p_.check_references(*scene);
  }

 private:
  void read_gravity(const Json& root, SceneDef* scene) {
    const Json* j = Reader::get(root, "gravity");
    if (!j) return;
    if (j->is_string()) {
      const auto& name = j->get_ref<const std::string&>();
      if (name == "earth") {
        scene->gravity = Vec3(0, 0, -earth_gravity_cgs);
      } else if (name == "paper") {
        scene->gravity = Vec3(0, 0, -paper_gravity_cgs);
      } else {
        std::string reason =
            "must be a list of 3 numbers, \"earth\" or \"paper\", got " + in_quotes(name);
        if (auto guess = closest(name, {"earth", "paper"})) {
          reason += " (did you mean \"" + std::string(*guess) + "\"?)";
        }
        r_.fail("gravity", reason);
      }
      return;
    }
    if (!j->is_array()) {
      r_.fail("gravity",
              "must be a list of 3 numbers, \"earth\" or \"paper\", got " + describe(*j));
      return;
    }
    if (auto g = r_.vec3(*j, "gravity")) scene->gravity = *g;
  }

  // A typo in duration or time_step (1e-10 for 1e-5) must not start a run of years.
  void check_step_count(const SceneDef& scene) {
    const double steps = scene.duration / scene.time_step;
    if (steps > kMaxSteps) {
      r_.fail("duration", "duration " + format_number(scene.duration) + " at time_step " +
                              format_number(scene.time_step) + " needs " + format_number(steps) +
                              " steps; at most 1e9 are allowed");
    }
  }

  void read_contact(const Json& j, const std::string& path, ContactDef* contact) {
    if (!r_.object(j, path)) return;
    r_.check_keys(j, path, kContactKeys);
    if (const Json* m = Reader::get(j, "model")) {
      if (auto model = r_.choice<ContactModel>(*m, child(path, "model"),
                                               {{"semm", ContactModel::semm},
                                                {"semm-paper", ContactModel::semm_paper},
                                                {"penalty", ContactModel::penalty}})) {
        contact->model = *model;
      }
    }
    const bool paper = contact->model == ContactModel::semm_paper;
    contact->normals = paper ? PatchNormals::paper : PatchNormals::faces;
    contact->points = paper ? PatchPoints::one : PatchPoints::corners;
    if (const Json* n = Reader::get(j, "normals")) {
      if (auto normals = r_.choice<PatchNormals>(
              *n, child(path, "normals"),
              {{"paper", PatchNormals::paper}, {"faces", PatchNormals::faces}})) {
        contact->normals = *normals;
      }
    }
    if (const Json* n = Reader::get(j, "points")) {
      if (auto points = r_.choice<PatchPoints>(
              *n, child(path, "points"),
              {{"one", PatchPoints::one}, {"corners", PatchPoints::corners}})) {
        contact->points = *points;
      }
    }
    r_.read_number(j, path, "friction", &contact->friction, Bound::non_negative);
    r_.read_number(j, path, "restitution", &contact->restitution, Bound::unit_interval);
    const Json* stiffness = Reader::get(j, "stiffness");
    const bool stiffness_ok =
        r_.read_number(j, path, "stiffness", &contact->stiffness, Bound::non_negative);
    r_.read_number(j, path, "damping", &contact->damping, Bound::non_negative);
    if (const Json* l = Reader::get(j, "law")) {
      if (auto law = r_.choice<PenaltyLaw>(
              *l, child(path, "law"),
              {{"linear", PenaltyLaw::linear}, {"hertz", PenaltyLaw::hertz}})) {
        contact->law = *law;
      }
    }
    r_.read_number(j, path, "tolerance", &contact->tolerance, Bound::positive);
    r_.read_int(j, path, "max_sweeps", &contact->max_sweeps, 1, 1'000'000);
    r_.read_int(j, path, "substeps", &contact->substeps, 1, 1'000);
    r_.read_int(j, path, "max_substeps", &contact->max_substeps, 1, 1'000);
    r_.read_number(j, path, "substep_motion", &contact->substep_motion, Bound::positive);
    // Only the choice of sub-steps per step reads it: a scene that sets it alone would run with
    // `substeps` fixed while its author believes the count follows the motion.
    if (Reader::get(j, "substep_motion") && !Reader::get(j, "max_substeps"))
      r_.fail(child(path, "substep_motion"),
              "has no effect without max_substeps (the most sub-steps a step may take)");
    if (contact->max_substeps > 0 && contact->max_substeps < contact->substeps)
      r_.fail(child(path, "max_substeps"), "must be at least substeps (" +
                                               std::to_string(contact->substeps) + "), got " +
                                               std::to_string(contact->max_substeps));
    r_.read_bool(j, path, "pair_cache", &contact->pair_cache);
    if (const Json* o = Reader::get(j, "sweep_order")) {
      if (auto coloured = r_.choice<bool>(*o, child(path, "sweep_order"),
                                          {{"patches", false}, {"colours", true}})) {
        contact->colour_sweeps = *coloured;
      }
    }
    if (const Json* m = Reader::get(j, "margin")) {
      if (m->is_string() && m->get_ref<const std::string&>() == "auto") {
        contact->margin.reset();
      } else if (m->is_number()) {
        if (auto margin = r_.number(*m, child(path, "margin"), Bound::non_negative))
          contact->margin = *margin;
      } else {
        r_.fail(child(path, "margin"),
                "must be \"auto\" or a non-negative number, got " + describe(*m));
      }
    }
    if (const Json* v = Reader::get(j, "solver")) {
      if (auto solver = r_.choice<ContactSolver>(*v, child(path, "solver"),
                                                 {{"rows", ContactSolver::rows},
                                                  {"blocks", ContactSolver::blocks},
                                                  {"newton", ContactSolver::newton}})) {
        contact->solver = *solver;
      }
    }
    if (const Json* a = Reader::get(j, "acceleration")) {
      if (auto cg = r_.choice<bool>(*a, child(path, "acceleration"),
                                    {{"none", false}, {"conjugate_gradients", true}})) {
        contact->conjugate_gradients = *cg;
      }
    }
    if (const Json* p = Reader::get(j, "pairs"))
      p_.read_pairs(*p, child(path, "pairs"), &contact->pairs);
    // Cundall and Strack's ratio when not given.
    contact->tangential_stiffness = 2.0 / 7.0 * contact->stiffness;
    r_.read_number(j, path, "tangential_stiffness", &contact->tangential_stiffness,
                   Bound::non_negative);
    // The penalty model has no spring without a stiffness; the others ignore it.
    if (contact->model == ContactModel::penalty) {
      if (!stiffness) {
        r_.fail(path, "missing required key 'stiffness' (the \"penalty\" model needs it)");
      } else if (stiffness_ok && !(contact->stiffness > 0)) {
        r_.fail(child(path, "stiffness"),
                "must be a positive number for the \"penalty\" model, got " +
                    format_number(contact->stiffness));
      }
    }
  }

  bool read_container(const Json& j, const std::string& path, ContainerDef* container) {
    const bool ok =
        scene_io::read_box(r_, j, path, &container->min, &container->max, kContainerKeys);
    if (j.is_object()) p_.read_material(j, path, &container->material);
    return ok;
  }

  void read_walls(const Json& j, const std::string& path, std::vector<WallDef>* walls) {
    if (!j.is_array()) {
      r_.fail(path,
              "must be a list of walls ({\"point\": [..], \"normal\": [..]}), got " + describe(j));
      return;
    }
    for (std::size_t i = 0; i < j.size(); ++i) {
      const std::string wpath = element(path, i);
      if (!r_.object(j[i], wpath)) continue;
      r_.check_keys(j[i], wpath, kWallKeys);
      WallDef wall;
      const bool point_ok = r_.read_vec3(j[i], wpath, "point", &wall.point, Bound::any, true);
      const bool normal_ok = r_.read_vec3(j[i], wpath, "normal", &wall.normal, Bound::any, true) &&
                             scene_io::unit_normal(r_, child(wpath, "normal"), &wall.normal,
                                                   "it says which side bodies are on");
      p_.read_material(j[i], wpath, &wall.material);
      p_.read_removed_at(j[i], wpath, &wall.removed_at);
      if (point_ok && normal_ok) walls->push_back(wall);
    }
  }

  void read_output(const Json& j, const std::string& path, OutputDef* output) {
    if (!r_.object(j, path)) return;
    r_.check_keys(j, path, kOutputKeys);
    r_.read_number(j, path, "interval", &output->interval, Bound::positive);
    r_.read_number(j, path, "checkpoint_interval", &output->checkpoint_interval,
                   Bound::non_negative);
    r_.read_bool(j, path, "paraview", &output->paraview);
  }

  // Both keys are required: a speed under which a body counts as at rest depends on the
  // scene's units and scale, so no default would fit every scene.
  void read_sleep(const Json& j, const std::string& path, SceneDef* scene) {
    if (!r_.object(j, path)) return;
    r_.check_keys(j, path, kSleepKeys);
    SleepDef sleep;
    const bool speed_ok = r_.read_number(j, path, "speed", &sleep.speed, Bound::positive, true);
    const bool time_ok = r_.read_number(j, path, "time", &sleep.time, Bound::positive, true);
    if (speed_ok && time_ok) scene->sleep = sleep;
  }

  void read_bodies(const Json& j, const std::string& path, std::vector<BodyDef>* bodies,
                   bool may_be_empty) {
    if (!j.is_array()) {
      r_.fail(path, "must be a list of bodies, got " + describe(j));
      return;
    }
    if (j.empty() && !may_be_empty) {
      r_.fail(path, "must list at least one body, got an empty list");
      return;
    }
    std::map<std::string, std::size_t> first_index;  // name -> first body that uses it
    for (std::size_t i = 0; i < j.size(); ++i) {
      BodyDef body;
      body.path = element(path, i);
      body.shape.path = child(body.path, "shape");
      const bool name_ok = read_body(j[i], &body);
      if (!name_ok) p_.body_names_incomplete();
      if (name_ok) {
        const auto [it, fresh] = first_index.emplace(body.name, i);
        if (!fresh) {
          r_.fail(child(body.path, "name"), "name " + in_quotes(body.name) + " is used by both " +
                                                element(path, it->second) + " and " + body.path +
                                                "; body names must be unique");
        }
      }
      bodies->push_back(std::move(body));
    }
  }

  // Returns whether the body has a valid name (for the uniqueness check).
  bool read_body(const Json& j, BodyDef* body) {
    const std::string& path = body->path;
    if (!r_.object(j, path)) return false;
    r_.check_keys(j, path, kBodyKeys, [&](std::string_view key) -> std::string {
      if (key == "scale")
        return "unknown key 'scale' (a size factor drawn per copy belongs to the body of a fill "
               "or an inlet; a mesh shape takes its own 'scale')";
      return "";
    });
    bool name_ok = false;
    if (const Json* n = r_.need(j, path, "name")) name_ok = read_name(*n, path, &body->name);
    if (const Json* s = r_.need(j, path, "shape")) {
      read_shape(*s, body->shape.path, &body->shape, /*is_part=*/false, 0);
    }
    r_.read_number(j, path, "density", &body->density, Bound::positive);
    r_.read_vec3(j, path, "position", &body->position, Bound::any, true);
    read_orientation(j, path, &body->rotation, &body->orientation_given);
    r_.read_vec3(j, path, "velocity", &body->velocity);
    r_.read_vec3(j, path, "angular_velocity", &body->angular_velocity);
    const bool fixed_ok = r_.read_bool(j, path, "fixed", &body->fixed);
    p_.read_material(j, path, &body->material);
    if (const Json* m = Reader::get(j, "motion")) {
      MotionDef motion;
      p_.read_motion(*m, child(path, "motion"), &motion);
      body->motion = motion;
      if (fixed_ok && body->fixed)
        r_.fail(child(path, "fixed"),
                "a body with a prescribed motion is moved by it; drop 'fixed' (a body without "
                "'motion' that is fixed stands still)");
    }
    p_.read_removed_at(j, path, &body->removed_at);
    return name_ok;
  }

  void read_fills(const Json& j, const std::string& path, SceneDef* scene) {
    std::vector<FillDef>* fills = &scene->fill;
    if (!j.is_array()) {
      r_.fail(path, "must be a list of fills ({\"name\", \"count\", \"region\", \"body\"}), got " +
                        describe(j));
      return;
    }
    for (std::size_t i = 0; i < j.size(); ++i) {
      FillDef fill;
      fill.path = element(path, i);
      const std::string& fpath = fill.path;
      if (!r_.object(j[i], fpath)) continue;
      r_.check_keys(j[i], fpath, kFillKeys);
      if (const Json* n = r_.need(j[i], fpath, "name")) {
        if (!read_name(*n, fpath, &fill.name)) p_.body_names_incomplete();
      }
      r_.read_int(j[i], fpath, "count", &fill.count, 1, kMaxFillCount, true);
      if (const Json* region = r_.need(j[i], fpath, "region")) {
        const std::string rpath = child(fpath, "region");
        if (scene_io::read_box(r_, *region, rpath, &fill.region_min, &fill.region_max,
                               kRegionKeys) &&
            scene->container)
          check_inside_container({fill.region_min, fill.region_max}, *scene->container, rpath);
      }
      int seed = 1;
      if (r_.read_int(j[i], fpath, "seed", &seed, 0, std::numeric_limits<int>::max()))
        fill.seed = static_cast<std::uint64_t>(seed);
      fill.body.path = child(fpath, "body");
      fill.body.shape.path = child(fill.body.path, "shape");
      if (const Json* b = r_.need(j[i], fpath, "body")) read_fill_body(*b, &fill.body);
      fills->push_back(std::move(fill));
    }
  }

  // The template of a fill: a body without name and pose, which the fill gives each copy.
  void read_fill_body(const Json& j, BodyDef* body) {
    const std::string& path = body->path;
    if (!r_.object(j, path)) return;
    r_.check_keys(j, path, kFillBodyKeys, [&](std::string_view key) -> std::string {
      if (key == "name" || contains(kPoseKeys, key))
        return "unknown key '" + std::string(key) +
               "' (a fill names and places its bodies itself: set 'name' and 'region' on the "
               "fill)";
      return template_key_reason(key, "fill");
    });
    if (const Json* s = r_.need(j, path, "shape"))
      read_shape(*s, body->shape.path, &body->shape, /*is_part=*/false, 0);
    r_.read_number(j, path, "density", &body->density, Bound::positive);
    r_.read_vec3(j, path, "velocity", &body->velocity);
    r_.read_vec3(j, path, "angular_velocity", &body->angular_velocity);
    r_.read_bool(j, path, "fixed", &body->fixed);
    read_template_material_and_scale(j, body);
  }

  // Keys of a plain body that a template (of a fill or an inlet) does not take.
  static std::string template_key_reason(std::string_view key, const std::string& maker) {
    if (key == "motion" || key == "removed_at")
      return "unknown key '" + std::string(key) + "' (the copies made by a " + maker +
             " move freely; prescribed motion and removal belong to bodies of 'bodies', and an "
             "outlet removes copies)";
    return "";
  }

  void read_template_material_and_scale(const Json& j, BodyDef* body) {
    p_.read_material(j, body->path, &body->material);
    if (const Json* s = Reader::get(j, "scale")) {
      ScaleDef scale;
      if (p_.read_scale(*s, child(body->path, "scale"), &scale)) body->scale = scale;
    }
  }

  void read_inlets(const Json& j, const std::string& path, SceneDef* scene) {
    if (!j.is_array()) {
      r_.fail(path,
              "must be a list of inlets ({\"name\", \"region\", \"rate\", \"count\", "
              "\"body\"}), got " +
                  describe(j));
      return;
    }
    for (std::size_t i = 0; i < j.size(); ++i) {
      InletDef inlet;
      inlet.path = element(path, i);
      const std::string& ipath = inlet.path;
      if (!r_.object(j[i], ipath)) continue;
      r_.check_keys(j[i], ipath, kInletKeys);
      if (const Json* n = r_.need(j[i], ipath, "name")) read_name(*n, ipath, &inlet.name);
      if (const Json* region = r_.need(j[i], ipath, "region")) {
        const std::string rpath = child(ipath, "region");
        if (p_.read_region(*region, rpath, &inlet.region) && scene->container)
          check_inside_container(inlet.region, *scene->container, rpath);
      }
      r_.read_number(j[i], ipath, "rate", &inlet.rate, Bound::positive, true);
      r_.read_int(j[i], ipath, "count", &inlet.count, 1, kMaxFillCount, true);
      r_.read_number(j[i], ipath, "start", &inlet.start, Bound::non_negative);
      int seed = 1;
      if (r_.read_int(j[i], ipath, "seed", &seed, 0, std::numeric_limits<int>::max()))
        inlet.seed = static_cast<std::uint64_t>(seed);
      r_.read_vec3(j[i], ipath, "velocity", &inlet.velocity);
      inlet.body.path = child(ipath, "body");
      inlet.body.shape.path = child(inlet.body.path, "shape");
      if (const Json* b = r_.need(j[i], ipath, "body")) read_inlet_body(*b, &inlet.body);
      scene->inlets.push_back(std::move(inlet));
    }
  }

  // The template of an inlet: a body without name, pose or velocity (the inlet gives those).
  void read_inlet_body(const Json& j, BodyDef* body) {
    const std::string& path = body->path;
    if (!r_.object(j, path)) return;
    r_.check_keys(j, path, kInletBodyKeys, [&](std::string_view key) -> std::string {
      if (key == "name" || contains(kPoseKeys, key))
        return "unknown key '" + std::string(key) +
               "' (an inlet names and places its bodies itself: set 'name' and 'region' on the "
               "inlet)";
      if (key == "velocity")
        return "unknown key 'velocity' (the velocity of an inlet's copies goes on the inlet: "
               "set 'velocity' there)";
      if (key == "fixed") return "unknown key 'fixed' (an inlet's copies move freely)";
      return template_key_reason(key, "inlet");
    });
    if (const Json* s = r_.need(j, path, "shape"))
      read_shape(*s, body->shape.path, &body->shape, /*is_part=*/false, 0);
    r_.read_number(j, path, "density", &body->density, Bound::positive);
    r_.read_vec3(j, path, "angular_velocity", &body->angular_velocity);
    read_template_material_and_scale(j, body);
  }

  // A fill or an inlet places its copies inside its region; with a container, that must be
  // inside too (copies placed outside would be shoved in by the overlap correction).
  void check_inside_container(const RegionDef& region, const ContainerDef& container,
                              const std::string& path) {
    static constexpr const char* kAxisNames[] = {"x", "y", "z"};
    for (int k = 0; k < 3; ++k) {
      if (region.min[k] < container.min[k] || region.max[k] > container.max[k]) {
        r_.fail(path, std::string("must lie inside the container, but along ") + kAxisNames[k] +
                          " it spans [" + format_number(region.min[k]) + ", " +
                          format_number(region.max[k]) + "] and the container [" +
                          format_number(container.min[k]) + ", " + format_number(container.max[k]) +
                          "]");
        return;
      }
    }
  }

  // Names go into CSV columns and contact rows, where "wall" already names the walls.
  bool read_name(const Json& j, const std::string& body_path, std::string* name) {
    return scene_io::read_name(r_, j, child(body_path, "name"), name, /*wall_reserved=*/true);
  }

  void read_shape(const Json& j, const std::string& path, ShapeDef* shape, bool is_part,
                  int depth) {
    shape->path = path;
    if (!r_.object(j, path)) return;
    std::optional<ShapeType> type;
    if (const Json* t = r_.need(j, path, "type")) {
      type = r_.choice(*t, child(path, "type"), shape_type_names());
    }

    // Keys: those of this type, or of any type when the type is unknown.
    KeyList allowed = {"type"};
    for (const auto& [name, value] : shape_type_names()) {
      if (type && value != *type) continue;
      for (std::string_view key : shape_keys(value)) {
        if (!contains(allowed, key)) allowed.push_back(key);
      }
    }
    if (is_part) allowed.insert(allowed.end(), kPoseKeys.begin(), kPoseKeys.end());
    r_.check_keys(j, path, allowed, [&](std::string_view key) -> std::string {
      if (!is_part && contains(kPoseKeys, key)) {
        return "unknown key '" + std::string(key) +
               "' (a body's pose goes on the body, not on its shape; only the blocks of a "
               "compound have their own)";
      }
      if (!type) return "";
      for (const auto& [name, value] : shape_type_names()) {
        if (value != *type && contains(shape_keys(value), key)) {
          return "key '" + std::string(key) + "' does not apply to a " +
                 std::string(shape_type_name(*type)) + " shape (it takes " +
                 join_quoted(shape_keys(*type)) + ")";
        }
      }
      return "";
    });
    if (!type) return;
    shape->type = *type;

    if (is_part) {
      r_.read_vec3(j, path, "position", &shape->position);
      read_orientation(j, path, &shape->rotation, &shape->orientation_given);
    }
    switch (*type) {
      case ShapeType::prism:
        r_.read_int(j, path, "sides", &shape->sides, 3, kMaxPolygonSides, true);
        r_.read_number(j, path, "radius", &shape->radius, Bound::positive, true);
        r_.read_number(j, path, "height", &shape->height, Bound::positive, true);
        read_axis(j, path, &shape->axis);
        break;
      case ShapeType::ring:
        read_ring(j, path, shape);
        break;
      case ShapeType::box:
        r_.read_vec3(j, path, "size", &shape->size, Bound::positive, true);
        break;
      case ShapeType::convex:
        read_points(j, path, shape);
        break;
      case ShapeType::compound:
        read_compound(j, path, shape, depth);
        break;
      case ShapeType::mesh:
        read_mesh(j, path, shape);
        break;
    }
  }

  void read_ring(const Json& j, const std::string& path, ShapeDef* shape) {
    // `segments` may be left at its default; only a bad value stops the blocks check below.
    const bool segments_ok =
        r_.read_int(j, path, "segments", &shape->segments, 3, kMaxPolygonSides) ||
        !Reader::get(j, "segments");
    r_.read_int(j, path, "sides", &shape->sides, 3, kMaxPolygonSides);
    const bool radius_ok = r_.read_number(j, path, "radius", &shape->radius, Bound::positive, true);
    const bool section_ok =
        r_.read_number(j, path, "section_radius", &shape->section_radius, Bound::positive, true);
    if (radius_ok && section_ok && !(shape->section_radius < shape->radius)) {
      r_.fail(child(path, "section_radius"),
              "must be smaller than radius (" + format_number(shape->radius) + "), got " +
                  format_number(shape->section_radius) + " (the ring would have no hole)");
    }
    // Default: one block per segment, which keeps every block convex.
    shape->blocks = shape->segments;
    if (r_.read_int(j, path, "blocks", &shape->blocks, 1, kMaxPolygonSides) && segments_ok &&
        shape->segments % shape->blocks != 0) {
      r_.fail(child(path, "blocks"), "must divide segments (" + std::to_string(shape->segments) +
                                         ") evenly, got " + std::to_string(shape->blocks));
    }
    read_axis(j, path, &shape->axis);
    r_.read_bool(j, path, "allow_nonconvex", &shape->allow_nonconvex);
  }

  void read_points(const Json& j, const std::string& path, ShapeDef* shape) {
    const Json* p = r_.need(j, path, "points");
    if (!p) return;
    const std::string ppath = child(path, "points");
    if (!p->is_array() || p->size() < 4) {
      r_.fail(ppath, "must be a list of at least 4 points ([x, y, z] each), got " + describe(*p));
      return;
    }
    std::vector<Vec3> points;
    bool good = true;
    for (std::size_t i = 0; i < p->size(); ++i) {
      const auto v = r_.vec3((*p)[i], element(ppath, i));
      good = good && v.has_value();
      if (v) points.push_back(*v);
    }
    if (good) shape->points = std::move(points);
  }

  // The file itself is read, checked and cut once the whole scene has been read
  // (load_meshes below): a scene with a typo elsewhere does not wait for a decomposition.
  void read_mesh(const Json& j, const std::string& path, ShapeDef* shape) {
    if (const Json* f = r_.need(j, path, "file")) {
      if (auto file = r_.string(*f, child(path, "file"))) {
        if (file->empty())
          r_.fail(child(path, "file"), "must name a mesh file (.obj, .stl, .ply or .off)");
        else
          shape->file = *file;
      }
    }
    r_.read_number(j, path, "scale", &shape->scale, Bound::positive);
    if (const Json* b = Reader::get(j, "blocks")) {
      if (auto cutting = r_.choice<MeshCutting>(
              *b, child(path, "blocks"),
              {{"exact", MeshCutting::exact}, {"approximate", MeshCutting::approximate}})) {
        shape->cutting = *cutting;
      }
    }
    r_.read_int(j, path, "max_blocks", &shape->max_blocks, 1, kMaxMeshBlocks);
  }

  void read_compound(const Json& j, const std::string& path, ShapeDef* shape, int depth) {
    const Json* b = r_.need(j, path, "blocks");
    if (!b) return;
    const std::string bpath = child(path, "blocks");
    if (!b->is_array() || b->empty()) {
      r_.fail(bpath, "must be a non-empty list of shapes, got " + describe(*b));
      return;
    }
    if (depth >= kMaxCompoundDepth) {
      r_.fail(bpath, "compounds nest too deeply (at most " + std::to_string(kMaxCompoundDepth) +
                         " levels)");
      return;
    }
    for (std::size_t k = 0; k < b->size(); ++k) {
      ShapeDef part;
      read_shape((*b)[k], element(bpath, k), &part, /*is_part=*/true, depth + 1);
      shape->parts.push_back(std::move(part));
    }
  }

  void read_axis(const Json& obj, const std::string& path, Axis* out) {
    if (const Json* j = Reader::get(obj, "axis")) {
      if (auto a = r_.choice<Axis>(*j, child(path, "axis"),
                                   {{"x", Axis::x}, {"y", Axis::y}, {"z", Axis::z}})) {
        *out = *a;
      }
    }
  }

  // euler_zxz_deg or quaternion (or neither: identity) of a body or a compound's part.
  void read_orientation(const Json& obj, const std::string& path, Mat3* out,
                        std::vector<Real>* given) {
    const Json* euler = Reader::get(obj, "euler_zxz_deg");
    const Json* quaternion = Reader::get(obj, "quaternion");
    if (euler && quaternion) {
      r_.fail(path, "gives both 'euler_zxz_deg' and 'quaternion'; give one orientation only");
      return;
    }
    if (euler) {
      if (auto angles = r_.vec3(*euler, child(path, "euler_zxz_deg"))) {
        *out = rotation_from_euler_zxz_deg(*angles);
        *given = {angles->x(), angles->y(), angles->z()};
      }
    } else if (quaternion) {
      const std::string qpath = child(path, "quaternion");
      const auto q = r_.numbers(*quaternion, qpath, 4, Bound::any);
      if (!q) return;
      const Real norm =
          std::sqrt((*q)[0] * (*q)[0] + (*q)[1] * (*q)[1] + (*q)[2] * (*q)[2] + (*q)[3] * (*q)[3]);
      if (!(std::abs(norm - 1) <= kQuaternionNormTolerance)) {
        r_.fail(qpath, "must be a unit quaternion [w, x, y, z], but its norm is " +
                           format_number(norm) +
                           " (it must be within 1e-6 of 1; divide by the norm)");
        return;
      }
      *out = rotation_from_quaternion((*q)[0], (*q)[1], (*q)[2], (*q)[3]);
      *given = {(*q)[0], (*q)[1], (*q)[2], (*q)[3]};
    }
  }

  Reader r_;
  scene_io::ProcessReader p_{r_};
};

}  // namespace

Mat3 rotation_from_euler_zxz_deg(const Vec3& angles_deg) {
  const auto [c1, s1] = cos_sin_deg(angles_deg[0]);
  const auto [c2, s2] = cos_sin_deg(angles_deg[1]);
  const auto [c3, s3] = cos_sin_deg(angles_deg[2]);
  // g = Rz(phi) Rx(theta) Rz(psi), as euler_zxz() in scene_def.hpp.
  return rotation_z_cs(c1, s1) * rotation_x_cs(c2, s2) * rotation_z_cs(c3, s3);
}

Mat3 rotation_from_quaternion(Real w, Real x, Real y, Real z) {
  return Quat(w, x, y, z).normalized().toRotationMatrix();
}

namespace {

// The name of a text encoding other than UTF-8 that `text` is in, told by its byte order mark or
// by NUL bytes (which UTF-8 JSON never holds; UTF-16 and UTF-32 text of ASCII characters does),
// or nullopt. Without this, JSON's parser reports "invalid literal" at the first byte.
std::optional<std::string> wide_encoding(const std::string& text) {
  const auto starts = [&](std::string_view bom) { return text.compare(0, bom.size(), bom) == 0; };
  using namespace std::string_view_literals;
  if (starts("\x00\x00\xFE\xFF"sv)) return "UTF-32 text (big-endian byte order mark)";
  if (starts("\xFF\xFE\x00\x00"sv)) return "UTF-32 text (little-endian byte order mark)";
  if (starts("\xFE\xFF"sv)) return "UTF-16 text (big-endian byte order mark FE FF)";
  if (starts("\xFF\xFE"sv)) return "UTF-16 text (little-endian byte order mark FF FE)";
  if (text.find('\0') != std::string::npos)
    return "not UTF-8 text: it holds NUL bytes, as UTF-16 or UTF-32 text does";
  return std::nullopt;
}

}  // namespace

SceneReadResult read_scene_text(const std::string& text, const std::string& source_name) {
  SceneReadResult result;
  result.scene.source = source_name;
  auto& problems = result.problems;
  try {
    if (json::blank(text)) {
      problems.push_back({"", "the file is empty (expected a JSON object: {...})"});
      return result;
    }
    if (const auto encoding = wide_encoding(text)) {
      problems.push_back({"", "the file is " + *encoding +
                                  "; scene files are read as UTF-8 only: save it as UTF-8"});
      return result;
    }
    json::PathTracker tracker(into(&problems));
    Json root;
    try {
      root = Json::parse(text, [&tracker](int depth, Json::parse_event_t event, Json& parsed) {
        return tracker(depth, event, parsed);
      });
    } catch (const Json::parse_error& e) {
      problems.push_back({"", json::syntax_message(text, e)});
      return result;
    } catch (const Json::out_of_range& e) {
      // Thrown for a number beyond the range of a double, e.g. 1e400.
      std::string reason = e.what();
      const std::size_t quote = reason.find('\'');
      const std::string number = quote == std::string::npos ? "" : " " + reason.substr(quote);
      problems.push_back({tracker.pending_path(), "must be a finite number, got" + number +
                                                      ", which is too large for a double"});
      return result;
    }
    SceneReader(&problems).read_scene(root, &result.scene);
  } catch (const std::exception& e) {
    // Not expected; the promise is that bad input never throws, so report it as a problem.
    problems.push_back({"", std::string("internal error while reading the scene: ") + e.what()});
  }
  return result;
}

std::string format_problem(const std::string& source_name, const SceneProblem& problem) {
  if (problem.path.empty()) return source_name + ": " + problem.message;
  return source_name + ": " + problem.path + ": " + problem.message;
}

}  // namespace tem
