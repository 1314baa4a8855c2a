#include "distributed/shared_solve.hpp"

#include <algorithm>

#include "distributed/messages.hpp"

namespace tem::distributed {

SharedSolve::SharedSolve(MPI_Comm comm, const BodySubset& subset, const std::vector<int>& owner)
    : comm_(comm), subset_(subset), owner_(owner) {
  MPI_Comm_rank(comm_, &rank_);
  MPI_Comm_size(comm_, &size_);
}

const std::vector<BodyResponse>& SharedSolve::split(const std::vector<ContactPoint>& points,
                                                    const std::vector<BodyResponse>& bodies) {
  given_ = &bodies;
  // The moving bodies this rank's rows touch.
  std::vector<int> touched;
  for (const ContactPoint& c : points)
    for (int b : {c.body_a, c.body_b})
      if (b >= 0 && bodies[b].inverse_mass > 0) touched.push_back(b);
  std::sort(touched.begin(), touched.end());
  touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
  // Each owner learns which other ranks touch its bodies.
  std::vector<std::vector<double>> send(static_cast<size_t>(size_));
  touched_ghosts_.clear();
  std::vector<char> here(bodies.size(), 0);
  for (int b : touched) {
    if (subset_.owned[b]) {
      here[b] = 1;
      continue;
    }
    touched_ghosts_.push_back(b);
    send[static_cast<size_t>(owner_[b])].push_back(b);
  }
  const std::vector<std::vector<double>> told = exchange_with_all(comm_, send);
  meetings_.clear();
  std::vector<int> meeting_of(bodies.size(), -1);
  for (int r = 0; r < size_; ++r)
    for (double id : told[static_cast<size_t>(r)]) {
      const int b = static_cast<int>(id);
      if (meeting_of[b] < 0) {
        meeting_of[b] = static_cast<int>(meetings_.size());
        meetings_.push_back({b, here[b] != 0, {}});
      }
      meetings_[static_cast<size_t>(meeting_of[b])].ranks.push_back(r);  // r ascending
    }
  // The number of copies of each body (the ranks touching it) goes back to those ranks; each
  // scales its copy's response by it.
  std::vector<std::vector<double>> counts(static_cast<size_t>(size_));
  for (const Meeting& m : meetings_) {
    const double k = static_cast<double>(m.ranks.size() + (m.here ? 1 : 0));
    for (int r : m.ranks) {
      counts[static_cast<size_t>(r)].push_back(m.body);
      counts[static_cast<size_t>(r)].push_back(k);
    }
  }
  const std::vector<std::vector<double>> copies = exchange_with_all(comm_, counts);
  split_ = bodies;
  auto scale = [&](int b, double k) {
    if (k <= 1) return;
    split_[b].inverse_mass *= k;
    split_[b].angular *= k;
  };
  for (const Meeting& m : meetings_)
    if (m.here) scale(m.body, static_cast<double>(m.ranks.size() + 1));
  for (const std::vector<double>& from : copies)
    for (size_t i = 0; i + 1 < from.size(); i += 2) scale(static_cast<int>(from[i]), from[i + 1]);
  return split_;
}

void SharedSolve::average(std::vector<SlotVelocity>& slots) {
  ++averages;
  // The touching ranks' copies to the owners.
  std::vector<std::vector<double>> send(static_cast<size_t>(size_));
  for (int b : touched_ghosts_) {
    Packer out(send[static_cast<size_t>(owner_[b])]);
    out.put(b);
    out.put(slots[b].linear);
    out.put(slots[b].angular);
  }
  for (const std::vector<double>& m : send)
    bytes_sent += static_cast<long long>(m.size() * sizeof(double));
  const std::vector<std::vector<double>> copies = exchange_with_all(comm_, send);
  // The owners' means, in rank order (this rank's own copy in its place).
  struct Copy {
    Vec3 v, w;
  };
  std::vector<int> slot(slots.size(), -1);
  for (size_t i = 0; i < meetings_.size(); ++i)
    slot[static_cast<size_t>(meetings_[i].body)] = static_cast<int>(i);
  std::vector<std::vector<Copy>> of_meeting(meetings_.size());
  for (int r = 0; r < size_; ++r) {
    Unpacker in(copies[static_cast<size_t>(r)]);
    while (!in.done()) {
      const int b = in.integer();
      const Vec3 v = in.vec3(), w = in.vec3();
      of_meeting[static_cast<size_t>(slot[b])].push_back({v, w});
    }
  }
  std::vector<std::vector<double>> back(static_cast<size_t>(size_));
  for (size_t i = 0; i < meetings_.size(); ++i) {
    const Meeting& m = meetings_[i];
    const std::vector<Copy>& others = of_meeting[i];  // in the order of m.ranks
    Vec3 v = Vec3::Zero(), w = Vec3::Zero();
    size_t next = 0;
    bool own_added = !m.here;
    for (int r : m.ranks) {
      if (!own_added && r > rank_) {
        v += slots[m.body].linear;
        w += slots[m.body].angular;
        own_added = true;
      }
      v += others[next].v;
      w += others[next].w;
      ++next;
    }
    if (!own_added) {
      v += slots[m.body].linear;
      w += slots[m.body].angular;
    }
    const Real k = static_cast<Real>(m.ranks.size() + (m.here ? 1 : 0));
    slots[m.body].linear = v / k;
    slots[m.body].angular = w / k;
    for (int r : m.ranks) {
      Packer out(back[static_cast<size_t>(r)]);
      out.put(m.body);
      out.put(slots[m.body].linear);
      out.put(slots[m.body].angular);
    }
  }
  for (const std::vector<double>& m : back)
    bytes_sent += static_cast<long long>(m.size() * sizeof(double));
  const std::vector<std::vector<double>> means = exchange_with_all(comm_, back);
  for (const std::vector<double>& from : means) {
    Unpacker in(from);
    while (!in.done()) {
      const int b = in.integer();
      slots[b].linear = in.vec3();
      slots[b].angular = in.vec3();
    }
  }
}

SweepSize SharedSolve::largest(const SweepSize& mine) {
  double local[2] = {mine.change, mine.largest}, all[2] = {0, 0};
  MPI_Allreduce(local, all, 2, MPI_DOUBLE, MPI_MAX, comm_);
  SweepSize s;
  s.change = all[0];
  s.largest = all[1];
  return s;
}

// Gathered and added in rank order on every rank: the same bits everywhere (an all-reduce
// may add in a different order on different ranks, and a decision taken on a sum must be the
// same on all of them, or they part ways).
Real SharedSolve::sum(Real mine) {
  std::vector<double> all(static_cast<size_t>(size_));
  MPI_Allgather(&mine, 1, MPI_DOUBLE, all.data(), 1, MPI_DOUBLE, comm_);
  Real total = 0;
  for (double x : all) total += x;
  return total;
}

}  // namespace tem::distributed
