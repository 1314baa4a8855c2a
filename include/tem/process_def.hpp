// Definitions of what granular processes add to a scene (docs/processes.md, interface.md
// "Granular processes"): materials and their pairs, prescribed motion, size factors, regions,
// outlets and sensors. Inlets, which hold a template body, are in scene_def.hpp beside `fill`.
// Like every def, each maps one-to-one onto its scene-file object and remembers its JSON path.
#pragma once

#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "tem/types.hpp"

namespace tem {

// A named set of contact coefficients. Rolling resistance is a coefficient (0: none): the
// rolling torque is limited by it times the normal force times the rolling radius.
struct MaterialDef {
  std::string name;
  std::string path;  // "materials.NAME"
  Real friction = 0.3;
  Real restitution = 0.0;
  Real rolling_resistance = 0.0;
};

// The coefficients of one pair of materials (contact.pairs[i]); what it leaves out follows the
// rule for pairs without an entry (smaller friction, smaller restitution, larger rolling
// resistance of the two).
struct MaterialPairDef {
  std::string path;  // "contact.pairs[i]"
  std::string first, second;
  std::optional<Real> friction, restitution, rolling_resistance;
};

// A displacement amplitude * sin(2 pi frequency (t - start)) added to a prescribed motion.
struct OscillationDef {
  Vec3 amplitude = Vec3::Zero();
  Real frequency = 0;  // Hz
};

// Prescribed motion of a body (a kinematic body: it pushes and is never pushed). Between
// `start` and `end` it moves with `velocity` and turns with `angular_velocity` (world axes)
// about the axis through `center` (absent: its centre of mass at `start`); before and after it
// stands still.
struct MotionDef {
  Vec3 velocity = Vec3::Zero();
  Vec3 angular_velocity = Vec3::Zero();
  std::optional<Vec3> center;
  Real start = 0;
  Real end = std::numeric_limits<Real>::infinity();
  std::optional<OscillationDef> oscillation;
  // A conveyor belt's surface: inside the window the body's surface slides at this velocity
  // (world axes) where it touches others, along each contact's tangent plane, while the body
  // itself stays where its other motion puts it (a belt that never runs off its rollers).
  std::optional<Vec3> surface_velocity;
};

// A copy's size factor, uniform in [min, max].
struct ScaleDef {
  Real min = 1, max = 1;
};

// An axis-aligned box.
struct RegionDef {
  Vec3 min = Vec3::Zero();
  Vec3 max = Vec3::Zero();
  bool contains(const Vec3& p) const {
    return p.x() >= min.x() && p.y() >= min.y() && p.z() >= min.z() && p.x() <= max.x() &&
           p.y() <= max.y() && p.z() <= max.z();
  }
};

// Bodies whose centre of mass enters `region` are removed (their last state goes to
// removed.csv).
struct OutletDef {
  std::string path;  // "outlets[i]"
  std::string name;
  RegionDef region;
};

enum class SensorType { plane, force, region };

// One column set of sensors.csv: net crossings of a plane, the contact force and torque on
// named bodies, or the bodies inside a region.
struct SensorDef {
  std::string path;  // "sensors[i]"
  std::string name;
  SensorType type = SensorType::plane;
  Vec3 point = Vec3::Zero();    // plane
  Vec3 normal = Vec3::UnitZ();  // plane: unit, the direction that counts +1
  // force: names of bodies; an entry ending in '*' names every body whose name starts with
  // what comes before it ("feed_*": every copy of inlet "feed", as they come).
  std::vector<std::string> bodies;
  RegionDef region;  // region
};

// Whether a force sensor's entry ("name" or "prefix*") names the body called `body_name`.
inline bool sensor_entry_names(const std::string& entry, const std::string& body_name) {
  if (!entry.empty() && entry.back() == '*')
    return body_name.compare(0, entry.size() - 1, entry, 0, entry.size() - 1) == 0;
  return entry == body_name;
}

}  // namespace tem
