// Reading the granular-process keys of a scene file (interface.md "Granular processes",
// docs/scene_format.md): materials and contact.pairs, the `material`, `motion`, `removed_at`
// and `scale` keys of bodies and walls, outlets and sensors, and the checks that tie them to
// the rest of the scene (names of materials and bodies, names of inlet copies). Inlets, whose
// template body needs the shape reader, are read in scene_reader.cpp with these pieces.
//
// Same rules as scene_reader.cpp: every problem is recorded with its JSON path, nothing
// throws, and a check across fields runs only when those fields were valid on their own.
#pragma once

#include <map>
#include <string>
#include <utility>
#include <vector>

#include "io/json_reader.hpp"
#include "tem/scene_def.hpp"

namespace tem::scene_io {

// Names become CSV fields (bodies.csv, contacts.csv, sensors.csv): non-empty, without commas,
// quotes or control characters; "wall" is reserved for bodies (contacts.csv uses it for
// walls). `path` is the path of the name itself. Returns whether it was valid.
bool check_name(json::Reader& r, const std::string& name, const std::string& path,
                bool wall_reserved);
bool read_name(json::Reader& r, const json::Json& j, const std::string& path, std::string* name,
               bool wall_reserved);

// An axis-aligned box {min, max} with min < max in every component, at `path`; `allowed` its
// keys (a container also takes `material`). Returns whether both corners were valid.
bool read_box(json::Reader& r, const json::Json& j, const std::string& path, Vec3* min, Vec3* max,
              const json::KeyList& allowed);

// A plane's normal, already read at `path`: scaled to unit length unless already of unit length
// to rounding (kept bit for bit, so scene.json reads back to the same scene). False and a
// problem when zero.
// `why` ends the message ("must not be zero: WHY").
bool unit_normal(json::Reader& r, const std::string& path, Vec3* normal, const std::string& why);

// Reads the process keys and remembers the references between objects (material names, the
// bodies of force sensors) until check_references(), called once the whole scene is read.
class ProcessReader {
 public:
  explicit ProcessReader(json::Reader& r) : r_(r) {}

  // `materials`: an object NAME -> {friction, restitution, rolling_resistance}.
  void read_materials(const json::Json& j, const std::string& path,
                      std::vector<MaterialDef>* materials);
  // `contact.pairs`.
  void read_pairs(const json::Json& j, const std::string& path,
                  std::vector<MaterialPairDef>* pairs);
  // obj["material"] when present: a name checked against `materials` later.
  void read_material(const json::Json& obj, const std::string& path, std::string* material);
  // obj["removed_at"] when present (s, >= 0).
  void read_removed_at(const json::Json& obj, const std::string& path,
                       std::optional<Real>* removed_at);
  // A body's `motion` at `path`.
  void read_motion(const json::Json& j, const std::string& path, MotionDef* motion);
  // A template's `scale` at `path`: {min > 0, max >= min}.
  bool read_scale(const json::Json& j, const std::string& path, ScaleDef* scale);
  // A region {min, max} at `path`.
  bool read_region(const json::Json& j, const std::string& path, RegionDef* region);
  void read_outlets(const json::Json& j, const std::string& path, std::vector<OutletDef>* outlets);
  void read_sensors(const json::Json& j, const std::string& path, std::vector<SensorDef>* sensors);

  // Not every body name could be read: unknown bodies are then not reported (they might be the
  // unreadable ones).
  void body_names_incomplete() { body_names_complete_ = false; }

  // Once everything is read: material names against `scene.materials`, force sensors' bodies
  // against the bodies and fill copies, and the names of inlet copies against every other
  // body name.
  void check_references(const SceneDef& scene);

 private:
  void check_materials(const SceneDef& scene);
  void check_sensor_bodies(const SceneDef& scene);
  void check_copy_names(const SceneDef& scene);
  // The `name` of element `item` (path `item_path`) of the list at `list_path`, refused when an
  // earlier element took it (`first`: name -> its element); `rule` ends the message.
  void read_list_name(const json::Json& obj, const std::string& list_path, std::size_t item,
                      const std::string& item_path, std::map<std::string, std::size_t>& first,
                      const std::string& rule, std::string* name);

  json::Reader& r_;
  bool materials_readable_ = true;   // `materials` absent or an object
  bool body_names_complete_ = true;  // every body and fill name was valid
  std::vector<std::pair<std::string, std::string>> material_refs_;     // path, name
  std::vector<std::pair<std::string, std::string>> sensor_body_refs_;  // path, name
};

}  // namespace tem::scene_io
