// libFuzzer target: any bytes given to the mesh reader as each of its formats, then to the
// mesh checks. What must hold for every input:
// - reading and checking return or throw MeshError (no crash, no hang, no sanitizer report, no
//   other exception);
// - every face of a mesh read indexes an existing vertex, and every vertex is finite and used;
// - a mesh that passes the checks is closed with a positive volume.
// The first byte chooses the format, so one corpus covers all of them.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include "mesh/mesh_check.hpp"
#include "mesh/mesh_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 1) return 0;
  static const char* const kFormats[] = {"obj", "stl", "ply", "off"};
  const std::string extension = kFormats[data[0] % 4];
  try {
    tem::TriangleMesh mesh =
        tem::read_mesh_memory(data + 1, size - 1, extension, "fuzz." + extension);
    std::vector<char> used(mesh.vertices.size(), 0);
    for (const auto& face : mesh.faces)
      for (int v : face) {
        if (v < 0 || v >= static_cast<int>(mesh.vertices.size())) std::abort();
        used[v] = 1;
      }
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
      if (!used[v] || !mesh.vertices[v].allFinite()) std::abort();
    const tem::MeshCheck check = tem::check_mesh(mesh);
    if (!check.closed || !(check.volume > 0)) std::abort();
  } catch (const tem::MeshError& e) {
    if (std::string(e.what()).empty()) std::abort();
  }
  return 0;
}
