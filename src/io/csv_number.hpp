// Numbers in TEM's CSV files: the shortest digits that read back as the same double, whatever
// the stream's locale or precision, and never "-0".
#pragma once

#include <charconv>
#include <string>

#include "tem/types.hpp"

namespace tem {

inline void append_number(std::string& row, Real value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value + 0.0);
  row.append(buffer, result.ptr);
}

// ",value"
inline void append_field(std::string& row, Real value) {
  row.push_back(',');
  append_number(row, value);
}

}  // namespace tem
