// OFF (Geomview's Object File Format), line by line: the keyword "[ST][C][N][4][n]OFF", the
// counts "vertices faces [edges]" (on the keyword's line or the next), one vertex per line
// (x y z, then w for 4OFF, then normals, colours or texture coordinates, ignored), one face per
// line (a corner count k >= 3, k vertex numbers from 0, then an optional colour, ignored).
// '#' starts a comment; blank lines are skipped. Lines after the last face are not read.
#include <algorithm>
#include <string>

#include "mesh/mesh_formats.hpp"

namespace tem::mesh_formats {

PolygonSoup read_off(std::string_view text, const std::string& source) {
  PolygonSoup soup;
  long long vertices = 0, faces = 0, face = 0;
  bool homogeneous = false;
  int stage = 0;  // 0: the keyword, 1: the counts, 2: vertices, 3: faces, 4: done
  Lines lines(text);
  for (std::string_view line; stage < 4 && lines.next(line);) {
    std::vector<std::string_view> w = words(line, '#');
    if (w.empty()) continue;
    auto refuse = [&](const std::string& why) {
      throw MeshError(source + ": " + at_line(lines.number()) + why);
    };
    if (stage == 0) {
      std::string_view keyword = w[0];
      if (!keyword.ends_with("OFF")) refuse("an OFF file begins with OFF");
      keyword.remove_suffix(3);
      if (keyword.starts_with("ST")) keyword.remove_prefix(2);
      if (keyword.starts_with("C")) keyword.remove_prefix(1);
      if (keyword.starts_with("N")) keyword.remove_prefix(1);
      if (keyword.starts_with("4")) homogeneous = true, keyword.remove_prefix(1);
      const bool dimension = keyword == "n";
      if (!keyword.empty() && !dimension)
        refuse("'" + std::string(w[0].substr(0, 30)) +
               "' is not an OFF keyword ([ST][C][N][4][n]OFF)");
      w.erase(w.begin());
      if (dimension) {
        if (w.empty()) refuse("nOFF: the dimension must follow the keyword on its line");
        if (w[0] != "3")
          refuse("nOFF: only 3-dimensional vertices make a body, not " +
                 std::string(w[0].substr(0, 30)));
        w.erase(w.begin());
      }
      stage = 1;
      if (w.empty()) continue;
    }
    if (stage == 1) {
      if (w.size() < 2 || !parse_integer(w[0], vertices) || !parse_integer(w[1], faces) ||
          vertices < 0 || faces < 0)
        refuse("expected the counts: vertices faces edges");
      check_count(static_cast<unsigned long long>(vertices), "vertices", text.size(), source);
      check_count(static_cast<unsigned long long>(faces), "faces", text.size(), source);
      // A vertex line takes 6 bytes at least ("0 0 0\n"), a face line 8 ("3 0 1 2\n").
      soup.points.reserve(
          std::min<std::size_t>(static_cast<std::size_t>(vertices), text.size() / 6));
      soup.face_ends.reserve(
          std::min<std::size_t>(static_cast<std::size_t>(faces), text.size() / 8));
      stage = vertices > 0 ? 2 : faces > 0 ? 3 : 4;
    } else if (stage == 2) {
      const std::string which = "vertex " + std::to_string(soup.points.size());
      double v[4] = {0, 0, 0, 1};
      const std::size_t n = homogeneous ? 4 : 3;
      if (w.size() < n)
        refuse(which + " needs three numbers x y z" + (homogeneous ? " and w" : ""));
      for (std::size_t k = 0; k < n; ++k)
        if (!parse_real(w[k], v[k]))
          refuse(which + " needs three numbers x y z" + (homogeneous ? " and w" : ""));
      if (v[3] == 0) refuse(which + ": a homogeneous vertex with w = 0");
      soup.points.push_back(homogeneous ? Vec3(v[0], v[1], v[2]) / v[3] : Vec3(v[0], v[1], v[2]));
      if (static_cast<long long>(soup.points.size()) == vertices) stage = faces > 0 ? 3 : 4;
    } else {
      const std::string which = "face " + std::to_string(face);
      long long k = 0;
      if (!parse_integer(w[0], k) || k < 3 || static_cast<long long>(w.size()) < 1 + k)
        refuse(which + " needs a corner count (3 or more) and as many indices");
      for (long long c = 1; c <= k; ++c) {
        long long index = -1;
        if (w[c].starts_with('-') || w[c].starts_with('+') || !parse_integer(w[c], index) ||
            index >= vertices)
          refuse(which + " has a corner '" + std::string(w[c].substr(0, 20)) +
                 "' that is not a vertex index below " + std::to_string(vertices));
        soup.add_corner(static_cast<int>(index));
      }
      soup.end_face();
      if (++face == faces) stage = 4;
    }
  }
  if (stage < 4)
    throw MeshError(source + ": the OFF file ends before its " + std::to_string(vertices) +
                    " vertices and " + std::to_string(faces) + " faces");
  return soup;
}

}  // namespace tem::mesh_formats
