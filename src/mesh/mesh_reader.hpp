// Reading triangle meshes from OBJ, STL (ASCII and binary), PLY (ASCII and binary) and OFF files.
//
// Coordinates are read in double precision, each rounded once from the file's decimal digits
// (binary STL holds floats, which convert exactly). Polygons are triangulated
// (polygon_triangulation.hpp) and vertices at identical positions welded (STL stores each
// triangle's corners separately); nothing else is dropped: checking is check_mesh()'s job. The
// vertices are numbered in the order the triangles first use them.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "mesh/triangle_mesh.hpp"

namespace tem {

// The file's extension (case-insensitive) chooses the format: .obj .stl .ply .off. Every vertex
// is multiplied by `scale` (> 0). Throws MeshError for a missing or unreadable file, an unknown
// extension, a damaged file (the message names the line in text formats), a file with no faces,
// points or lines among its faces, or a non-finite coordinate.
// `content_hash`, when given, receives the FNV-1a hash of the file's bytes (support/fnv1a.hpp).
TriangleMesh read_mesh_file(const std::string& path, Real scale = 1.0,
                            std::uint64_t* content_hash = nullptr);

// The same from bytes in memory; `extension` ("obj", "stl", ...) says the format and `source`
// names it in messages. The fuzz target reads meshes this way.
TriangleMesh read_mesh_memory(const void* data, std::size_t size, const std::string& extension,
                              const std::string& source, Real scale = 1.0);

}  // namespace tem
