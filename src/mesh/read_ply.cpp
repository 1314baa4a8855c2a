// PLY (Stanford polygon format), ASCII and binary (either byte order): the header says which
// elements follow, how many of each, and their properties; the body holds them in that order.
//
// Used: the "vertex" element's x, y and z (any numeric type: integers and floats convert to
// double exactly), the "face" element's list "vertex_indices" (or "vertex_index") of integer
// vertex numbers from 0, and the "tristrips" element's list of the same name: triangle strips,
// -1 restarting a strip, every second triangle turned (a b c, c b d, c d e, ...) so that all
// face the same way; triangles with a repeated corner (joins between strips) are left out.
// Every other element and property is walked over and skipped. Each count
// is checked against what is left of the file before anything is allocated for it, and every
// vertex number against the header's vertex count.
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>

#include "mesh/mesh_formats.hpp"

namespace tem::mesh_formats {
namespace {

enum class Kind { signed_integer, unsigned_integer, floating };

struct Type {
  int size = 0;
  Kind kind = Kind::floating;
};

std::optional<Type> type_named(std::string_view name) {
  static const std::array<std::pair<std::string_view, Type>, 16> types = {{
      {"char", {1, Kind::signed_integer}},
      {"int8", {1, Kind::signed_integer}},
      {"uchar", {1, Kind::unsigned_integer}},
      {"uint8", {1, Kind::unsigned_integer}},
      {"short", {2, Kind::signed_integer}},
      {"int16", {2, Kind::signed_integer}},
      {"ushort", {2, Kind::unsigned_integer}},
      {"uint16", {2, Kind::unsigned_integer}},
      {"int", {4, Kind::signed_integer}},
      {"int32", {4, Kind::signed_integer}},
      {"uint", {4, Kind::unsigned_integer}},
      {"uint32", {4, Kind::unsigned_integer}},
      {"float", {4, Kind::floating}},
      {"float32", {4, Kind::floating}},
      {"double", {8, Kind::floating}},
      {"float64", {8, Kind::floating}},
  }};
  for (const auto& [n, t] : types)
    if (n == name) return t;
  return std::nullopt;
}

struct Property {
  std::string name;
  Type type;                  // a scalar's type, a list's item type
  std::optional<Type> count;  // a list's count type
};

struct Element {
  std::string name;
  unsigned long long count = 0;
  std::vector<Property> properties;
};

enum class Format { ascii, little, big };

struct Header {
  Format format = Format::ascii;
  std::vector<Element> elements;
  std::size_t body = 0;  // where the body begins
};

[[noreturn]] void refuse_header_line(const std::string& source, int number, std::string_view line) {
  throw MeshError(source + ": line " + std::to_string(number) +
                  " of the PLY header is not a PLY header line: '" +
                  std::string(line.substr(0, 80)) + "'");
}

Header read_header(std::string_view text, const std::string& source) {
  const std::size_t end = text.find("\nend_header");
  const std::string_view after = end == std::string_view::npos ? "" : text.substr(end + 11);
  if (!after.starts_with('\n') && !after.starts_with("\r\n"))
    throw MeshError(source + ": the PLY header has no end_header line");
  Header header;
  header.body = end + 11 + (after.starts_with('\n') ? 1 : 2);
  bool format = false;
  Lines lines(text.substr(0, end));
  for (std::string_view line; lines.next(line);) {
    const std::vector<std::string_view> w = words(line);
    const std::string_view keyword = w.empty() ? "" : w[0];
    bool good = false;
    if (lines.number() == 1) {
      good = keyword == "ply" && w.size() == 1;
    } else if (keyword == "comment" || keyword == "obj_info") {
      good = true;
    } else if (keyword == "format" && w.size() == 3 && !format) {
      good = format = true;
      if (w[1] == "ascii")
        header.format = Format::ascii;
      else if (w[1] == "binary_little_endian")
        header.format = Format::little;
      else if (w[1] == "binary_big_endian")
        header.format = Format::big;
      else
        good = false;
    } else if (keyword == "element" && w.size() == 3) {
      long long count = 0;
      good = parse_integer(w[2], count) && count >= 0 && !w[2].starts_with('-');
      if (good) {
        check_count(static_cast<unsigned long long>(count), std::string(w[1]) + " elements",
                    text.size(), source);
        header.elements.push_back({std::string(w[1]), static_cast<unsigned long long>(count), {}});
      }
    } else if (keyword == "property" && !header.elements.empty()) {
      if (w.size() == 3 && type_named(w[1])) {
        good = true;
        header.elements.back().properties.push_back({std::string(w[2]), *type_named(w[1]), {}});
      } else if (w.size() == 5 && w[1] == "list" && type_named(w[2]) && type_named(w[3]) &&
                 type_named(w[2])->kind != Kind::floating) {
        good = true;
        header.elements.back().properties.push_back(
            {std::string(w[4]), *type_named(w[3]), type_named(w[2])});
      }
    }
    if (!good) refuse_header_line(source, lines.number(), line);
  }
  if (!format) throw MeshError(source + ": the PLY header has no format line");
  return header;
}

// What the body is read for: the vertex element's x, y, z and the face element's index list.
struct Roles {
  const Element* vertex = nullptr;
  int x = -1, y = -1, z = -1;
  const Element* face = nullptr;
  int indices = -1;
  const Element* strips = nullptr;
  int strip_indices = -1;
};

Roles find_roles(const Header& header, const std::string& source) {
  Roles roles;
  for (const Element& e : header.elements) {
    if (e.name != "vertex" && e.name != "face" && e.name != "tristrips") continue;
    const Element*& role = e.name == "vertex" ? roles.vertex
                           : e.name == "face" ? roles.face
                                              : roles.strips;
    if (role != nullptr)
      throw MeshError(source + ": the PLY header declares two " + e.name + " elements");
    role = &e;
    for (int p = 0; p < static_cast<int>(e.properties.size()); ++p) {
      const Property& property = e.properties[p];
      if (e.name == "vertex" && !property.count) {
        if (property.name == "x") roles.x = p;
        if (property.name == "y") roles.y = p;
        if (property.name == "z") roles.z = p;
      }
      const bool indices =
          property.count && (property.name == "vertex_indices" || property.name == "vertex_index");
      if (e.name == "face" && indices && roles.indices < 0) roles.indices = p;
      if (e.name == "tristrips" && indices && roles.strip_indices < 0) roles.strip_indices = p;
    }
  }
  if (!roles.vertex || roles.x < 0 || roles.y < 0 || roles.z < 0)
    throw MeshError(source + ": the PLY header declares no vertex element with x, y and z");
  if (roles.face && roles.indices < 0)
    throw MeshError(source + ": the PLY face element has no vertex_indices list");
  if (roles.strips && roles.strip_indices < 0)
    throw MeshError(source + ": the PLY tristrips element has no vertex_indices list");
  for (const auto& [element, p] :
       {std::pair{roles.face, roles.indices}, {roles.strips, roles.strip_indices}})
    if (element && element->properties[p].type.kind == Kind::floating)
      throw MeshError(source + ": the PLY " + element->name +
                      " element's vertex_indices are not integers");
  return roles;
}

// Reads the body, ASCII or binary, element by element, into `soup`. The two differ only in
// how one value is taken, which Values does.
template <class Values>
void read_body(const Header& header, const Roles& roles, Values& values, PolygonSoup& soup,
               const std::string& source) {
  const unsigned long long vertices = roles.vertex->count;
  for (const Element& e : header.elements) {
    values.check_count(e, source);
    const bool is_vertex = &e == roles.vertex, is_face = &e == roles.face,
               is_strip = &e == roles.strips;
    if (is_vertex) soup.points.reserve(static_cast<std::size_t>(e.count));
    if (is_face) soup.face_ends.reserve(static_cast<std::size_t>(e.count));
    for (unsigned long long i = 0; i < e.count; ++i) {
      auto refuse = [&](const std::string& why) {
        throw MeshError(source + ": " + e.name + " " + std::to_string(i) + " of the PLY body " +
                        why + values.where());
      };
      Vec3 point = Vec3::Zero();
      for (int p = 0; p < static_cast<int>(e.properties.size()); ++p) {
        const Property& property = e.properties[p];
        if (!property.count) {
          const double value = values.scalar(property.type, refuse);
          if (is_vertex && (p == roles.x || p == roles.y || p == roles.z))
            point[p == roles.x ? 0 : p == roles.y ? 1 : 2] = value;
          continue;
        }
        const unsigned long long count = values.list_count(*property.count, property.type, refuse);
        const bool corners = is_face && p == roles.indices;
        const bool strip = is_strip && p == roles.strip_indices;
        int last[2] = {-1, -1};  // a strip's two corners before the next
        bool turned = false;
        for (unsigned long long k = 0; k < count; ++k) {
          const double index = values.scalar(property.type, refuse);
          if (!corners && !strip) continue;
          // -1 restarts a strip; as an unsigned type, its bits read as the type's largest value.
          const bool restart =
              index == -1 || (property.type.kind == Kind::unsigned_integer &&
                              index == std::ldexp(1.0, 8 * property.type.size) - 1);
          if (strip && restart) {
            last[0] = last[1] = -1;
            turned = false;
            continue;
          }
          if (!(index >= 0 && index < static_cast<double>(vertices)))
            refuse("has a corner " + std::to_string(static_cast<long long>(index)) +
                   " that is not a vertex index below " + std::to_string(vertices));
          const int corner = static_cast<int>(index);
          if (corners) {
            soup.add_corner(corner);
          } else if (last[0] < 0 || last[1] < 0) {
            last[last[0] < 0 ? 0 : 1] = corner;
          } else {
            if (last[0] != last[1] && last[1] != corner && corner != last[0]) {
              soup.add_corner(last[turned ? 1 : 0]);
              soup.add_corner(last[turned ? 0 : 1]);
              soup.add_corner(corner);
              soup.end_face();
            }
            turned = !turned;
            last[0] = last[1];
            last[1] = corner;
          }
        }
        if (corners) soup.end_face();
      }
      if (is_vertex) soup.points.push_back(point);
    }
  }
}

// ASCII values: whitespace-separated words, lines counted for messages.
class AsciiValues {
 public:
  AsciiValues(std::string_view body, int first_line) : body_(body), line_(first_line) {}

