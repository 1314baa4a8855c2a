// From a shape definition to the polyhedra of its blocks, each placed in the shape's frame.
// A compound places its parts (any shape, compounds included) by their own poses.
#pragma once

#include <string>
#include <vector>

#include "geometry/block.hpp"
#include "tem/scene_def.hpp"

namespace tem {

struct PlacedPolyhedron {
  PolyhedronDef polyhedron;
  Mat3 rotation;  // x_shape = rotation * x_polyhedron + position
  Vec3 position;
  std::string path;    // JSON path of the shape that made it
  std::string label;   // which block of that shape, for messages ("block 3 of 8"), or empty
  std::string advice;  // what to change when this block is rejected, or empty
};

// Throws SceneError naming the shape's path for a shape whose points cannot make a block.
std::vector<PlacedPolyhedron> shape_polyhedra(const ShapeDef& shape);

}  // namespace tem
