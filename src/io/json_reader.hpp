// Reading hand-written JSON value by value, with the path of each value, collecting every
// problem instead of stopping at the first.
//
// This is the half of the scene reader (scene_reader.cpp) that knows JSON and paths such as
// `bodies[1].shape.radius` but nothing about scenes: path building, the pieces of messages
// ("must be X, got Y", "did you mean"), a `Reader` that reads one value of each kind and
// records a problem when it is wrong, a `PathTracker` that watches the parser for what the
// JSON library lets through silently (duplicate keys), and the wording of syntax errors.
// Problems go to a caller-supplied sink, so no scene type is needed here.
#pragma once

#include <cstddef>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_set>
#include <utility>
#include <vector>

#include "tem/types.hpp"

namespace tem::json {

// ordered_json keeps the file's key order, so unknown keys are reported in reading order.
using Json = nlohmann::ordered_json;
using KeyList = std::vector<std::string_view>;

// Receives each problem: the JSON path of the value ("(root)" for the document as a whole)
// and a reason in plain words. The caller decides how to keep them.
using ProblemSink = std::function<void(std::string path, std::string message)>;

// ---- Paths and message pieces ------------------------------------------------------------

// `path.key`, or just `key` at the root (empty path).
std::string child(const std::string& path, std::string_view key);
// `path[index]`.
std::string element(const std::string& path, std::size_t index);

// Shortest text that reads back as the same double (1e-05, 0.1, 980.665), so a message shows
// the value as written rather than a rounded one.
std::string format_number(Real x);
// `s` in double quotes, escaped and cut to 40 characters, so a message stays one short line.
std::string in_quotes(std::string_view s);
// A JSON number as written: integers without a decimal point, others via format_number().
std::string number_text(const Json& j);
// What a value is, for "must be X, got Y" messages ("the number 3", "a list of 2", ...).
std::string describe(const Json& j);

// ---- Did you mean ------------------------------------------------------------------------

// The allowed word nearest to `word` (edit distance, ignoring case), if it is near enough to
// be a plausible typo; otherwise nothing, and the message lists what is allowed instead.
std::optional<std::string_view> closest(std::string_view word, const KeyList& allowed);
// 'a', 'b', 'c': the allowed words for a message.
std::string join_quoted(const KeyList& words);
bool contains(const KeyList& list, std::string_view word);

// ---- The reader --------------------------------------------------------------------------

// Range a number must lie in.
enum class Bound { any, positive, non_negative, unit_interval };

// Reads one JSON value of each kind at a given path. A wrong value is recorded as a problem
// (never thrown) and gives nothing back, so the caller keeps its default and goes on reading.
class Reader {
 public:
  explicit Reader(ProblemSink sink) : sink_(std::move(sink)) {}

  // Records a problem at `path` (the empty path is the document, shown as "(root)").
  void fail(const std::string& path, std::string message);

  // Whether `j` is an object; records a problem if not.
  bool object(const Json& j, const std::string& path);

  // Reports every key of `obj` that is not in `allowed`. `explain` may give a better reason
  // for a particular key (valid elsewhere, say); it returns "" to use the generic one.
  template <class Explain>
  void check_keys(const Json& obj, const std::string& path, const KeyList& allowed,
                  Explain explain) {
    for (const auto& [key, value] : obj.items()) {
      if (contains(allowed, key)) continue;
      std::string reason = explain(key);
      if (reason.empty()) {
        reason = "unknown key '" + key + "'";
        if (auto guess = closest(key, allowed)) {
          reason += " (did you mean '" + std::string(*guess) + "'?)";
        } else {
          reason += " (allowed here: " + join_quoted(allowed) + ")";
        }
      }
      fail(path, reason);
    }
  }
  void check_keys(const Json& obj, const std::string& path, const KeyList& allowed) {
    check_keys(obj, path, allowed, [](std::string_view) { return std::string(); });
  }

  // obj[key], or null when absent (no problem recorded).
  static const Json* get(const Json& obj, std::string_view key);
  // obj[key], or null and a "missing required key" problem when absent.
  const Json* need(const Json& obj, const std::string& path, std::string_view key);

