// What ranks send each other, as flat arrays of doubles: a body's state, contact memory records
// (contact_memory.hpp), a contact patch's output fields. Integers travel as doubles (exact below 2^53). One
// all-to-all of counts and one of the data per exchange (exchange_with_all).
#pragma once

#include <mpi.h>

#include <vector>

#include "contact/contact_patch.hpp"
#include "dynamics/body_state.hpp"

namespace tem::distributed {

// Appends to / reads from a flat message.
class Packer {
 public:
  explicit Packer(std::vector<double>& out) : out_(out) {}
  void put(double v) { out_.push_back(v); }
  void put(const Vec3& v) { out_.insert(out_.end(), {v.x(), v.y(), v.z()}); }
  void put(const Mat3& m) {
    for (int i = 0; i < 9; ++i) out_.push_back(m.data()[i]);
  }
  void put(const BodyState& s);

 private:
  std::vector<double>& out_;
};

class Unpacker {
 public:
  explicit Unpacker(const std::vector<double>& in) : in_(in) {}
  bool done() const { return at_ >= in_.size(); }
  double number() { return in_.at(at_++); }
  int integer() { return static_cast<int>(number()); }
  Vec3 vec3() {
    Vec3 v(in_.at(at_), in_.at(at_ + 1), in_.at(at_ + 2));
    at_ += 3;
    return v;
  }
  Mat3 mat3() {
    Mat3 m;
    for (int i = 0; i < 9; ++i) m.data()[i] = in_.at(at_ + static_cast<size_t>(i));
    at_ += 9;
    return m;
  }
  BodyState body_state();

 private:
  const std::vector<double>& in_;
  size_t at_ = 0;
};

// Sends send[r] to rank r and returns what every rank sent this one (received[r] from r).
std::vector<std::vector<double>> exchange_with_all(MPI_Comm comm,
                                                   const std::vector<std::vector<double>>& send);

// Gathers every rank's `mine` on rank 0, in rank order (empty on the others).
std::vector<std::vector<double>> gather_to_root(MPI_Comm comm, const std::vector<double>& mine);

}  // namespace tem::distributed
