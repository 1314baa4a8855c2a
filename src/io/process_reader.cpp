// The granular-process keys of a scene file (see process_reader.hpp). One function per object
// of the format, each checking its keys first; references between objects are kept and checked
// once the whole scene is read, so that they may be given in any order.
#include "io/process_reader.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <string_view>

namespace tem::scene_io {
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

const KeyList kMaterialKeys = {"friction", "restitution", "rolling_resistance"};
const KeyList kPairKeys = {"materials", "friction", "restitution", "rolling_resistance"};
const KeyList kMotionKeys = {"velocity", "angular_velocity", "center", "start",
                             "end",      "oscillation",      "surface_velocity"};
const KeyList kOscillationKeys = {"amplitude", "frequency"};
const KeyList kScaleKeys = {"min", "max"};
const KeyList kRegionKeys = {"min", "max"};
const KeyList kOutletKeys = {"name", "region"};

const std::vector<std::pair<std::string_view, SensorType>> kSensorTypes = {
    {"plane", SensorType::plane}, {"force", SensorType::force}, {"region", SensorType::region}};

std::string_view sensor_type_name(SensorType type) {
  for (const auto& [name, value] : kSensorTypes) {
    if (value == type) return name;
  }
  return "?";
}

// Keys a sensor of each type takes, besides `name` and `type`.
const KeyList& sensor_keys(SensorType type) {
  static const std::map<SensorType, KeyList> keys = {{SensorType::plane, {"point", "normal"}},
                                                     {SensorType::force, {"bodies"}},
                                                     {SensorType::region, {"region"}}};
  return keys.at(type);
}

constexpr const char* kAxisNames[] = {"x", "y", "z"};

// "NAME_<k>" -> (NAME, k) when k is written as std::to_string writes it (no sign, no leading
// zero), as the names of fill and inlet copies are; nothing otherwise.
std::optional<std::pair<std::string, long long>> split_copy_name(const std::string& name) {
  const std::size_t underscore = name.rfind('_');
  if (underscore == std::string::npos || underscore + 1 >= name.size()) return std::nullopt;
  const std::string digits = name.substr(underscore + 1);
  if (digits.size() > 18 || (digits.size() > 1 && digits[0] == '0')) return std::nullopt;
  if (!std::all_of(digits.begin(), digits.end(),
                   [](char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; }))
    return std::nullopt;
  return std::make_pair(name.substr(0, underscore), std::stoll(digits));
}

// Whether a force sensor's "prefix*" entry can name a body of the run: one of 'bodies', or a
// copy NAME_<k> made by a fill or an inlet.
bool prefix_names_a_body(const SceneDef& scene, const std::string& entry) {
  const auto names = [&](const std::string& name) { return sensor_entry_names(entry, name); };
  for (const BodyDef& b : scene.bodies)
    if (names(b.name)) return true;
  const std::string prefix = entry.substr(0, entry.size() - 1);
  // The copies of `source` (count of them) that the prefix names: all of them when the prefix is
  // a start of "NAME_"; otherwise those whose number starts with the prefix's digits after it.
  const auto names_a_copy = [&](const std::string& source, long long count) {
    if (count <= 0) return false;
    const std::string stem = source + "_";
    if (stem.compare(0, prefix.size(), prefix) == 0 && prefix.size() <= stem.size()) return true;
    if (prefix.compare(0, stem.size(), stem) != 0) return false;
    const std::string digits = prefix.substr(stem.size());
    if (!std::all_of(digits.begin(), digits.end(),
                     [](char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; }) ||
        digits.size() > 18 || (digits.size() > 1 && digits[0] == '0'))
      return false;
    if (digits == "0") return true;
    // Some k < count whose decimal digits start with `digits`: the smallest is `digits` itself.
    return std::stoll(digits) < count;
  };
  for (const FillDef& f : scene.fill)
    if (names_a_copy(f.name, f.count)) return true;
  for (const InletDef& i : scene.inlets)
    if (names_a_copy(i.name, i.count)) return true;
  return false;
}

// 'name' as the brief messages show it, or in_quotes() when it needs escaping or cutting.
std::string quoted_name(const std::string& name) {
  const std::string quoted = in_quotes(name);
  if (quoted == "\"" + name + "\"") return "'" + name + "'";
  return quoted;
}

}  // namespace

// ---- Shared pieces -----------------------------------------------------------------------

