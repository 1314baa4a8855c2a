#include "distributed/messages.hpp"

#include <stdexcept>

namespace tem::distributed {

void Packer::put(const BodyState& s) {
  put(s.x);
  put(s.v);
  put(s.g);
  put(s.omega);
  put(s.prev_torque);
  put(s.has_prev_torque ? 1.0 : 0.0);
}

BodyState Unpacker::body_state() {
  BodyState s;
  s.x = vec3();
  s.v = vec3();
  s.g = mat3();
  s.omega = vec3();
  s.prev_torque = vec3();
  s.has_prev_torque = number() != 0;
  return s;
}

namespace {
std::vector<int> displacements(const std::vector<int>& counts) {
  std::vector<int> at(counts.size(), 0);
  for (size_t r = 1; r < counts.size(); ++r) at[r] = at[r - 1] + counts[r - 1];
  return at;
}
void check(int code, const char* what) {
  if (code != MPI_SUCCESS) throw std::runtime_error(std::string(what) + " failed");
}
}  // namespace

std::vector<std::vector<double>> exchange_with_all(MPI_Comm comm,
                                                   const std::vector<std::vector<double>>& send) {
  int size = 1;
  MPI_Comm_size(comm, &size);
  std::vector<int> send_counts(static_cast<size_t>(size)),
      receive_counts(static_cast<size_t>(size));
  std::vector<double> flat;
  for (int r = 0; r < size; ++r) {
    send_counts[static_cast<size_t>(r)] = static_cast<int>(send[static_cast<size_t>(r)].size());
    flat.insert(flat.end(), send[static_cast<size_t>(r)].begin(),
                send[static_cast<size_t>(r)].end());
  }
  check(MPI_Alltoall(send_counts.data(), 1, MPI_INT, receive_counts.data(), 1, MPI_INT, comm),
        "MPI_Alltoall");
  const std::vector<int> send_at = displacements(send_counts);
  const std::vector<int> receive_at = displacements(receive_counts);
  std::vector<double> received(static_cast<size_t>(receive_at.back() + receive_counts.back()));
  check(MPI_Alltoallv(flat.data(), send_counts.data(), send_at.data(), MPI_DOUBLE, received.data(),
                      receive_counts.data(), receive_at.data(), MPI_DOUBLE, comm),
        "MPI_Alltoallv");
  std::vector<std::vector<double>> out(static_cast<size_t>(size));
  for (int r = 0; r < size; ++r) {
    const auto first = received.begin() + receive_at[static_cast<size_t>(r)];
    out[static_cast<size_t>(r)].assign(first, first + receive_counts[static_cast<size_t>(r)]);
  }
  return out;
}

std::vector<std::vector<double>> gather_to_root(MPI_Comm comm, const std::vector<double>& mine) {
  int size = 1, rank = 0;
  MPI_Comm_size(comm, &size);
  MPI_Comm_rank(comm, &rank);
  const int count = static_cast<int>(mine.size());
  std::vector<int> counts(rank == 0 ? static_cast<size_t>(size) : 0);
  check(MPI_Gather(&count, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm), "MPI_Gather");
  std::vector<int> at;
  std::vector<double> all;
  if (rank == 0) {
    at = displacements(counts);
    all.resize(static_cast<size_t>(at.back() + counts.back()));
  }
  check(MPI_Gatherv(mine.data(), count, MPI_DOUBLE, all.data(), counts.data(), at.data(),
                    MPI_DOUBLE, 0, comm),
        "MPI_Gatherv");
  std::vector<std::vector<double>> out;
  if (rank != 0) return out;
  out.resize(static_cast<size_t>(size));
  for (int r = 0; r < size; ++r) {
    const auto first = all.begin() + at[static_cast<size_t>(r)];
    out[static_cast<size_t>(r)].assign(first, first + counts[static_cast<size_t>(r)]);
  }
  return out;
}

}  // namespace tem::distributed
