// Reading triangle meshes through assimp, then welding the corners assimp keeps apart.
//
// Debian's assimp 5.2 is built without ASSIMP_DOUBLE_PRECISION: every format, ASCII ones too,
// reaches TEM as 32-bit floats. Coordinates are converted to Real before scaling and welding.
//
// The file is read into memory and parsed from there, so files and fuzzed bytes take one path.
// assimp's default logger is its NullLogger (nothing is created here), so reading prints nothing.
#include "mesh/mesh_reader.hpp"

#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <array>
#include <assimp/IOSystem.hpp>
#include <assimp/Importer.hpp>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <set>
#include <sstream>
#include <string_view>
#include <unordered_map>
#include <vector>

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

// The file system as assimp sees it: empty. An OBJ's "mtllib" line would otherwise make assimp
// open any path the file names (materials are of no use here, and a fuzzed "mtllib /dev/stdin"
// would block); assimp's in-memory reading passes every other name on to this handler.
class NoFiles : public Assimp::IOSystem {
 public:
  bool Exists(const char*) const override { return false; }
  char getOsSeparator() const override { return '/'; }
  Assimp::IOStream* Open(const char*, const char*) override { return nullptr; }
  void Close(Assimp::IOStream*) override {}
};

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

// The scene as the loader left it, before any post-processing: assimp 5.2's loaders can leave
// faces of no corners or indices past the vertices in damaged files, on which its Triangulate
// step aborts (an ai_assert) or reads out of bounds. Points and lines are refused here too.
void screen_scene(const aiScene& scene, const std::string& source) {
  bool points = false, lines = false, polygons = false;
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
    const aiMesh* mesh = scene.mMeshes ? scene.mMeshes[m] : nullptr;
    if (!mesh || (mesh->mNumVertices && !mesh->mVertices) || (mesh->mNumFaces && !mesh->mFaces))
      throw MeshError(source + ": the file's data is damaged (a mesh is missing its arrays)");
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices == 0 || !face.mIndices)
        throw MeshError(source + ": the file's data is damaged (a face has no corners)");
      for (unsigned k = 0; k < face.mNumIndices; ++k)
        if (face.mIndices[k] >= mesh->mNumVertices)
          throw MeshError(source +
                          ": the file's data is damaged (a face refers to a missing vertex)");
      (face.mNumIndices == 1 ? points : face.mNumIndices == 2 ? lines : polygons) = true;
    }
  }
  if (!points && !lines) return;
  const std::string kinds = points && lines ? "points and lines" : points ? "points" : "lines";
  if (!polygons) throw MeshError(source + ": the file has no triangles, only " + kinds);
  throw MeshError(source + ": the file has " + kinds +
                  " besides its triangles; a mesh body is made of triangles only");
}

// Appends one triangulated assimp mesh, placed by `transform` (its nodes' transforms).
void append_mesh(const aiMesh& in, const aiMatrix4x4& transform, Real scale, Welder& welder,
                 TriangleMesh& out) {
  for (unsigned f = 0; f < in.mNumFaces; ++f) {
    const aiFace& face = in.mFaces[f];
    if (face.mNumIndices != 3)
      throw MeshError(out.source + ": a face of " + std::to_string(face.mNumIndices) +
                      " corners was left after triangulation");
    std::array<int, 3> corners{};
    for (int k = 0; k < 3; ++k) {
      const aiVector3D p = transform * in.mVertices[face.mIndices[k]];
      const Vec3 q = scale * Vec3(p.x, p.y, p.z);
      if (!q.allFinite()) {
        std::ostringstream message;
        message << out.source << ": vertex at (" << q.x() << ", " << q.y() << ", " << q.z()
                << "): a coordinate is not finite";
        throw MeshError(message.str());
      }
      corners[k] = welder.index(q);
    }
    out.faces.push_back(corners);
  }
}

