#include "io/vtu_text.hpp"

#include <charconv>

#include "io/csv_number.hpp"

namespace tem {
namespace {

void open_array(std::string& text, const char* type, const char* name, int components) {
  text += "<DataArray type=\"";
  text += type;
  text += "\" Name=\"";
  text += name;
  text += '"';
  // Scalars go without NumberOfComponents, as VTK writes them: readers then give 1-D arrays.
  if (components > 1) text += " NumberOfComponents=\"" + std::to_string(components) + '"';
  text += " format=\"ascii\">\n";
}

void append_integer(std::string& text, long long value) {
  char buffer[24];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  text.append(buffer, result.ptr);
}

// One tuple per line keeps the file readable by eye at no cost to readers.
void append_vector_lines(std::string& text, const std::vector<Vec3>& values) {
  for (const Vec3& v : values) {
    append_number(text, v.x());
    text.push_back(' ');
    append_number(text, v.y());
    text.push_back(' ');
    append_number(text, v.z());
    text.push_back('\n');
  }
}

}  // namespace

VtuText::VtuText(Real time, size_t points, size_t cells) {
  text_.reserve(64 * (points + cells) + 1024);
  text_ +=
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
      "header_type=\"UInt64\">\n"
      "<UnstructuredGrid>\n"
      "<FieldData>\n"
      "<DataArray type=\"Float64\" Name=\"TimeValue\" NumberOfTuples=\"1\" format=\"ascii\">\n";
  append_number(text_, time);
  text_ += "\n</DataArray>\n</FieldData>\n";
  text_ += "<Piece NumberOfPoints=\"" + std::to_string(points) + "\" NumberOfCells=\"" +
           std::to_string(cells) + "\">\n";
}

void VtuText::vectors(const char* name, const std::vector<Vec3>& values) {
  open_array(text_, "Float64", name, 3);
  append_vector_lines(text_, values);
  text_ += "</DataArray>\n";
}

void VtuText::reals(const char* name, const std::vector<Real>& values) {
  open_array(text_, "Float64", name, 1);
  for (Real v : values) {
    append_number(text_, v);
    text_.push_back('\n');
  }
  text_ += "</DataArray>\n";
}

void VtuText::ints(const char* name, const std::vector<int>& values) {
  open_array(text_, "Int32", name, 1);
  for (int v : values) {
    append_integer(text_, v);
    text_.push_back('\n');
  }
  text_ += "</DataArray>\n";
}

void VtuText::points(const std::vector<Vec3>& positions) {
  text_ += "<Points>\n";
  open_array(text_, "Float64", "Points", 3);
  append_vector_lines(text_, positions);
  text_ += "</DataArray>\n</Points>\n";
}

void VtuText::cells(const std::vector<std::int64_t>& connectivity, int nodes_per_cell,
                    std::uint8_t type) {
  const size_t count = connectivity.size() / static_cast<size_t>(nodes_per_cell);
  text_ += "<Cells>\n";
  open_array(text_, "Int64", "connectivity", 1);
  for (size_t c = 0; c < count; ++c) {
    for (int k = 0; k < nodes_per_cell; ++k) {
      if (k > 0) text_.push_back(' ');
      append_integer(text_, connectivity[c * nodes_per_cell + k]);
    }
    text_.push_back('\n');
  }
  text_ += "</DataArray>\n";
  open_array(text_, "Int64", "offsets", 1);
  for (size_t c = 1; c <= count; ++c) {
    append_integer(text_, static_cast<long long>(c) * nodes_per_cell);
    text_.push_back('\n');
  }
  text_ += "</DataArray>\n";
  open_array(text_, "UInt8", "types", 1);
  const std::string type_line = std::to_string(type) + "\n";
  for (size_t c = 0; c < count; ++c) text_ += type_line;
  text_ += "</DataArray>\n</Cells>\n";
}

std::string VtuText::finish() {
  text_ += "</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
  return std::move(text_);
}

}  // namespace tem