  // A finite number within `bound`.
  std::optional<Real> number(const Json& j, const std::string& path, Bound bound);
  // A whole number in [lo, hi] (3.0 counts as an integer; 3.5 does not).
  std::optional<int> integer(const Json& j, const std::string& path, int lo, int hi);
  std::optional<bool> boolean(const Json& j, const std::string& path);
  std::optional<std::string> string(const Json& j, const std::string& path);
  // A list of exactly `n` numbers, each within `bound`; every bad element is reported.
  std::optional<std::vector<Real>> numbers(const Json& j, const std::string& path, std::size_t n,
                                           Bound bound);
  std::optional<Vec3> vec3(const Json& j, const std::string& path, Bound bound = Bound::any);

  // One of the strings of `options`, giving its value; a near miss gets a "did you mean".
  template <class T>
  std::optional<T> choice(const Json& j, const std::string& path,
                          const std::vector<std::pair<std::string_view, T>>& options) {
    KeyList names;
    for (const auto& option : options) names.push_back(option.first);
    std::string wanted = "must be one of ";
    for (std::size_t i = 0; i < names.size(); ++i) {
      wanted += (i ? ", \"" : "\"") + std::string(names[i]) + "\"";
    }
    if (!j.is_string()) {
      fail(path, wanted + ", got " + describe(j));
      return std::nullopt;
    }
    const auto& s = j.get_ref<const std::string&>();
    for (const auto& [name, value] : options) {
      if (s == name) return value;
    }
    std::string reason = wanted + ", got " + in_quotes(s);
    if (auto guess = closest(s, names))
      reason += " (did you mean \"" + std::string(*guess) + "\"?)";
    fail(path, reason);
    return std::nullopt;
  }

  // Field helpers: read obj[key] into *out when present and valid; otherwise the default in
  // *out stays. A missing key is a problem only when `required`. Return whether *out was set.
  template <class T, class ReadValue>
  bool field(const Json& obj, const std::string& path, std::string_view key, T* out, bool required,
             ReadValue read) {
    const Json* j = required ? need(obj, path, key) : get(obj, key);
    if (!j) return false;
    const auto x = read(*j, child(path, key));
    if (x) *out = *x;
    return x.has_value();
  }
  bool read_number(const Json& obj, const std::string& path, std::string_view key, Real* out,
                   Bound bound, bool required = false);
  bool read_int(const Json& obj, const std::string& path, std::string_view key, int* out, int lo,
                int hi, bool required = false);
  bool read_bool(const Json& obj, const std::string& path, std::string_view key, bool* out);
  bool read_vec3(const Json& obj, const std::string& path, std::string_view key, Vec3* out,
                 Bound bound = Bound::any, bool required = false);

 private:
  ProblemSink sink_;
};

// ---- Parsing -----------------------------------------------------------------------------

// Follows the parser's position as a JSON path, to report duplicate keys (the JSON library
// silently keeps the last one, so a repeated "radius" would go unnoticed) and to say where a
// number too large for a double was met. Pass it as the parser callback of Json::parse.
class PathTracker {
 public:
  explicit PathTracker(ProblemSink sink) : sink_(std::move(sink)) {}

  bool operator()(int depth, Json::parse_event_t event, Json& parsed);

  // Path of the value being read now (the one after the last key, or the next list element).
  std::string pending_path() const { return path(1); }

 private:
  struct Frame {
    bool array;
    long index;
    std::string key;
    std::unordered_set<std::string> keys;
  };

  void enter_value();
  // `ahead` = 1 names the list element after the last one seen.
  std::string path(int ahead) const;

  ProblemSink sink_;
  std::vector<Frame> frames_;
};

// "syntax error at line L, column C: reason", with L and C from the byte offset of the error;
// NaN and Infinity, which people do write, get their own explanation.
std::string syntax_message(const std::string& text, const Json::parse_error& error);

// Whether `text` holds only white space (an empty file deserves its own message).
bool blank(const std::string& text);

}  // namespace tem::json
