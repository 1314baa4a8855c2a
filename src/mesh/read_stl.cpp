// STL, binary or ASCII. Each facet stores its three corners on their own (the reader's welding
// joins them); the facet normal is ignored (the corners' order says which way a face points).
//
// As assimp decided: a file of exactly 84 + 50 N bytes, N being the facet count at byte 80, is
// binary (32-bit floats: each converts to double exactly); otherwise a file beginning with
// "solid" is ASCII: "solid [name]", then facets "facet normal nx ny nz / outer loop / vertex x y
// z (three times) / endloop / endfacet", then "endsolid [name]"; several solids may follow one
// another, and a missing last "endsolid" is let pass.
#include <bit>
#include <cstdint>
#include <string>

#include "mesh/mesh_formats.hpp"

namespace tem::mesh_formats {
namespace {

std::uint32_t little_uint32(std::string_view bytes, std::size_t at) {
  std::uint32_t value = 0;
  for (int k = 3; k >= 0; --k) value = (value << 8) | static_cast<unsigned char>(bytes[at + k]);
  return value;
}

PolygonSoup read_binary(std::string_view bytes, std::uint32_t facets) {
  PolygonSoup soup;
  soup.points.reserve(3 * std::size_t{facets});
  soup.face_ends.reserve(facets);
  for (std::size_t f = 0; f < facets; ++f) {
    const std::size_t at = 84 + 50 * f + 12;  // after the normal
    for (int corner = 0; corner < 3; ++corner) {
      Vec3 p;
      for (int k = 0; k < 3; ++k)
        p[k] = static_cast<double>(
            std::bit_cast<float>(little_uint32(bytes, at + 12 * corner + 4 * k)));
      soup.add_corner(static_cast<int>(soup.points.size()));
      soup.points.push_back(p);
    }
    soup.end_face();
  }
  return soup;
}

PolygonSoup read_ascii(std::string_view text, const std::string& source) {
  PolygonSoup soup;
  enum class State { before_solid, in_solid, in_facet, after_solid } state = State::before_solid;
  int corners = 0;
  Lines lines(text);
  for (std::string_view line; lines.next(line);) {
    const std::vector<std::string_view> w = words(line);
    auto refuse = [&](const std::string& why) {
      throw MeshError(source + ": " + at_line(lines.number()) + why);
    };
    for (std::size_t k = 0; k < w.size(); ++k) {
      const std::string_view word = w[k];
      if (word == "solid" && (state == State::before_solid || state == State::after_solid)) {
        state = State::in_solid;
        break;  // the rest of the line is the solid's name
      } else if (word == "facet" && state == State::in_solid) {
        state = State::in_facet;
        corners = 0;
        break;  // the normal
      } else if ((word == "outer" || word == "loop" || word == "endloop") &&
                 state == State::in_facet) {
      } else if (word == "vertex" && state == State::in_facet) {
        if (corners == 3) refuse("a facet with more than three vertices");
        Vec3 p;
        for (int c = 0; c < 3; ++c)
          if (k + 1 + c >= w.size() || !parse_real(w[k + 1 + c], p[c]))
            refuse("a vertex needs three numbers x y z");
        k += 3;
        ++corners;
        soup.add_corner(static_cast<int>(soup.points.size()));
        soup.points.push_back(p);
      } else if (word == "endfacet" && state == State::in_facet) {
        if (corners != 3) refuse("a facet of " + std::to_string(corners) + " vertices, not three");
        soup.end_face();
        state = State::in_solid;
      } else if (word == "endsolid" && state == State::in_solid) {
        state = State::after_solid;
        break;  // the solid's name
      } else {
        refuse("'" + std::string(word.substr(0, 30)) + "' was not expected here in an ASCII STL");
      }
    }
  }
  if (state == State::in_facet) throw MeshError(source + ": the file ends inside a facet");
  return soup;
}

}  // namespace

PolygonSoup read_stl(std::string_view text, const std::string& source) {
  const std::uint32_t facets = text.size() >= 84 ? little_uint32(text, 80) : 0;
  const unsigned long long binary_size = 84 + 50ull * facets;
  if (text.size() >= 84 && binary_size == text.size()) return read_binary(text, facets);
  text = without_byte_order_mark(text);
  std::size_t first = 0;
  while (first < text.size() && is_space(text[first])) ++first;
  const bool solid = text.substr(first).starts_with("solid");
  if (solid && text.find('\0') == std::string_view::npos) return read_ascii(text, source);
  std::string why = "neither an ASCII STL (";
  why += solid ? "it holds NUL bytes" : "it does not begin with 'solid'";
  why += ") nor a binary one (";
  why += text.size() < 84 ? "84 bytes at least"
                          : "84 + 50 x " + std::to_string(facets) +
                                " facets = " + std::to_string(binary_size) + " bytes";
  throw MeshError(source + ": " + why + ", the file has " + std::to_string(text.size()) + ")");
}

}  // namespace tem::mesh_formats
