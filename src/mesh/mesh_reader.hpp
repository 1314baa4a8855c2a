// Reading triangle meshes from OBJ, STL (ASCII and binary), PLY and OFF files through assimp.
//
// assimp triangulates polygons; TEM then welds vertices at identical positions (STL stores each
// triangle's corners separately) and drops nothing else: checking is check_mesh()'s job.
#pragma once

#include <cstddef>
#include <string>

#include "mesh/triangle_mesh.hpp"

namespace tem {

// The file's extension (case-insensitive) chooses the format: .obj .stl .ply .off. Every vertex
// is multiplied by `scale` (> 0). Throws MeshError for a missing or unreadable file, an unknown
// extension, a file assimp cannot parse, a file with no triangles, or a non-finite coordinate.
TriangleMesh read_mesh_file(const std::string& path, Real scale = 1.0);

// The same from bytes in memory; `extension` ("obj", "stl", ...) says the format and `source`
// names it in messages. The fuzz target reads meshes this way.
TriangleMesh read_mesh_memory(const void* data, std::size_t size, const std::string& extension,
                              const std::string& source, Real scale = 1.0);

}  // namespace tem
