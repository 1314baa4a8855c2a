// Reading triangle meshes: the format's own reader (read_obj.cpp, read_off.cpp, read_ply.cpp,
// read_stl.cpp) gives the file's polygons with double-precision coordinates, exactly as the
// file writes them; here they are triangulated, scaled and welded.
//
// The file is read into memory and parsed from there, so files and fuzzed bytes take one path.
#include "mesh/mesh_reader.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "mesh/mesh_formats.hpp"
#include "mesh/polygon_triangulation.hpp"
#include "support/fnv1a.hpp"

namespace tem {
namespace {

constexpr std::array<const char*, 4> kSupported = {"obj", "stl", "ply", "off"};

std::string lower_extension(std::string extension) {
  if (!extension.empty() && extension.front() == '.') extension.erase(0, 1);
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

void require_supported(const std::string& extension, const std::string& source) {
  if (std::find(kSupported.begin(), kSupported.end(), extension) != kSupported.end()) return;
  throw MeshError(source + ": unknown mesh format '" + extension +
                  "' (supported extensions: .obj, .stl, .ply, .off)");
}

void require_scale(Real scale, const std::string& source) {
  if (!(std::isfinite(scale) && scale > 0)) {
    std::ostringstream message;
    message << source << ": scale " << scale << " must be finite and positive";
    throw MeshError(message.str());
  }
}

// Welds corners at bitwise-identical positions (after scaling). +0 and -0 are the same position:
// adding 0.0 turns -0 into +0 before the bits are compared.
class Welder {
 public:
  explicit Welder(std::vector<Vec3>& vertices) : vertices_(vertices) {}

  int index(const Vec3& p) {
    const Key key{bits(p.x()), bits(p.y()), bits(p.z())};
    auto [it, added] = index_.try_emplace(key, static_cast<int>(vertices_.size()));
    if (added) vertices_.push_back(p);
    return it->second;
  }

 private:
  using Key = std::array<std::uint64_t, 3>;
  struct Hash {
    std::size_t operator()(const Key& k) const {
      std::uint64_t h = 0x9e3779b97f4a7c15ULL;
      for (std::uint64_t v : k) h = (h ^ v) * 0xff51afd7ed558ccdULL;
      return static_cast<std::size_t>(h ^ (h >> 33));
    }
  };
  static std::uint64_t bits(Real x) {
    const Real positive_zero = x + 0.0;
    std::uint64_t b;
    std::memcpy(&b, &positive_zero, sizeof b);
    return b;
  }

  std::vector<Vec3>& vertices_;
  std::unordered_map<Key, int, Hash> index_;
};

// Triangulates, scales and welds what a format reader found, refusing points and lines.
TriangleMesh assemble(const mesh_formats::PolygonSoup& soup, Real scale,
                      const std::string& source) {
  bool points = soup.has_points, lines = soup.has_lines;
  std::size_t begin = 0;
  for (std::size_t f = 0; f < soup.face_ends.size(); begin = soup.face_ends[f++]) {
    const std::size_t corners = soup.face_ends[f] - begin;
    if (corners == 0) throw MeshError(source + ": face " + std::to_string(f) + " has no corners");
    (corners == 1 ? points : lines) |= corners < 3;
  }
  if (points || lines) {
    const std::string kinds = points && lines ? "points and lines" : points ? "points" : "lines";
    bool polygons = false;
    begin = 0;
    for (std::size_t f = 0; f < soup.face_ends.size(); begin = soup.face_ends[f++])
      polygons |= soup.face_ends[f] - begin >= 3;
    if (!polygons) throw MeshError(source + ": the file has no triangles, only " + kinds);
    throw MeshError(source + ": the file has " + kinds +
                    " besides its triangles; a mesh body is made of triangles only");
  }
  if (soup.face_ends.empty()) {
    if (soup.points.empty()) throw MeshError(source + ": the file has no faces and no vertices");
    throw MeshError(source + ": the file has no faces, only " + std::to_string(soup.points.size()) +
                    " vertices");
  }
  TriangleMesh mesh;
  mesh.source = source;
  mesh.faces.reserve(soup.face_ends.size());
  Welder welder(mesh.vertices);
  auto weld = [&](int point) {
    const Vec3 q = scale * soup.points[point];
    if (!q.allFinite()) {
      std::ostringstream message;
      message << source << ": vertex at (" << q.x() << ", " << q.y() << ", " << q.z()
              << "): a coordinate is not finite";
      throw MeshError(message.str());
    }
    return welder.index(q);
  };
  std::vector<Vec3> polygon;
  begin = 0;
  for (std::size_t f = 0; f < soup.face_ends.size(); begin = soup.face_ends[f++]) {
    const int* corners = soup.corners.data() + begin;
    const std::size_t n = soup.face_ends[f] - begin;
    if (n == 3) {
      mesh.faces.push_back({weld(corners[0]), weld(corners[1]), weld(corners[2])});
      continue;
    }
    polygon.clear();
    for (std::size_t k = 0; k < n; ++k) polygon.push_back(soup.points[corners[k]]);
    for (const auto& t : triangulate_polygon(polygon))
      mesh.faces.push_back({weld(corners[t[0]]), weld(corners[t[1]]), weld(corners[t[2]])});
  }
  return mesh;
}

TriangleMesh parse(const void* data, std::size_t size, const std::string& extension,
                   const std::string& source, Real scale) {
  require_supported(extension, source);
  require_scale(scale, source);
  if (!data || size == 0) throw MeshError(source + ": the file is empty");
  using namespace mesh_formats;
  const std::string_view bytes(static_cast<const char*>(data), size);
  const std::string_view text = extension == "stl" ? bytes : without_byte_order_mark(bytes);
  const PolygonSoup soup = extension == "obj"   ? read_obj(text, source)
                           : extension == "off" ? read_off(text, source)
                           : extension == "ply" ? read_ply(text, source)
                                                : read_stl(text, source);
  return assemble(soup, scale, source);
}

}  // namespace

TriangleMesh read_mesh_file(const std::string& path, Real scale, std::uint64_t* content_hash) {
  const std::string extension = lower_extension(std::filesystem::path(path).extension().string());
  require_supported(extension, path);
  require_scale(scale, path);
  std::error_code error;
  if (!std::filesystem::exists(path, error)) throw MeshError(path + ": no such file");
  if (!std::filesystem::is_regular_file(path, error)) throw MeshError(path + ": not a file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw MeshError(path + ": cannot be opened for reading");
  std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw MeshError(path + ": cannot be read");
  if (content_hash) *content_hash = fnv1a(bytes.data(), bytes.size());
  return parse(bytes.data(), bytes.size(), extension, path, scale);
}

TriangleMesh read_mesh_memory(const void* data, std::size_t size, const std::string& extension,
                              const std::string& source, Real scale) {
  return parse(data, size, lower_extension(extension), source, scale);
}

}  // namespace tem