bool check_name(Reader& r, const std::string& name, const std::string& path, bool wall_reserved) {
  if (name.empty()) {
    r.fail(path, "must not be empty");
    return false;
  }
  const bool bad_char = std::any_of(name.begin(), name.end(), [](char c) {
    return c == ',' || c == '"' || std::iscntrl(static_cast<unsigned char>(c));
  });
  if (bad_char) {
    r.fail(path,
           "must not contain commas, quotes or control characters (it becomes a CSV field), "
           "got " +
               in_quotes(name));
    return false;
  }
  if (wall_reserved && name == "wall") {
    r.fail(path, "\"wall\" is reserved: contacts.csv uses it for walls");
    return false;
  }
  return true;
}

bool read_name(Reader& r, const Json& j, const std::string& path, std::string* name,
               bool wall_reserved) {
  const auto s = r.string(j, path);
  if (!s || !check_name(r, *s, path, wall_reserved)) return false;
  *name = *s;
  return true;
}

bool read_box(Reader& r, const Json& j, const std::string& path, Vec3* min, Vec3* max,
              const KeyList& allowed) {
  if (!r.object(j, path)) return false;
  r.check_keys(j, path, allowed);
  Vec3 lo = *min, hi = *max;
  const bool min_ok = r.read_vec3(j, path, "min", &lo, Bound::any, true);
  const bool max_ok = r.read_vec3(j, path, "max", &hi, Bound::any, true);
  if (!min_ok || !max_ok) return false;
  for (int k = 0; k < 3; ++k) {
    if (!(lo[k] < hi[k])) {
      r.fail(child(path, "max"), std::string("must exceed min in every component, but ") +
                                     kAxisNames[k] + " has max " + format_number(hi[k]) +
                                     " and min " + format_number(lo[k]));
      return false;
    }
  }
  *min = lo;
  *max = hi;
  return true;
}

bool unit_normal(Reader& r, const std::string& path, Vec3* normal, const std::string& why) {
  const Real length = normal->stableNorm();
  if (!(length > 0) || !std::isfinite(length)) {
    r.fail(path, "must not be zero: " + why);
    return false;
  }
  // A normal already of unit length (to rounding) is kept as written: dividing it by its
  // rounded length again could move it by an ulp, and scene.json must read back to the very
  // same scene (fuzz-found).
  if (std::abs(length - 1) > 4 * std::numeric_limits<Real>::epsilon()) *normal /= length;
  return true;
}

// ---- Materials ---------------------------------------------------------------------------

void ProcessReader::read_materials(const Json& j, const std::string& path,
                                   std::vector<MaterialDef>* materials) {
  if (!j.is_object()) {
    r_.fail(path,
            "must be an object of named materials ({\"NAME\": {\"friction\": .., "
            "\"restitution\": .., \"rolling_resistance\": ..}}), got " +
                describe(j));
    materials_readable_ = false;
    return;
  }
  for (const auto& [name, value] : j.items()) {
    MaterialDef material;
    material.path = child(path, name);
    if (!check_name(r_, name, material.path, /*wall_reserved=*/false)) continue;
    material.name = name;
    if (r_.object(value, material.path)) {
      r_.check_keys(value, material.path, kMaterialKeys);
      r_.read_number(value, material.path, "friction", &material.friction, Bound::non_negative);
      r_.read_number(value, material.path, "restitution", &material.restitution,
                     Bound::unit_interval);
      r_.read_number(value, material.path, "rolling_resistance", &material.rolling_resistance,
                     Bound::non_negative);
    }
    // Kept even when a coefficient was bad: the name is defined, and references to it are
    // not unknown.
    materials->push_back(std::move(material));
  }
  std::sort(materials->begin(), materials->end(),
            [](const MaterialDef& a, const MaterialDef& b) { return a.name < b.name; });
}

