// The names of the shape types in scene files: the one table the reader parses and the writer
// writes, so that a scene written back reads the same.
#pragma once

#include <string_view>
#include <utility>
#include <vector>

#include "tem/scene_def.hpp"

namespace tem {

inline const std::vector<std::pair<std::string_view, ShapeType>>& shape_type_names() {
  static const std::vector<std::pair<std::string_view, ShapeType>> names = {
      {"prism", ShapeType::prism},     {"ring", ShapeType::ring},
      {"box", ShapeType::box},         {"convex", ShapeType::convex},
      {"compound", ShapeType::compound}, {"mesh", ShapeType::mesh}};
  return names;
}

inline std::string_view shape_type_name(ShapeType type) {
  for (const auto& [name, value] : shape_type_names())
    if (value == type) return name;
  return "?";
}

}  // namespace tem
