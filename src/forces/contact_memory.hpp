// The contact memory of a force model: what it carries from one step to the next (SEMM's warm
// start, the penalty model's tangential springs), as records the rest of TEM can keep without
// knowing the model. Each record is one contact's memory, keyed by the two sides it joins
// (body A, and body B or a wall), its contents the model's own numbers. So that bodies can
// leave (population.cpp renumbers the keys and drops what touched a body gone), a checkpoint
// can save it (io/checkpoint.cpp writes the records as they are) and MPI ranks can pass it on
// (distributed/domain.cpp sends a record with its body A), whatever the model.
#pragma once

#include <cstdint>
#include <cstring>
#include <vector>

#include "world/model.hpp"

namespace tem {

struct MemoryRecord {
  int body_a = -1, body_b = -1, wall = -1;
  std::vector<double> values;  // the model's, read back by it alone
};

// After bodies leave (map: old body -> new, -1 for gone): whether a pair of body a and body b
// (b < 0: a wall) touched a body gone, and the pair's new numbers.
inline bool pair_gone(const std::vector<int>& map, int a, int b) {
  return map[a] < 0 || (b >= 0 && map[b] < 0);
}
inline void renumber_pair(const std::vector<int>& map, int& a, int& b) {
  a = map[a];
  if (b >= 0) b = map[b];
}

// Drops the records that touch a body gone and renumbers the rest. The map keeps the bodies'
// order, so the records keep the order of pair_key.
void renumber_records(const std::vector<int>& map, std::vector<MemoryRecord>& records);

// Writing a model's numbers into a record and reading them back: integers as doubles (exact
// below 2^53), reals as they are.
class RecordWriter {
 public:
  explicit RecordWriter(std::vector<double>& out) : out_(out) {}
  void put(double v) { out_.push_back(v); }
  void put(int v) { out_.push_back(static_cast<double>(v)); }
  void put(const Vec3& v) { out_.insert(out_.end(), {v.x(), v.y(), v.z()}); }

 private:
  std::vector<double>& out_;
};

class RecordReader {
 public:
  explicit RecordReader(const std::vector<double>& in) : in_(in) {}
  // Whether `count` more numbers are there (a record from a damaged file may be short).
  bool has(size_t count) const { return in_.size() - at_ >= count; }
  bool done() const { return at_ == in_.size(); }
  double number() { return in_.at(at_++); }
  int integer() { return static_cast<int>(number()); }
  Vec3 vec3() {
    const Vec3 v(in_.at(at_), in_.at(at_ + 1), in_.at(at_ + 2));
    at_ += 3;
    return v;
  }

 private:
  const std::vector<double>& in_;
  size_t at_ = 0;
};

}  // namespace tem
