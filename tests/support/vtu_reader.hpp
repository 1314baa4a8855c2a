// A reader, for the tests, of the .vtu files TEM writes (src/io/vtu_binary.hpp): the XML's
// DataArray tags, and each array's bytes decoded from the appended raw data (VTK's zlib blocks,
// UInt64 header). It checks the layout as it goes and throws std::runtime_error, saying what is
// wrong, where a file is not as VTK's readers expect: the "\n_" before the data and the "\n"
// after it, the arrays tiling the data (each, in the order of their offsets, starting where the
// one before it ends, nothing between or after them; TEM lays them out in the reverse of the
// XML's order, vtu_binary.hpp), every block inflating to the size the header gives.
//
// It shares no code with the writer, so that a test of the writer does not read the writer's
// own mistakes back as right.
#pragma once

#include <zlib.h>

#include <cstdint>
#include <cstring>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace tem::testing_support {

struct VtuArray {
  std::string section;  // FieldData, PointData, CellData, Points or Cells
  std::string type;     // Float64, Int32, Int64, UInt8
  int components = 1;
  std::uint64_t blocks = 0, block_size = 0, last_block = 0;  // the compression header
  std::uint64_t compressed = 0;                              // the zlib blocks' bytes
  std::string bytes;                                         // inflated

  // The values, when T is as wide as `type` says; throws otherwise.
  template <class T>
  std::vector<T> values() const {
    const std::map<std::string, size_t> widths = {
        {"Float64", 8}, {"Int32", 4}, {"Int64", 8}, {"UInt8", 1}};
    const auto width = widths.find(type);
    if (width == widths.end() || width->second != sizeof(T) || bytes.size() % sizeof(T) != 0)
      throw std::runtime_error("array of type " + type + " read with a type of " +
                               std::to_string(sizeof(T)) + " bytes");
    std::vector<T> out(bytes.size() / sizeof(T));
    if (!out.empty()) std::memcpy(out.data(), bytes.data(), bytes.size());
    return out;
  }
};

struct VtuFile {
  std::map<std::string, std::string> root;  // the VTKFile tag's attributes
  long long points = -1, cells = -1;        // the Piece's
  std::vector<std::string> names;           // the arrays in the order of the file
  std::map<std::string, VtuArray> arrays;
};

namespace vtu_detail {

inline std::map<std::string, std::string> attributes(const std::string& tag) {
  std::map<std::string, std::string> out;
  for (size_t at = tag.find('='); at != std::string::npos; at = tag.find('=', at + 1)) {
    const size_t name_start = tag.rfind(' ', at) + 1;
    const size_t value_end = tag.find('"', at + 2);
    if (tag[at + 1] != '"' || value_end == std::string::npos)
      throw std::runtime_error("bad attribute in " + tag);
    out[tag.substr(name_start, at - name_start)] = tag.substr(at + 2, value_end - at - 2);
    at = value_end;
  }
  return out;
}

inline std::uint64_t uint64_at(const std::string& data, size_t offset) {
  if (offset + 8 > data.size()) throw std::runtime_error("header past the end of the data");
  std::uint64_t value;
  std::memcpy(&value, data.data() + offset, 8);  // LittleEndian, as is this machine
  return value;
}

// Inflates the array at `offset` of the appended data into `array`; returns where it ends.
inline size_t inflate_array(const std::string& data, size_t offset, VtuArray& array) {
  array.blocks = uint64_at(data, offset);
  array.block_size = uint64_at(data, offset + 8);
  array.last_block = uint64_at(data, offset + 16);
  size_t position = offset + 8 * (3 + array.blocks);
  for (std::uint64_t b = 0; b < array.blocks; ++b) {
    const std::uint64_t compressed = uint64_at(data, offset + 24 + 8 * b);
    const bool partial = b + 1 == array.blocks && array.last_block != 0;
    const std::uint64_t expected = partial ? array.last_block : array.block_size;
    if (position + compressed > data.size()) throw std::runtime_error("block past the end");
    std::string block(expected, '\0');
    uLongf length = expected;
    if (uncompress(reinterpret_cast<Bytef*>(block.data()), &length,
                   reinterpret_cast<const Bytef*>(data.data() + position), compressed) != Z_OK ||
        length != expected)
      throw std::runtime_error("block " + std::to_string(b) + " does not inflate to " +
                               std::to_string(expected) + " bytes");
    array.bytes += block;
    array.compressed += compressed;
    position += compressed;
  }
  return position;
}

}  // namespace vtu_detail

inline VtuFile read_vtu(const std::string& file) {
  const std::string opening = "<AppendedData encoding=\"raw\">\n_";
  const std::string closing = "\n</AppendedData>\n</VTKFile>\n";
  const size_t data_start = file.find(opening);
  if (data_start == std::string::npos ||
      file.size() < data_start + opening.size() + closing.size() ||
      file.compare(file.size() - closing.size(), closing.size(), closing) != 0)
    throw std::runtime_error(
        "no <AppendedData encoding=\"raw\">\\n_DATA\\n</AppendedData> at the end");
  const std::string xml = file.substr(0, data_start);
  const std::string data = file.substr(data_start + opening.size(),
                                       file.size() - closing.size() - data_start - opening.size());

  VtuFile out;
  std::string section;
  std::map<size_t, std::string> at_offset;  // the arrays by offset, to check they tile the data
  for (size_t open = xml.find('<'); open != std::string::npos; open = xml.find('<', open + 1)) {
    const std::string tag = xml.substr(open, xml.find('>', open) - open + 1);
    const std::string name = tag.substr(1, tag.find_first_of(" />") - 1);
    const auto attrs = vtu_detail::attributes(tag);
    if (name == "VTKFile") out.root = attrs;
    if (name == "Piece") {
      out.points = std::stoll(attrs.at("NumberOfPoints"));
      out.cells = std::stoll(attrs.at("NumberOfCells"));
    }
    if (name == "FieldData" || name == "PointData" || name == "CellData" || name == "Points" ||
        name == "Cells")
      section = name;
    if (name != "DataArray") continue;
    VtuArray array;
    array.section = section;
    array.type = attrs.at("type");
    if (attrs.count("NumberOfComponents"))
      array.components = std::stoi(attrs.at("NumberOfComponents"));
    if (attrs.at("format") != "appended")
      throw std::runtime_error(attrs.at("Name") + " is not appended");
    if (!at_offset.emplace(std::stoull(attrs.at("offset")), attrs.at("Name")).second)
      throw std::runtime_error(attrs.at("Name") + " shares its offset with another array");
    out.names.push_back(attrs.at("Name"));
    out.arrays[attrs.at("Name")] = std::move(array);
  }
  size_t end_of_last = 0;
  for (const auto& [offset, name] : at_offset) {
    if (offset != end_of_last)
      throw std::runtime_error(name + " is not appended at offset " +
                               std::to_string(end_of_last));
    end_of_last = vtu_detail::inflate_array(data, offset, out.arrays[name]);
  }
  if (end_of_last != data.size())
    throw std::runtime_error(std::to_string(data.size() - end_of_last) +
                             " bytes of appended data after the last array");
  return out;
}

}  // namespace tem::testing_support