void ProcessReader::read_pairs(const Json& j, const std::string& path,
                               std::vector<MaterialPairDef>* pairs) {
  if (!j.is_array()) {
    r_.fail(path,
            "must be a list of pairs ({\"materials\": [\"a\", \"b\"], \"friction\": ..}), got " +
                describe(j));
    return;
  }
  std::map<std::pair<std::string, std::string>, std::size_t> seen;  // sorted pair -> index
  for (std::size_t i = 0; i < j.size(); ++i) {
    MaterialPairDef pair;
    pair.path = element(path, i);
    if (!r_.object(j[i], pair.path)) continue;
    r_.check_keys(j[i], pair.path, kPairKeys);
    bool names_ok = false;
    if (const Json* m = r_.need(j[i], pair.path, "materials")) {
      const std::string mpath = child(pair.path, "materials");
      if (!m->is_array() || m->size() != 2) {
        r_.fail(mpath, "must be a list of 2 material names, got " + describe(*m));
      } else {
        const auto a = r_.string((*m)[0], element(mpath, 0));
        const auto b = r_.string((*m)[1], element(mpath, 1));
        if (a && b) {
          pair.first = *a;
          pair.second = *b;
          names_ok = true;
          material_refs_.emplace_back(element(mpath, 0), *a);
          material_refs_.emplace_back(element(mpath, 1), *b);
        }
      }
    }
    auto coefficient = [&](std::string_view key, Bound bound, std::optional<Real>* out) {
      Real value = 0;
      if (r_.read_number(j[i], pair.path, key, &value, bound)) *out = value;
    };
    coefficient("friction", Bound::non_negative, &pair.friction);
    coefficient("restitution", Bound::unit_interval, &pair.restitution);
    coefficient("rolling_resistance", Bound::non_negative, &pair.rolling_resistance);
    if (names_ok) {
      const auto key = std::minmax(pair.first, pair.second);
      const auto [it, fresh] = seen.emplace(std::make_pair(key.first, key.second), i);
      if (!fresh) {
        r_.fail(child(pair.path, "materials"),
                "the pair " + in_quotes(pair.first) + ", " + in_quotes(pair.second) +
                    " is already given by " + element(path, it->second) +
                    " (a pair is the same in either order); give each pair once");
      }
    }
    pairs->push_back(std::move(pair));
  }
}

void ProcessReader::read_material(const Json& obj, const std::string& path, std::string* material) {
  const Json* m = Reader::get(obj, "material");
  if (!m) return;
  const std::string mpath = child(path, "material");
  if (auto name = r_.string(*m, mpath)) {
    *material = *name;
    material_refs_.emplace_back(mpath, *name);
  }
}

void ProcessReader::read_removed_at(const Json& obj, const std::string& path,
                                    std::optional<Real>* removed_at) {
  Real t = 0;
  if (r_.read_number(obj, path, "removed_at", &t, Bound::non_negative)) *removed_at = t;
}

// ---- Motion, scale, regions --------------------------------------------------------------

void ProcessReader::read_motion(const Json& j, const std::string& path, MotionDef* motion) {
  if (!r_.object(j, path)) return;
  r_.check_keys(j, path, kMotionKeys);
  r_.read_vec3(j, path, "velocity", &motion->velocity);
  r_.read_vec3(j, path, "angular_velocity", &motion->angular_velocity);
  Vec3 center = Vec3::Zero();
  if (r_.read_vec3(j, path, "center", &center)) motion->center = center;
  Vec3 surface = Vec3::Zero();
  if (r_.read_vec3(j, path, "surface_velocity", &surface)) motion->surface_velocity = surface;
  const bool start_ok = r_.read_number(j, path, "start", &motion->start, Bound::non_negative) ||
                        !Reader::get(j, "start");
  Real end = 0;
  if (r_.read_number(j, path, "end", &end, Bound::any)) {
    if (start_ok && !(end > motion->start)) {
      r_.fail(child(path, "end"), "must be later than start (" + format_number(motion->start) +
                                      "), got " + format_number(end));
    } else {
      motion->end = end;
    }
  }
  if (const Json* o = Reader::get(j, "oscillation")) {
    const std::string opath = child(path, "oscillation");
    if (r_.object(*o, opath)) {
      r_.check_keys(*o, opath, kOscillationKeys);
      OscillationDef oscillation;
      const bool amplitude_ok =
          r_.read_vec3(*o, opath, "amplitude", &oscillation.amplitude, Bound::any, true);
      const bool frequency_ok =
          r_.read_number(*o, opath, "frequency", &oscillation.frequency, Bound::positive, true);
      if (amplitude_ok && frequency_ok) motion->oscillation = oscillation;
    }
  }
}

bool ProcessReader::read_scale(const Json& j, const std::string& path, ScaleDef* scale) {
  if (!r_.object(j, path)) return false;
  r_.check_keys(j, path, kScaleKeys);
  ScaleDef s;
  const bool min_ok = r_.read_number(j, path, "min", &s.min, Bound::positive, true);
  const bool max_ok = r_.read_number(j, path, "max", &s.max, Bound::positive, true);
  if (!min_ok || !max_ok) return false;
  if (!(s.max >= s.min)) {
    r_.fail(child(path, "max"),
            "must be at least min (" + format_number(s.min) + "), got " + format_number(s.max));
    return false;
  }
  *scale = s;
  return true;
}

bool ProcessReader::read_region(const Json& j, const std::string& path, RegionDef* region) {
  return read_box(r_, j, path, &region->min, &region->max, kRegionKeys);
}

// ---- Outlets and sensors -----------------------------------------------------------------