TriangleMesh convert(const aiScene& scene, Real scale, const std::string& source) {
  TriangleMesh mesh;
  mesh.source = source;
  Welder welder(mesh.vertices);
  // Depth-first over the node tree with each node's accumulated transform (identity in the four
  // formats read here, but nothing is assumed).
  std::vector<std::pair<const aiNode*, aiMatrix4x4>> stack;
  if (scene.mRootNode) stack.emplace_back(scene.mRootNode, scene.mRootNode->mTransformation);
  while (!stack.empty()) {
    const auto [node, transform] = stack.back();
    stack.pop_back();
    for (unsigned k = 0; k < node->mNumMeshes; ++k) {
      const unsigned m = node->mMeshes[k];
      if (m >= scene.mNumMeshes || !scene.mMeshes[m])
        throw MeshError(source + ": a node refers to a missing mesh");
      append_mesh(*scene.mMeshes[m], transform, scale, welder, mesh);
    }
    for (unsigned c = 0; c < node->mNumChildren; ++c)
      if (node->mChildren[c])
        stack.emplace_back(node->mChildren[c], transform * node->mChildren[c]->mTransformation);
  }
  if (mesh.faces.empty()) throw MeshError(source + ": the file has no triangles");
  return mesh;
}

// assimp 5.2's PLY and OFF loaders allocate for the element counts their headers declare (2e9
// vertices in a 100-byte file: gigabytes), and its PLY header parser loops forever on a line it
// does not know (a damaged type name) or a header cut off before end_header. Such headers are
// refused here, before assimp sees them: each PLY header line must be well formed, and as an
// element takes at least one byte, no count may exceed the file's size.
void too_many(unsigned long long count, const std::string& what, std::size_t size,
              const std::string& source) {
  if (count <= size) return;
  throw MeshError(source + ": the header declares " + std::to_string(count) + " " + what +
                  ", more than the file's " + std::to_string(size) + " bytes can hold");
}

void screen_ply_header(std::string_view text, const std::string& source) {
  const std::size_t end = text.find("\nend_header");
  const std::string_view after = end == std::string_view::npos ? "" : text.substr(end + 11);
  if (!after.starts_with('\n') && !after.starts_with("\r\n"))
    throw MeshError(source + ": the PLY header has no end_header line");
  static const std::set<std::string> types = {
      "char", "uchar", "short", "ushort", "int",   "uint",   "float",   "double",
      "int8", "uint8", "int16", "uint16", "int32", "uint32", "float32", "float64"};
  std::istringstream header{std::string(text.substr(0, end))};
  int number = 0;
  for (std::string line; std::getline(header, line); ++number) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream words(line);
    std::string keyword, a, b, c, extra;
    words >> keyword;
    bool good = false;
    if (number == 0) {
      good = keyword == "ply";
    } else if (keyword == "comment" || keyword == "obj_info") {
      good = true;
    } else if (keyword == "format") {
      good = words >> a >> b &&
             (a == "ascii" || a == "binary_little_endian" || a == "binary_big_endian");
    } else if (keyword == "element") {
      unsigned long long count = 0;
      good = words >> a >> count && !(words >> extra);
      if (good) too_many(count, a + " elements", text.size(), source);
    } else if (keyword == "property") {
      good =
          words >> a >> b && (a == "list" ? types.count(b) && words >> c >> extra && types.count(c)
                                          : types.count(a) != 0);
    }
    if (!good)
      throw MeshError(source + ": line " + std::to_string(number + 1) +
                      " of the PLY header is not a PLY header line: '" + line.substr(0, 80) + "'");
  }
}

// assimp 5.2's OFF loader trusts the file: a vertex line with a damaged number or a face whose
// indices run past the vertices makes it read out of bounds (found by fuzz/fuzz_mesh_reader).
// The body is screened here first, line by line, in the format's own terms: "[C][N]OFF", the
// counts, `vertices` lines of at least three numbers, then `faces` lines of a corner count k >= 3
// and k indices below `vertices` (anything after them, a colour, is left to assimp). Every token
// checked must be a whole number; '#' starts a comment.
bool whole_number(const std::string& token) {
  if (token.empty()) return false;
  char* end = nullptr;
  const double value = std::strtod(token.c_str(), &end);
  return end == token.c_str() + token.size() && std::isfinite(value);
}

bool whole_index(const std::string& token, unsigned long long below) {
  if (token.empty() || token.size() > 19 ||
      token.find_first_not_of("0123456789") != std::string::npos)
    return false;
  return std::stoull(token) < below;
}