  void check_count(const Element& e, const std::string& source) const {
    // Each value takes a character and a separator at least.
    const unsigned long long per = 2 * std::max<std::size_t>(1, e.properties.size());
    if (e.count > (body_.size() - at_) / per + 1)
      throw MeshError(source + ": the header declares " + std::to_string(e.count) + " " + e.name +
                      " elements, more than the body's " + std::to_string(body_.size() - at_) +
                      " bytes left can hold");
  }

  template <class Refuse>
  double scalar(const Type& type, Refuse& refuse) {
    const std::string_view word = next(refuse);
    double value;
    if (!parse_real(word, value) ||
        (type.kind != Kind::floating && !(std::abs(value) < 1e18 && std::trunc(value) == value)))
      refuse("has a value '" + std::string(word.substr(0, 20)) +
             "' that is not a number of its type");
    return value;
  }

  template <class Refuse>
  unsigned long long list_count(const Type&, const Type&, Refuse& refuse) {
    const std::string_view word = next(refuse);
    long long count = -1;
    // Each item takes a character and a separator at least.
    if (!parse_integer(word, count) || count < 0 ||
        static_cast<unsigned long long>(count) > (body_.size() - at_ + 1) / 2)
      refuse("has a list whose count '" + std::string(word.substr(0, 20)) +
             "' is more than the values left in the file");
    return static_cast<unsigned long long>(count);
  }

