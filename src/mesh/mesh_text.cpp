// Plain-text scanning shared by the OBJ, OFF, ASCII PLY and ASCII STL readers (mesh_formats.hpp).
#include <charconv>
#include <cstdlib>
#include <string>
#include <system_error>

#include "mesh/mesh_formats.hpp"

namespace tem::mesh_formats {

bool Lines::next(std::string_view& line) {
  if (at_ >= text_.size()) return false;
  std::size_t end = text_.find('\n', at_);
  if (end == std::string_view::npos) end = text_.size();
  line = text_.substr(at_, end - at_);
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  at_ = end + 1;
  ++number_;
  return true;
}

bool is_space(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f';
}

std::string_view without_byte_order_mark(std::string_view text) {
  if (text.starts_with("\xEF\xBB\xBF")) text.remove_prefix(3);
  return text;
}

std::vector<std::string_view> words(std::string_view line, char comment) {
  if (comment != '\0') line = line.substr(0, line.find(comment));
  std::vector<std::string_view> result;
  std::size_t at = 0;
  while (true) {
    while (at < line.size() && is_space(line[at])) ++at;
    if (at == line.size()) break;
    std::size_t end = at;
    while (end < line.size() && !is_space(line[end])) ++end;
    result.push_back(line.substr(at, end - at));
    at = end;
  }
  return result;
}

bool parse_real(std::string_view word, double& value) {
  if (!word.empty() && word.front() == '+') word.remove_prefix(1);
  if (word.empty() || word.front() == '+') return false;
  const char* end = word.data() + word.size();
  const auto [stop, error] = std::from_chars(word.data(), end, value);
  if (stop != end) return false;
  if (error == std::errc::result_out_of_range) {
    // from_chars leaves `value` alone here; strtod gives the overflow's infinity or the
    // underflow's zero or subnormal. The word is known to be one whole number by now.
    value = std::strtod(std::string(word).c_str(), nullptr);
    return true;
  }
  return error == std::errc();
}

bool parse_integer(std::string_view word, long long& value) {
  if (!word.empty() && word.front() == '+') word.remove_prefix(1);
  const std::size_t digits = word.size() - (!word.empty() && word.front() == '-' ? 1 : 0);
  if (digits == 0 || digits > 18) return false;
  const char* end = word.data() + word.size();
  const auto [stop, error] = std::from_chars(word.data(), end, value);
  return stop == end && error == std::errc();
}

void check_count(unsigned long long count, const std::string& what, std::size_t size,
                 const std::string& source) {
  if (count <= size) return;
  throw MeshError(source + ": the header declares " + std::to_string(count) + " " + what +
                  ", more than the file's " + std::to_string(size) + " bytes can hold");
}

std::string at_line(int number) { return "line " + std::to_string(number) + ": "; }

}  // namespace tem::mesh_formats
