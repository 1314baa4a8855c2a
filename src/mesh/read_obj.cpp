// Wavefront OBJ: "v x y z" vertices and "f" faces, the rest ignored.
//
// A face corner is "v", "v/vt", "v//vn" or "v/vt/vn"; only v is used. Indices count from 1; a
// negative one counts back from the last vertex defined so far (-1 is that vertex). A positive
// index may name a vertex defined further down, as assimp allowed; it is checked at the end.
// A vertex is "v x y z", "v x y z w" (homogeneous: divided by w) or "v x y z r g b [a]" (a
// colour, ignored). "l" and "p" elements are noted (a body is made of faces only); vt, vn, vp,
// usemtl, mtllib, o, g, s and unknown lines are skipped: no other file is ever opened. '#'
// starts a comment; a line ending in '\' continues on the next.
#include <climits>
#include <string>

#include "mesh/mesh_formats.hpp"

namespace tem::mesh_formats {
namespace {

[[noreturn]] void refuse(const std::string& source, int line, const std::string& why) {
  throw MeshError(source + ": " + at_line(line) + why);
}

Vec3 parse_vertex(const std::vector<std::string_view>& w, const std::string& source, int line) {
  const std::size_t n = w.size() - 1;
  if (n != 3 && n != 4 && n != 6 && n != 7)
    refuse(source, line,
           "a vertex is 'v x y z' (or x y z w, or x y z r g b): this one has " + std::to_string(n) +
               " numbers");
  double values[4] = {0, 0, 0, 1};
  for (std::size_t k = 1; k <= n; ++k) {
    double value;
    if (!parse_real(w[k], value))
      refuse(source, line, "'" + std::string(w[k].substr(0, 30)) + "' is not a number");
    if (k <= 4) values[k - 1] = value;
  }
  Vec3 p(values[0], values[1], values[2]);
  if (n == 4) {
    if (values[3] == 0) refuse(source, line, "a homogeneous vertex with w = 0");
    p /= values[3];
  }
  return p;
}

}  // namespace

PolygonSoup read_obj(std::string_view text, const std::string& source) {
  PolygonSoup soup;
  std::vector<int> face_lines;  // for the messages of indices checked at the end
  Lines lines(text);
  std::string joined;
  for (std::string_view line; lines.next(line);) {
    const int number = lines.number();
    if (!line.empty() && line.back() == '\\') {
      joined.assign(line.substr(0, line.size() - 1));
      std::string_view more;
      while (lines.next(more)) {
        joined += ' ';
        const bool again = !more.empty() && more.back() == '\\';
        joined.append(more.substr(0, more.size() - (again ? 1 : 0)));
        if (!again) break;
      }
      line = joined;
    }
    const std::vector<std::string_view> w = words(line, '#');
    if (w.empty()) continue;
    if (w[0] == "v") {
      soup.points.push_back(parse_vertex(w, source, number));
    } else if (w[0] == "f") {
      if (w.size() == 1) refuse(source, number, "a face with no corners");
      const long long defined = static_cast<long long>(soup.points.size());
      for (std::size_t k = 1; k < w.size(); ++k) {
        const std::string_view index = w[k].substr(0, w[k].find('/'));
        long long value = 0;
        if (!parse_integer(index, value) || value == 0 || value > INT_MAX)
          refuse(source, number,
                 "face corner '" + std::string(w[k].substr(0, 30)) +
                     "' is not a vertex number (1, 2, ... or -1, -2, ... counting back)");
        if (value < 0 && defined + value < 0)
          refuse(source, number,
                 "face corner " + std::string(index) + " counts back past the first vertex (" +
                     std::to_string(defined) + " defined so far)");
        soup.add_corner(static_cast<int>(value < 0 ? defined + value : value - 1));
      }
      soup.end_face();
      face_lines.push_back(number);
    } else if (w[0] == "l") {
      soup.has_lines = true;
    } else if (w[0] == "p") {
      soup.has_points = true;
    }
  }
  std::size_t begin = 0;
  for (std::size_t f = 0; f < soup.face_ends.size(); ++f) {
    for (std::size_t k = begin; k < soup.face_ends[f]; ++k)
      if (soup.corners[k] >= static_cast<int>(soup.points.size()))
        refuse(source, face_lines[f],
               "face corner " + std::to_string(soup.corners[k] + 1) +
                   " names a missing vertex (the file has " + std::to_string(soup.points.size()) +
                   ")");
    begin = soup.face_ends[f];
  }
  return soup;
}

}  // namespace tem::mesh_formats