void ProcessReader::read_outlets(const Json& j, const std::string& path,
                                 std::vector<OutletDef>* outlets) {
  if (!j.is_array()) {
    r_.fail(path, "must be a list of outlets ({\"name\", \"region\"}), got " + describe(j));
    return;
  }
  std::map<std::string, std::size_t> first_index;
  for (std::size_t i = 0; i < j.size(); ++i) {
    OutletDef outlet;
    outlet.path = element(path, i);
    if (!r_.object(j[i], outlet.path)) continue;
    r_.check_keys(j[i], outlet.path, kOutletKeys);
    read_list_name(j[i], path, i, outlet.path, first_index, "outlet names must be unique",
                   &outlet.name);
    if (const Json* region = r_.need(j[i], outlet.path, "region"))
      read_region(*region, child(outlet.path, "region"), &outlet.region);
    outlets->push_back(std::move(outlet));
  }
}

void ProcessReader::read_list_name(const Json& obj, const std::string& list_path,
                                   std::size_t item, const std::string& item_path,
                                   std::map<std::string, std::size_t>& first,
                                   const std::string& rule, std::string* name) {
  const Json* n = r_.need(obj, item_path, "name");
  if (!n) return;
  const std::string npath = child(item_path, "name");
  if (!read_name(r_, *n, npath, name, /*wall_reserved=*/false)) return;
  const auto [it, fresh] = first.emplace(*name, item);
  if (!fresh)
    r_.fail(npath, "name " + in_quotes(*name) + " is used by both " +
                       element(list_path, it->second) + " and " + item_path + "; " + rule);
}

void ProcessReader::read_sensors(const Json& j, const std::string& path,
                                 std::vector<SensorDef>* sensors) {
  if (!j.is_array()) {
    r_.fail(path, "must be a list of sensors ({\"name\", \"type\", ...}), got " + describe(j));
    return;
  }
  std::map<std::string, std::size_t> first_index;
  for (std::size_t i = 0; i < j.size(); ++i) {
    SensorDef sensor;
    sensor.path = element(path, i);
    const std::string& spath = sensor.path;
    if (!r_.object(j[i], spath)) continue;
    std::optional<SensorType> type;
    if (const Json* t = r_.need(j[i], spath, "type"))
      type = r_.choice(*t, child(spath, "type"), kSensorTypes);

    // Keys: those of this type, or of any type when the type is unknown.
    KeyList allowed = {"name", "type"};
    for (const auto& [name, value] : kSensorTypes) {
      if (type && value != *type) continue;
      for (std::string_view key : sensor_keys(value)) {
        if (!contains(allowed, key)) allowed.push_back(key);
      }
    }
    r_.check_keys(j[i], spath, allowed, [&](std::string_view key) -> std::string {
      if (!type) return "";
      for (const auto& [name, value] : kSensorTypes) {
        if (value != *type && contains(sensor_keys(value), key)) {
          return "key '" + std::string(key) + "' does not apply to a " +
                 std::string(sensor_type_name(*type)) + " sensor (it takes " +
                 join_quoted(sensor_keys(*type)) + ")";
        }
      }
      return "";
    });

    read_list_name(j[i], path, i, spath, first_index,
                   "sensor names must be unique (they label rows of sensors.csv)", &sensor.name);
    if (!type) continue;
    sensor.type = *type;
    switch (*type) {
      case SensorType::plane: {
        r_.read_vec3(j[i], spath, "point", &sensor.point, Bound::any, true);
        Vec3 normal = sensor.normal;
        if (r_.read_vec3(j[i], spath, "normal", &normal, Bound::any, true) &&
            unit_normal(r_, child(spath, "normal"), &normal,
                        "it says which way a crossing counts +1"))
          sensor.normal = normal;
        break;
      }
      case SensorType::force: {
        const Json* b = r_.need(j[i], spath, "bodies");
        if (!b) break;
        const std::string bpath = child(spath, "bodies");
        if (!b->is_array() || b->empty()) {
          r_.fail(bpath, "must be a non-empty list of body names, got " + describe(*b));
          break;
        }
        for (std::size_t k = 0; k < b->size(); ++k) {
          if (auto name = r_.string((*b)[k], element(bpath, k))) {
            // Named twice, a body's force and mass would be counted twice.
            const auto first = std::find(sensor.bodies.begin(), sensor.bodies.end(), *name);
            if (first != sensor.bodies.end()) {
              r_.fail(element(bpath, k),
                      "body " + quoted_name(*name) + " is already named by " +
                          element(bpath, static_cast<std::size_t>(first - sensor.bodies.begin())) +
                          "; a force sensor counts each body once, so name it once");
              continue;
            }
            sensor.bodies.push_back(*name);
            sensor_body_refs_.emplace_back(element(bpath, k), *name);
          }
        }
        break;
      }
      case SensorType::region:
        if (const Json* region = r_.need(j[i], spath, "region"))
          read_region(*region, child(spath, "region"), &sensor.region);
        break;
    }
    sensors->push_back(std::move(sensor));
  }
}