void screen_off(std::string_view text, const std::string& source) {
  std::istringstream lines{std::string(text)};
  unsigned long long vertices = 0, faces = 0, vertex = 0, face = 0;
  int stage = 0;  // 0: the OFF keyword, 1: the counts, 2: vertices, 3: faces
  int number = 0;
  for (std::string line; std::getline(lines, line) && stage < 4;) {
    ++number;
    line = line.substr(0, line.find('#'));
    std::istringstream words(line);
    std::vector<std::string> tokens;
    for (std::string t; words >> t;) tokens.push_back(t);
    if (tokens.empty()) continue;
    auto refuse = [&](const std::string& why) {
      throw MeshError(source + ": line " + std::to_string(number) + ": " + why);
    };
    if (stage == 0) {
      if (!tokens[0].ends_with("OFF")) refuse("an OFF file begins with OFF");
      stage = 1;
      if (tokens.size() == 1) continue;
      tokens.erase(tokens.begin());
    }
    if (stage == 1) {
      if (tokens.size() < 2 || !whole_index(tokens[0], ~0ull) || !whole_index(tokens[1], ~0ull))
        refuse("expected the counts: vertices faces edges");
      vertices = std::stoull(tokens[0]);
      faces = std::stoull(tokens[1]);
      too_many(vertices, "vertices", text.size(), source);
      too_many(faces, "faces", text.size(), source);
      stage = vertices > 0 ? 2 : 3;
    } else if (stage == 2) {
      if (tokens.size() < 3 || !whole_number(tokens[0]) || !whole_number(tokens[1]) ||
          !whole_number(tokens[2]))
        refuse("vertex " + std::to_string(vertex) + " needs three numbers x y z");
      if (++vertex == vertices) stage = 3;
    } else {
      if (face == faces) break;
      if (!whole_index(tokens[0], 1ull << 20) || std::stoull(tokens[0]) < 3 ||
          tokens.size() < 1 + std::stoull(tokens[0]))
        refuse("face " + std::to_string(face) +
               " needs a corner count (3 or more) and as many indices");
      for (unsigned long long k = 1; k <= std::stoull(tokens[0]); ++k)
        if (!whole_index(tokens[k], vertices))
          refuse("face " + std::to_string(face) + " has a corner '" + tokens[k].substr(0, 20) +
                 "' that is not a vertex index below " + std::to_string(vertices));
      if (++face == faces) stage = 4;
    }
  }
  if (stage < 2 || vertex < vertices || face < faces)
    throw MeshError(source + ": the OFF file ends before its " + std::to_string(vertices) +
                    " vertices and " + std::to_string(faces) + " faces");
}