  std::string where() const { return line_ > 0 ? " (line " + std::to_string(line_) + ")" : ""; }

 private:
  template <class Refuse>
  std::string_view next(Refuse& refuse) {
    while (at_ < body_.size() && is_space(body_[at_])) line_ += body_[at_++] == '\n';
    if (at_ == body_.size()) {
      line_ = 0;  // no line to name
      refuse("is missing: the file ends first");
    }
    const std::size_t begin = at_;
    while (at_ < body_.size() && !is_space(body_[at_])) ++at_;
    return body_.substr(begin, at_ - begin);
  }

  std::string_view body_;
  std::size_t at_ = 0;
  int line_;
};

// Binary values in the file's byte order.
class BinaryValues {
 public:
  BinaryValues(std::string_view body, bool big) : body_(body), big_(big) {}

  void check_count(const Element& e, const std::string& source) const {
    unsigned long long per = 0;
    for (const Property& p : e.properties) per += p.count ? p.count->size : p.type.size;
    if (per > 0 && e.count > (body_.size() - at_) / per)
      throw MeshError(source + ": the header declares " + std::to_string(e.count) + " " + e.name +
                      " elements, more than the body's " + std::to_string(body_.size() - at_) +
                      " bytes left can hold");
  }

  template <class Refuse>
  double scalar(const Type& type, Refuse& refuse) {
    if (body_.size() - at_ < static_cast<std::size_t>(type.size))
      refuse("is missing: the file ends first");
    std::uint64_t bits = 0;  // the value's bytes, most significant first
    for (int k = 0; k < type.size; ++k) {
      const auto byte = static_cast<unsigned char>(body_[at_ + (big_ ? k : type.size - 1 - k)]);
      bits = (bits << 8) | byte;
    }
    at_ += static_cast<std::size_t>(type.size);
    if (type.kind == Kind::floating)
      return type.size == 4
                 ? static_cast<double>(std::bit_cast<float>(static_cast<std::uint32_t>(bits)))
                 : std::bit_cast<double>(bits);
    if (type.kind == Kind::unsigned_integer) return static_cast<double>(bits);
    const int shift = 64 - 8 * type.size;  // sign-extend
    return static_cast<double>(static_cast<std::int64_t>(bits << shift) >> shift);
  }

  template <class Refuse>
  unsigned long long list_count(const Type& count_type, const Type& item, Refuse& refuse) {
    const double count = scalar(count_type, refuse);
    if (count < 0 ||
        count > static_cast<double>((body_.size() - at_) / static_cast<std::size_t>(item.size)))
      refuse("has a list whose count is more than the bytes left in the file");
    return static_cast<unsigned long long>(count);
  }

  std::string where() const { return ""; }

 private:
  std::string_view body_;
  std::size_t at_ = 0;
  bool big_;
};

int count_lines(std::string_view text) {
  int lines = 0;
  for (char c : text) lines += c == '\n';
  return lines;
}

}  // namespace

PolygonSoup read_ply(std::string_view text, const std::string& source) {
  const Header header = read_header(text, source);
  const Roles roles = find_roles(header, source);
  const std::string_view body = text.substr(header.body);
  PolygonSoup soup;
  if (header.format == Format::ascii) {
    AsciiValues values(body, count_lines(text.substr(0, header.body)) + 1);
    read_body(header, roles, values, soup, source);
  } else {
    BinaryValues values(body, header.format == Format::big);
    read_body(header, roles, values, soup, source);
  }
  return soup;
}

}  // namespace tem::mesh_formats