// ---- References --------------------------------------------------------------------------

void ProcessReader::check_references(const SceneDef& scene) {
  check_materials(scene);
  check_sensor_bodies(scene);
  check_copy_names(scene);
}

void ProcessReader::check_materials(const SceneDef& scene) {
  if (!materials_readable_) return;
  KeyList names;
  for (const MaterialDef& m : scene.materials) names.push_back(m.name);
  for (const auto& [path, name] : material_refs_) {
    if (contains(names, name)) continue;
    std::string reason = "unknown material " + quoted_name(name);
    if (names.empty()) {
      reason += " (the scene defines no materials: define it under 'materials')";
    } else {
      if (auto guess = closest(name, names))
        reason += " (did you mean '" + std::string(*guess) + "'?)";
      reason += " (materials are: " + join_quoted(names) + ")";
    }
    r_.fail(path, reason);
  }
}

void ProcessReader::check_sensor_bodies(const SceneDef& scene) {
  if (!body_names_complete_ || sensor_body_refs_.empty()) return;
  std::set<std::string> bodies;
  KeyList names;
  for (const BodyDef& b : scene.bodies) {
    bodies.insert(b.name);
    names.push_back(b.name);
  }
  std::map<std::string, int> fill_counts;  // and inlets' counts: their copies are named alike
  for (const FillDef& f : scene.fill) fill_counts[f.name] = std::max(fill_counts[f.name], f.count);
  for (const InletDef& i : scene.inlets)
    fill_counts[i.name] = std::max(fill_counts[i.name], i.count);
  for (const auto& [path, name] : sensor_body_refs_) {
    if (bodies.count(name)) continue;
    if (!name.empty() && name.back() == '*') {
      if (!prefix_names_a_body(scene, name)) {
        r_.fail(path, quoted_name(name) +
                          " names no body: no body of 'bodies' and no copy made by 'fill' or an "
                          "inlet has a name that starts with " +
                          quoted_name(name.substr(0, name.size() - 1)));
      }
      continue;
    }
    if (const auto copy = split_copy_name(name)) {
      const auto it = fill_counts.find(copy->first);
      if (it != fill_counts.end() && copy->second < it->second) continue;
    }
    std::string reason = "unknown body " + quoted_name(name);
    if (auto guess = closest(name, names)) {
      reason += " (did you mean '" + std::string(*guess) + "'?)";
    } else {
      reason +=
          " (a force sensor names bodies of 'bodies', copies made by 'fill' or an inlet, NAME_0 "
          "to NAME_<count-1>, or with 'PREFIX*' every body whose name starts with PREFIX)";
    }
    r_.fail(path, reason);
  }
}

// Copies are named NAME_<k>: two fills or inlets of one name, a fill and an inlet of one name,
// or a body named like one of an inlet's copies would give two bodies one name. (A body named
// like a fill's copy is found when the fill is placed.)
void ProcessReader::check_copy_names(const SceneDef& scene) {
  // name -> path of the first fill or inlet that has it
  std::map<std::string, std::string> makers;
  auto claim = [&](const std::string& name, const std::string& path) {
    if (name.empty()) return;  // unreadable: already reported
    const auto [it, fresh] = makers.emplace(name, path);
    if (!fresh)
      r_.fail(child(path, "name"), "name " + in_quotes(name) + " is used by both " + it->second +
                                       " and " + path +
                                       "; their copies (NAME_0, NAME_1, ...) would have the same "
                                       "names");
  };
  for (const FillDef& f : scene.fill) claim(f.name, f.path);
  for (const InletDef& in : scene.inlets) claim(in.name, in.path);
  if (scene.inlets.empty()) return;
  std::map<std::string, const InletDef*> inlets;
  for (const InletDef& in : scene.inlets) inlets.emplace(in.name, &in);
  for (const BodyDef& b : scene.bodies) {
    const auto copy = split_copy_name(b.name);
    if (!copy) continue;
    const auto it = inlets.find(copy->first);
    if (it == inlets.end() || copy->second >= it->second->count) continue;
    r_.fail(child(it->second->path, "name"),
            "makes the body name " + quoted_name(b.name) + ", which " + b.path +
                " already has (an inlet's copies are named NAME_0 to NAME_<count-1>)");
  }
}

}  // namespace tem::scene_io
