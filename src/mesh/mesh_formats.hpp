// What the four format readers share (mesh_reader.cpp's helpers, not a public API): the faces
// of a file as it stores them, and the plain-text scanning of the ASCII formats.
//
// Each reader (read_obj.cpp, read_off.cpp, read_ply.cpp, read_stl.cpp) turns the file's bytes
// into a PolygonSoup in file order, coordinates in double precision exactly as the file writes
// them, or throws MeshError naming the source, the line where there is one, and what is wrong.
// mesh_reader.cpp then triangulates, scales and welds.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "mesh/triangle_mesh.hpp"

namespace tem::mesh_formats {

struct PolygonSoup {
  std::vector<Vec3> points;
  // Face f's corners are corners[face_ends[f - 1] .. face_ends[f]) (from 0 for face 0): point
  // numbers, each checked below points.size(). Faces of one or two corners are points and lines.
  std::vector<int> corners;
  std::vector<std::size_t> face_ends;
  bool has_points = false, has_lines = false;  // OBJ "p" and "l" elements

  void add_corner(int point) { corners.push_back(point); }
  void end_face() { face_ends.push_back(corners.size()); }
};

PolygonSoup read_obj(std::string_view text, const std::string& source);
PolygonSoup read_off(std::string_view text, const std::string& source);
PolygonSoup read_ply(std::string_view text, const std::string& source);
PolygonSoup read_stl(std::string_view text, const std::string& source);

// ---- Plain-text scanning (OBJ, OFF, ASCII PLY and STL) ----

// The text line by line: '\n' ends a line, a '\r' before it is dropped. Counts lines from 1.
class Lines {
 public:
  explicit Lines(std::string_view text) : text_(text) {}
  bool next(std::string_view& line);
  int number() const { return number_; }
  std::size_t offset() const { return at_; }  // where the next line begins

 private:
  std::string_view text_;
  std::size_t at_ = 0;
  int number_ = 0;
};

bool is_space(char c);

// The text after a UTF-8 byte order mark, if it begins with one: editors on Windows write one
// before the first keyword of OBJ, OFF, ASCII PLY and ASCII STL files (CGAL's elephant.off has
// one). Not for binary STL, whose 80-byte header may begin with any bytes.
std::string_view without_byte_order_mark(std::string_view text);

// The whitespace-separated words of a line, from its start to `comment` (exclusive) if given.
std::vector<std::string_view> words(std::string_view line, char comment = '\0');

// A decimal number as the file writes it, rounded once to the nearest double (std::from_chars,
// as correctly rounded as strtod and independent of the locale). A leading '+' is allowed. A
// number beyond double's range becomes +-infinity (the caller refuses it), one below its
// smallest becomes 0 or a subnormal; "inf" and "nan" are read as such. False if `word` is not
// one whole number.
bool parse_real(std::string_view word, double& value);

// A whole number with an optional sign, at most 18 digits: false otherwise.
bool parse_integer(std::string_view word, long long& value);

// Refuses a count from a header that the file cannot hold: every element takes a byte at least.
void check_count(unsigned long long count, const std::string& what, std::size_t size,
                 const std::string& source);

// "line 12: " for messages.
std::string at_line(int number);

}  // namespace tem::mesh_formats
