// Reading hand-written JSON with paths (see json_reader.hpp).
#include "io/json_reader.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <limits>

namespace tem::json {
namespace {

// Levenshtein distance, for "did you mean" hints.
std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      const bool same = std::tolower(static_cast<unsigned char>(a[i - 1])) ==
                        std::tolower(static_cast<unsigned char>(b[j - 1]));
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (same ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

bool is_nan_or_infinity_word(std::string word) {
  std::transform(word.begin(), word.end(), word.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  if (!word.empty() && (word[0] == '-' || word[0] == '+')) word.erase(0, 1);
  return word == "nan" || word == "inf" || word == "infinity";
}

}  // namespace

// ---- Paths and message pieces ------------------------------------------------------------

std::string child(const std::string& path, std::string_view key) {
  return path.empty() ? std::string(key) : path + "." + std::string(key);
}

std::string element(const std::string& path, std::size_t index) {
  return path + "[" + std::to_string(index) + "]";
}

// Shortest text that reads back as the same double (1e-05, 0.1, 980.665).
std::string format_number(Real x) {
  if (std::isnan(x)) return "NaN";
  if (std::isinf(x)) return x > 0 ? "infinity" : "-infinity";
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, x);
  return std::string(buffer, result.ptr);
}

std::string in_quotes(std::string_view s) {
  constexpr std::size_t kMaxShown = 40;
  std::string shown(s.substr(0, kMaxShown));
  if (s.size() > kMaxShown) shown += "...";
  // Json's dump escapes quotes and control characters, so the message stays one line.
  return Json(shown).dump(-1, ' ', false, Json::error_handler_t::replace);
}

std::string number_text(const Json& j) {
  if (j.is_number_integer()) {
    return j.is_number_unsigned() ? std::to_string(j.get<std::uint64_t>())
                                  : std::to_string(j.get<std::int64_t>());
  }
  return format_number(j.get<Real>());
}

// What a value is, for "must be X, got Y" messages.
std::string describe(const Json& j) {
  switch (j.type()) {
    case Json::value_t::null:
      return "null";
    case Json::value_t::boolean:
      return j.get<bool>() ? "true" : "false";
    case Json::value_t::number_integer:
    case Json::value_t::number_unsigned:
    case Json::value_t::number_float:
      return "the number " + number_text(j);
    case Json::value_t::string:
      return "a string (" + in_quotes(j.get_ref<const std::string&>()) + ")";
    case Json::value_t::array:
      return j.empty() ? "an empty list" : "a list of " + std::to_string(j.size());
    case Json::value_t::object:
      return "an object";
    default:
      return "an unreadable value";
  }
}

// The allowed word nearest to `word`, if it is near enough to be a plausible typo.
std::optional<std::string_view> closest(std::string_view word, const KeyList& allowed) {
  std::optional<std::string_view> best;
  std::size_t best_distance = std::numeric_limits<std::size_t>::max();
  for (std::string_view candidate : allowed) {
    const std::size_t d = edit_distance(word, candidate);
    if (d < best_distance) {
      best_distance = d;
      best = candidate;
    }
  }
  const std::size_t tolerance = std::max<std::size_t>(2, word.size() / 3);
  if (best && best_distance <= tolerance && best_distance < word.size()) return best;
  return std::nullopt;
}

std::string join_quoted(const KeyList& words) {
  std::string out;
  for (std::string_view w : words) {
    if (!out.empty()) out += ", ";
    // Appended piece by piece: GCC 12 gives a false -Wrestrict for "'" + std::string(w).
    out += '\'';
    out += w;
    out += '\'';
  }
  return out;
}

bool contains(const KeyList& list, std::string_view word) {
  return std::find(list.begin(), list.end(), word) != list.end();
}

// ---- The reader --------------------------------------------------------------------------

void Reader::fail(const std::string& path, std::string message) {
  sink_(path.empty() ? "(root)" : path, std::move(message));
}

bool Reader::object(const Json& j, const std::string& path) {
  if (j.is_object()) return true;
  fail(path, "must be an object ({...}), got " + describe(j));
  return false;
}

const Json* Reader::get(const Json& obj, std::string_view key) {
  const auto it = obj.find(key);
  return it == obj.end() ? nullptr : &*it;
}

const Json* Reader::need(const Json& obj, const std::string& path, std::string_view key) {
  const Json* value = get(obj, key);
  if (!value) fail(path, "missing required key '" + std::string(key) + "'");
  return value;
}

std::optional<Real> Reader::number(const Json& j, const std::string& path, Bound bound) {
  if (!j.is_number()) {
    fail(path, "must be a number, got " + describe(j));
    return std::nullopt;
  }
  const Real x = j.get<Real>();
  if (!std::isfinite(x)) {
    fail(path, "must be a finite number, got " + format_number(x));
    return std::nullopt;
  }
  // Comparisons are written so that they fail for values outside the bound.
  std::string wanted;
  switch (bound) {
    case Bound::any:
      break;
    case Bound::positive:
      if (!(x > 0)) wanted = "must be a positive number";
      break;
    case Bound::non_negative:
      if (!(x >= 0)) wanted = "must be zero or positive";
      break;
    case Bound::unit_interval:
      if (!(x >= 0 && x <= 1)) wanted = "must be between 0 and 1";
      break;
  }
  if (!wanted.empty()) {
    fail(path, wanted + ", got " + number_text(j));
    return std::nullopt;
  }
  return x;
}

std::optional<int> Reader::integer(const Json& j, const std::string& path, int lo, int hi) {
  if (!j.is_number()) {
    fail(path, "must be an integer, got " + describe(j));
    return std::nullopt;
  }
  const Real x = j.get<Real>();
  if (!std::isfinite(x) || x != std::floor(x)) {
    fail(path, "must be an integer, got " + number_text(j));
    return std::nullopt;
  }
  if (x < lo) {
    fail(path, "must be an integer of at least " + std::to_string(lo) + ", got " + number_text(j));
    return std::nullopt;
  }
  if (x > hi) {
    fail(path, "must be at most " + std::to_string(hi) + ", got " + number_text(j));
    return std::nullopt;
  }
  return static_cast<int>(x);
}

std::optional<bool> Reader::boolean(const Json& j, const std::string& path) {
  if (j.is_boolean()) return j.get<bool>();
  fail(path, "must be true or false, got " + describe(j));
  return std::nullopt;
}

std::optional<std::string> Reader::string(const Json& j, const std::string& path) {
  if (j.is_string()) return j.get<std::string>();
  fail(path, "must be a string, got " + describe(j));
  return std::nullopt;
}

std::optional<std::vector<Real>> Reader::numbers(const Json& j, const std::string& path,
                                                 std::size_t n, Bound bound) {
  const std::string wanted = "must be a list of " + std::to_string(n) + " numbers";
  if (!j.is_array() || j.size() != n) {
    fail(path, wanted + ", got " + describe(j));
    return std::nullopt;
  }
  std::vector<Real> out(n);
  bool good = true;
  for (std::size_t i = 0; i < n; ++i) {
    const auto x = number(j[i], element(path, i), bound);
    good = good && x.has_value();  // every element is checked, so every bad one reported
    if (x) out[i] = *x;
  }
  if (!good) return std::nullopt;
  return out;
}

std::optional<Vec3> Reader::vec3(const Json& j, const std::string& path, Bound bound) {
  const auto v = numbers(j, path, 3, bound);
  if (!v) return std::nullopt;
  return Vec3((*v)[0], (*v)[1], (*v)[2]);
}

bool Reader::read_number(const Json& obj, const std::string& path, std::string_view key, Real* out,
                         Bound bound, bool required) {
  return field(obj, path, key, out, required,
               [&](const Json& j, const std::string& p) { return number(j, p, bound); });
}

bool Reader::read_int(const Json& obj, const std::string& path, std::string_view key, int* out,
                      int lo, int hi, bool required) {
  return field(obj, path, key, out, required,
               [&](const Json& j, const std::string& p) { return integer(j, p, lo, hi); });
}

bool Reader::read_bool(const Json& obj, const std::string& path, std::string_view key, bool* out) {
  return field(obj, path, key, out, false,
               [&](const Json& j, const std::string& p) { return boolean(j, p); });
}

bool Reader::read_vec3(const Json& obj, const std::string& path, std::string_view key, Vec3* out,
                       Bound bound, bool required) {
  return field(obj, path, key, out, required,
               [&](const Json& j, const std::string& p) { return vec3(j, p, bound); });
}

// ---- Parsing -------------------------------------------------------------------------------

bool PathTracker::operator()(int /*depth*/, Json::parse_event_t event, Json& parsed) {
  using E = Json::parse_event_t;
  switch (event) {
    case E::object_start:
    case E::array_start:
      enter_value();
      frames_.push_back({event == E::array_start, -1, {}, {}});
      break;
    case E::key: {
      Frame& top = frames_.back();
      top.key = parsed.get<std::string>();
      if (!top.keys.insert(top.key).second) {
        sink_(path(0),
              "duplicate key '" + top.key + "' (JSON keeps only the last one; remove the other)");
      }
      break;
    }
    case E::value:
      enter_value();
      break;
    case E::object_end:
    case E::array_end:
      frames_.pop_back();
      break;
  }
  return true;
}

void PathTracker::enter_value() {
  if (!frames_.empty() && frames_.back().array) ++frames_.back().index;
}

std::string PathTracker::path(int ahead) const {
  std::string p;
  for (std::size_t i = 0; i < frames_.size(); ++i) {
    const Frame& f = frames_[i];
    const bool last = i + 1 == frames_.size();
    if (f.array) {
      p = element(p, static_cast<std::size_t>(f.index + (last ? ahead : 0)));
    } else {
      p = child(p, f.key);
    }
  }
  return p.empty() ? "(root)" : p;
}

// "syntax error at line L, column C: reason", with L and C from the byte offset of the error.
std::string syntax_message(const std::string& text, const Json::parse_error& error) {
  std::size_t at = error.byte == 0 ? 0 : std::min<std::size_t>(error.byte - 1, text.size());
  // The word at the error: NaN and Infinity deserve their own explanation.
  auto word_char = [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '+' || c == '.';
  };
  std::size_t begin = at;
  while (begin > 0 && begin <= text.size() && word_char(text[begin - 1])) --begin;
  std::size_t end = at;
  while (end < text.size() && word_char(text[end])) ++end;
  const std::string word = text.substr(begin, end - begin);
  const bool nan_or_inf = is_nan_or_infinity_word(word);
  if (nan_or_inf) at = begin;

  const std::size_t line = 1 + std::count(text.begin(), text.begin() + at, '\n');
  const std::size_t line_start = text.rfind('\n', at == 0 ? 0 : at - 1);
  const std::size_t column =
      at + 1 - (line_start == std::string::npos || at == 0 ? 0 : line_start + 1);
  std::string where =
      "syntax error at line " + std::to_string(line) + ", column " + std::to_string(column) + ": ";

  if (nan_or_inf) {
    return where + word + " is not valid JSON (JSON has no NaN or infinity); write a finite number";
  }
  // The library's own reason follows "... - " in its message ("invalid literal; last read...").
  std::string reason = error.what();
  const std::size_t dash = reason.find(" - ");
  reason = dash == std::string::npos ? reason : reason.substr(dash + 3);
  return where + reason;
}

bool blank(const std::string& text) {
  return std::all_of(text.begin(), text.end(),
                     [](unsigned char c) { return std::isspace(c) != 0; });
}

}  // namespace tem::json