// assimp 5.2's PLY loader also trusts a list's count in the body: a face line "3999999999 ..."
// made it allocate 16 GB (found by the fuzzer). The body is walked here as the header lays it
// out, element by element, property by property: a scalar takes one number (ASCII) or its
// type's bytes (binary); a list's count must be a whole number that the rest of the file can
// hold, then its items are taken. A body that ends early is refused too.
void screen_ply_body(std::string_view text, const std::string& source) {
  struct Property {
    bool list = false;
    std::string count_type, type;
  };
  struct Element {
    std::string name;
    unsigned long long count = 0;
    std::vector<Property> properties;
  };
  static const std::map<std::string, int> sizes = {
      {"char", 1},  {"uchar", 1},   {"int8", 1},   {"uint8", 1},  {"short", 2}, {"ushort", 2},
      {"int16", 2}, {"uint16", 2},  {"int", 4},    {"uint", 4},   {"int32", 4}, {"uint32", 4},
      {"float", 4}, {"float32", 4}, {"double", 8}, {"float64", 8}};
  const std::size_t end = text.find("\nend_header");
  std::size_t at = end + 11;
  if (at < text.size() && text[at] == '\r') ++at;
  ++at;  // the newline
  std::istringstream header{std::string(text.substr(0, end))};
  std::vector<Element> elements;
  std::string format;
  for (std::string line; std::getline(header, line);) {
    std::istringstream words(line);
    std::string keyword, a, b, c;
    words >> keyword;
    if (keyword == "format") {
      words >> format;
    } else if (keyword == "element") {
      Element e;
      words >> e.name >> e.count;
      elements.push_back(e);
    } else if (keyword == "property" && !elements.empty()) {
      words >> a >> b >> c;
      elements.back().properties.push_back(a == "list" ? Property{true, b, c}
                                                       : Property{false, "", a});
    }
  }
  const std::string_view body = at <= text.size() ? text.substr(at) : std::string_view();
  auto refuse = [&](const Element& e, unsigned long long i, const std::string& why) {
    throw MeshError(source + ": " + e.name + " " + std::to_string(i) + " of the PLY body " + why);
  };
  if (format == "ascii") {
    std::istringstream words{std::string(body)};
    std::vector<std::string> tokens;
    for (std::string t; words >> t;) tokens.push_back(t);
    std::size_t next = 0;
    for (const Element& e : elements)
      for (unsigned long long i = 0; i < e.count; ++i)
        for (const Property& p : e.properties) {
          if (next >= tokens.size()) refuse(e, i, "is missing: the file ends first");
          if (!p.list) {
            if (!whole_number(tokens[next++])) refuse(e, i, "has a value that is not a number");
            continue;
          }
          if (!whole_index(tokens[next], tokens.size() - next))
            refuse(e, i,
                   "has a list whose count '" + tokens[next].substr(0, 20) +
                       "' is more than the values left in the file");
          next += 1 + std::stoull(tokens[next]);
        }
    return;
  }
  // Binary: counts read in the file's byte order.
  const bool big = format == "binary_big_endian";
  std::size_t next = 0;
  auto read_count = [&](const std::string& type) -> unsigned long long {
    const int n = sizes.at(type);
    unsigned long long value = 0;
    for (int k = 0; k < n; ++k) {
      const auto byte = static_cast<unsigned char>(body[next + (big ? k : n - 1 - k)]);
      value = (value << 8) | byte;
    }
    const bool is_signed = type == "char" || type == "int8" || type == "short" || type == "int16" ||
                           type == "int" || type == "int32";
    if (is_signed && (value >> (8 * n - 1)) & 1) return ~0ull;  // negative: refused below
    next += static_cast<std::size_t>(n);
    return value;
  };
  for (const Element& e : elements)
    for (unsigned long long i = 0; i < e.count; ++i)
      for (const Property& p : e.properties) {
        if (!p.list) {
          next += static_cast<std::size_t>(sizes.at(p.type));
          if (next > body.size()) refuse(e, i, "is missing: the file ends first");
          continue;
        }
        if (next + static_cast<std::size_t>(sizes.at(p.count_type)) > body.size())
          refuse(e, i, "is missing: the file ends first");
        const unsigned long long count = read_count(p.count_type);
        const unsigned long long item = static_cast<unsigned long long>(sizes.at(p.type));
        if (count == ~0ull || count > (body.size() - next) / item)
          refuse(e, i, "has a list whose count is more than the bytes left in the file");
        next += static_cast<std::size_t>(count * item);
      }
}

TriangleMesh parse(const void* data, std::size_t size, const std::string& extension,
                   const std::string& source, Real scale) {
  require_supported(extension, source);
  require_scale(scale, source);
  if (!data || size == 0) throw MeshError(source + ": the file is empty");
  const std::string_view text(static_cast<const char*>(data), size);
  if (extension == "ply") {
    screen_ply_header(text, source);
    screen_ply_body(text, source);
  }
  if (extension == "off") screen_off(text, source);
  Assimp::Importer importer;
  importer.SetIOHandler(new NoFiles);  // the importer owns and deletes it
  auto failed = [&](const std::string& why) {
    return MeshError(source + ": cannot be parsed as ." + extension + " (" + why + ")");
  };
  // Loading and post-processing are two calls so that the loader's output can be screened
  // before Triangulate runs on it; ValidateDataStructure then checks what Triangulate made.
  const aiScene* scene = nullptr;
  try {
    scene = importer.ReadFileFromMemory(data, size, 0, extension.c_str());
    if (scene) {
      screen_scene(*scene, source);
      scene = importer.ApplyPostProcessing(aiProcess_Triangulate | aiProcess_ValidateDataStructure);
    }
  } catch (const MeshError&) {
    throw;
  } catch (const std::exception& e) {  // assimp catches its own errors; this is for bad_alloc &c.
    throw failed(e.what());
  }
  if (!scene) throw failed(importer.GetErrorString());
  return convert(*scene, scale, source);
}

}  // namespace

TriangleMesh read_mesh_file(const std::string& path, Real scale) {
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
  return parse(bytes.data(), bytes.size(), extension, path, scale);
}

TriangleMesh read_mesh_memory(const void* data, std::size_t size, const std::string& extension,
                              const std::string& source, Real scale) {
  return parse(data, size, lower_extension(extension), source, scale);
}

}  // namespace tem
