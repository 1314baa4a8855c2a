#include "world/shape_blocks.hpp"

#include "geometry/primitives.hpp"
#include "mesh/mesh_body.hpp"

namespace tem {
namespace {

void collect(const ShapeDef& shape, const Mat3& rotation, const Vec3& position,
             std::vector<PlacedPolyhedron>& out) {
  auto place = [&](PolyhedronDef def, std::string label, std::string advice = "") {
    out.push_back(
        {std::move(def), rotation, position, shape.path, std::move(label), std::move(advice)});
  };
  switch (shape.type) {
    case ShapeType::prism:
      place(regular_prism(shape.sides, shape.radius, shape.height, shape.axis), "");
      break;
    case ShapeType::box:
      place(box(shape.size), "");
      break;
    case ShapeType::ring: {
      const int blocks = shape.blocks > 0 ? shape.blocks : shape.segments;
      if (shape.segments % blocks != 0)
        throw SceneError(shape.path + ".blocks",
                         "must divide segments (" + std::to_string(shape.segments) + ")");
      auto parts = polygonal_ring(shape.segments, shape.sides, shape.radius, shape.section_radius,
                                  blocks, shape.axis, shape.allow_nonconvex);
      // A block of several segments bends inward: not convex (method.md §1).
      const std::string advice =
          blocks == shape.segments
              ? ""
              : "a ring block of several segments is not convex; use one block per segment "
                "(blocks = segments, the default) or set allow_nonconvex to accept it as the "
                "paper did";
      for (size_t i = 0; i < parts.size(); ++i)
        place(std::move(parts[i]),
              "block " + std::to_string(i + 1) + " of " + std::to_string(parts.size()), advice);
      break;
    }
    case ShapeType::convex:
      try {
        place(convex_hull(shape.points), "");
      } catch (const GeometryError& e) {
        throw SceneError(shape.path + ".points", e.what());
      }
      break;
    case ShapeType::mesh: {
      if (!shape.mesh)
        throw SceneError(shape.path + ".file",
                         "the mesh was not loaded (a scene from read_scene_text needs "
                         "load_scene_meshes before its model is built)");
      const auto& blocks = shape.mesh->decomposition.blocks;
      for (size_t i = 0; i < blocks.size(); ++i)
        place(blocks[i], "block " + std::to_string(i + 1) + " of " +
                             std::to_string(blocks.size()) + " cut from " + shape.file);
      break;
    }
    case ShapeType::compound:
      for (const ShapeDef& part : shape.parts)
        collect(part, rotation * part.rotation, rotation * part.position + position, out);
      break;
  }
}

}  // namespace

std::vector<PlacedPolyhedron> shape_polyhedra(const ShapeDef& shape) {
  std::vector<PlacedPolyhedron> out;
  collect(shape, Mat3::Identity(), Vec3::Zero(), out);
  return out;
}

}  // namespace tem
