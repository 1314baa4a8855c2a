#include "distributed/domain.hpp"

#include <algorithm>
#include <chrono>
#include <limits>

#include "collision/broad_phase.hpp"
#include "contact/contact_margins.hpp"
#include "distributed/contact_memory.hpp"
#include "distributed/messages.hpp"

namespace tem::distributed {
namespace {

// A body's world bounds at `s`, every block's grown by `reach` (as the broad phase grows them).
Aabb body_bounds(const Model& model, int body, const BodyState& s, Real reach) {
  Aabb box = Aabb::empty();
  for (const BlockInstance& instance : model.bodies[body].blocks) {
    Aabb b = block_bounds(model.blocks[instance.block], block_pose(instance, s));
    b.min.array() -= reach;
    b.max.array() += reach;
    box.add(b);
  }
  return box;
}

// Where each body's contact memory (as body A) lies in `records`, in one process's order:
// [first, last) per body.
std::vector<std::pair<size_t, size_t>> memory_runs(const std::vector<MemoryRecord>& records,
                                                   size_t bodies) {
  std::vector<std::pair<size_t, size_t>> runs(bodies, {0, 0});
  for (size_t k = 0; k < records.size();) {
    size_t last = k;
    while (last < records.size() && records[last].body_a == records[k].body_a) ++last;
    runs[records[k].body_a] = {k, last};
    k = last;
  }
  return runs;
}

// A body as it travels: its index, its state and the memory of its contacts as body A (those
// of `records` in `run`; none for a SEMM body lent as a ghost).
void pack_body(Packer& out, int body, const BodyState& state,
               const std::vector<MemoryRecord>& records, std::pair<size_t, size_t> run) {
  out.put(body);
  out.put(state);
  out.put(static_cast<double>(run.second - run.first));
  for (size_t k = run.first; k < run.second; ++k) pack(out, records[k]);
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

Domain::Domain(MPI_Comm comm) : comm_(comm), partition_(comm) {
  MPI_Comm_rank(comm_, &rank_);
  MPI_Comm_size(comm_, &size_);
}

long long Domain::owned_count() const { return static_cast<long long>(owned_ids_.size()); }

void Domain::start(const Model& model, const State& state, Workspace& w) {
  const int n = static_cast<int>(model.bodies.size());
  // Zoltan balances the bodies each rank brings: a slice of the scene's order each, to start.
  std::vector<int> ids;
  std::vector<Vec3> centres;
  std::vector<double> costs;
  for (int b = static_cast<int>(static_cast<long long>(n) * rank_ / size_);
       b < static_cast<int>(static_cast<long long>(n) * (rank_ + 1) / size_); ++b) {
    ids.push_back(b);
    centres.push_back(state.bodies[b].x);
    costs.push_back(static_cast<double>(model.bodies[b].blocks.size()));
  }
  partition_.balance(ids, centres, costs);
  ++stats_.balancings;
  // Every rank holds the whole state here, so each finds every body's owner by the new cuts.
  w.subset.owned.assign(static_cast<size_t>(n), 0);
  owned_ids_.clear();
  for (int b = 0; b < n; ++b)
    if (partition_.owner_of(state.bodies[b].x) == rank_) {
      w.subset.owned[b] = 1;
      owned_ids_.push_back(b);
    }
  w.subset.resident = w.subset.owned;
  owner_.assign(static_cast<size_t>(n), -1);
  for (int b : owned_ids_) owner_[b] = rank_;
  solved_once_ = force_model(model.scene.contact).solves_across_ranks();
  w.subset.solved_once = solved_once_;
  if (solved_once_) {
    shared_ = std::make_unique<SharedSolve>(comm_, w.subset, owner_);
    w.sync = shared_.get();
  }
  keep_owned_memory(model, w);
}

void Domain::keep_owned_memory(const Model& model, Workspace& w) const {
  // The memory of the contacts of bodies this rank no longer owns: the copies it evaluated for
  // another rank (the penalty model), or after a start from a checkpoint every rank read.
  const ForceModel& force = force_model(model.scene.contact);
  std::vector<MemoryRecord> records;
  force.save_memory(w.forces, records);
  const size_t before = records.size();
  std::erase_if(records, [&](const MemoryRecord& r) { return !w.subset.owned[r.body_a]; });
  if (records.size() == before) return;
  sort_records(records);
  force.load_memory(records, w.forces);
}

void Domain::balance_if_needed(const Model& model, State& state, Workspace& w) {
  if (++steps_since_balance_ < balance_every) return;
  steps_since_balance_ = 0;
  std::vector<double> costs(owned_ids_.size());
  std::vector<int> index(model.bodies.size(), -1);
  for (size_t i = 0; i < owned_ids_.size(); ++i) {
    index[owned_ids_[i]] = static_cast<int>(i);
    costs[i] = static_cast<double>(model.bodies[owned_ids_[i]].blocks.size());
  }
  for (const ContactPatch& p : w.patches)
    for (int body : {p.body_a, p.body_b})
      if (body >= 0 && index[body] >= 0) costs[index[body]] += 2;
  double mine = 0;
  for (double c : costs) mine += c;
  double most = 0, total = 0;
  MPI_Allreduce(&mine, &most, 1, MPI_DOUBLE, MPI_MAX, comm_);
  MPI_Allreduce(&mine, &total, 1, MPI_DOUBLE, MPI_SUM, comm_);
  if (total <= 0 || most / (total / size_) <= balance_tolerance) return;
  std::vector<Vec3> centres;
  for (int b : owned_ids_) centres.push_back(state.bodies[b].x);
  partition_.balance(owned_ids_, centres, costs);
  ++stats_.balancings;
}

void Domain::exchange(const Model& model, State& state, Workspace& w) {
  const auto start = std::chrono::steady_clock::now();
  keep_owned_memory(model, w);  // the copies of contacts this rank evaluated for another go
  migrate(model, state, w);
  borders(model, state, w);
  stats_.seconds += seconds_since(start);
}

void Domain::migrate(const Model& model, State& state, Workspace& w) {
  const ForceModel& force = force_model(model.scene.contact);
  std::vector<std::vector<double>> send(static_cast<size_t>(size_));
  std::vector<char> leaving(model.bodies.size(), 0);
  std::vector<int> kept;
  std::vector<MemoryRecord> records;
  force.save_memory(w.forces, records);
  sort_records(records);  // each body's records as one run
  const auto runs = memory_runs(records, model.bodies.size());
  for (int b : owned_ids_) {
    const int to = partition_.owner_of(state.bodies[b].x);
    if (to == rank_) {
      kept.push_back(b);
      continue;
    }
    Packer out(send[static_cast<size_t>(to)]);
    pack_body(out, b, state.bodies[b], records, runs[b]);
    leaving[b] = 1;
    w.subset.owned[b] = 0;
    owner_[b] = to;
  }
  std::erase_if(records, [&](const MemoryRecord& r) { return leaving[r.body_a] != 0; });
  arrived_.clear();
  for (const auto& [b, from] : deliver(send, state)) {
    w.subset.owned[b] = 1;
    owner_[b] = rank_;
    kept.push_back(b);
    ++stats_.migrated;
  }
  for (MemoryRecord& r : arrived_) records.push_back(std::move(r));
  arrived_.clear();
  sort_records(records);
  force.load_memory(records, w.forces);
  std::sort(kept.begin(), kept.end());
  owned_ids_ = std::move(kept);
}

std::vector<std::pair<int, int>> Domain::deliver(const std::vector<std::vector<double>>& send,
                                                 State& state) {
  for (const std::vector<double>& message : send)
    if (!message.empty()) {
      stats_.bytes_sent += static_cast<long long>(message.size() * sizeof(double));
      ++stats_.messages_sent;
    }
  const std::vector<std::vector<double>> received = exchange_with_all(comm_, send);
  std::vector<std::pair<int, int>> bodies;
  for (int r = 0; r < size_; ++r) {
    Unpacker in(received[static_cast<size_t>(r)]);
    while (!in.done()) {
      const int b = in.integer();
      state.bodies[b] = in.body_state();
      const int records = in.integer();
      for (int k = 0; k < records; ++k) arrived_.push_back(unpack_memory_record(in));
      bodies.push_back({b, r});
    }
  }
  return bodies;
}

void Domain::borders(const Model& model, State& state, Workspace& w) {
  w.subset.resident = w.subset.owned;
  contact_reaches(model, state, reach_, nullptr, &w.subset);
  // Each owned body's reach box, and this rank's: their union.
  std::vector<Aabb> bounds(owned_ids_.size());
  Aabb mine = Aabb::empty();
  for (size_t i = 0; i < owned_ids_.size(); ++i) {
    const int b = owned_ids_[i];
    bounds[i] = body_bounds(model, b, state.bodies[b], reach_.empty() ? 0 : reach_[b]);
    mine.add(bounds[i]);
  }
  std::vector<double> boxes(static_cast<size_t>(6 * size_));
  const double my_box[6] = {mine.min.x(), mine.min.y(), mine.min.z(),
                            mine.max.x(), mine.max.y(), mine.max.z()};
  MPI_Allgather(my_box, 6, MPI_DOUBLE, boxes.data(), 6, MPI_DOUBLE, comm_);
  // Neighbours: the ranks whose box meets this one's.
  std::vector<std::pair<int, Aabb>> neighbours;
  for (int r = 0; r < size_; ++r) {
    if (r == rank_) continue;
    const double* q = &boxes[static_cast<size_t>(6 * r)];
    const Aabb box{Vec3(q[0], q[1], q[2]), Vec3(q[3], q[4], q[5])};
    if (box.overlaps(mine)) neighbours.push_back({r, box});
  }
  std::vector<std::vector<double>> send(static_cast<size_t>(size_));
  // A model whose ranks find the forces of their own bodies' contacts (the penalty model) finds
  // those with the ghosts too: the ghosts bring their memory.
  const ForceModel& force = force_model(model.scene.contact);
  std::vector<MemoryRecord> records;
  if (!solved_once_) force.save_memory(w.forces, records);
  const auto runs = memory_runs(records, model.bodies.size());
  for (size_t i = 0; i < owned_ids_.size(); ++i) {
    const int b = owned_ids_[i];
    for (const auto& [r, box] : neighbours) {
      if (!bounds[i].overlaps(box)) continue;
      Packer out(send[static_cast<size_t>(r)]);
      pack_body(out, b, state.bodies[b], records, runs[b]);
    }
  }
  ghost_ids_.clear();
  arrived_.clear();
  for (const auto& [b, from] : deliver(send, state)) {
    w.subset.resident[b] = 1;
    owner_[b] = from;
    ghost_ids_.push_back(b);
    ++stats_.ghosts;
  }
  if (arrived_.empty()) return;
  for (MemoryRecord& r : arrived_) records.push_back(std::move(r));
  arrived_.clear();
  sort_records(records);
  force.load_memory(records, w.forces);
}

void Domain::return_ghost_forces(Workspace& w) {
  if (!solved_once_) return;
  const auto start = std::chrono::steady_clock::now();
  std::vector<std::vector<double>> send(static_cast<size_t>(size_));
  ContactForces& f = w.forces;
  for (int b : ghost_ids_) {
    if (f.force[b].isZero(0) && f.torque[b].isZero(0)) continue;
    Packer out(send[static_cast<size_t>(owner_[b])]);
    out.put(b);
    out.put(f.force[b]);
    out.put(f.torque[b]);
  }
  for (const std::vector<double>& message : send)
    stats_.bytes_sent += static_cast<long long>(message.size() * sizeof(double));
  const std::vector<std::vector<double>> received = exchange_with_all(comm_, send);
  for (const std::vector<double>& message : received) {  // in rank order
    Unpacker in(message);
    while (!in.done()) {
      const int b = in.integer();
      f.force[b] += in.vec3();
      f.torque[b] += in.vec3();
    }
  }
  stats_.seconds += seconds_since(start);
}

void Domain::gather_state(const Model& model, const State& state, State& whole) const {
  std::vector<double> mine;
  Packer out(mine);
  for (int b : owned_ids_) {
    out.put(b);
    out.put(state.bodies[b]);
  }
  const std::vector<std::vector<double>> all = gather_to_root(comm_, mine);
  if (rank_ != 0) return;
  whole.time = state.time;
  whole.step = state.step;
  whole.bodies.resize(model.bodies.size());
  for (const std::vector<double>& part : all) {
    Unpacker in(part);
    while (!in.done()) {
      const int b = in.integer();
      whole.bodies[b] = in.body_state();
    }
  }
}

void Domain::gather_contacts(const Workspace& w, std::vector<ContactPatch>& patches,
                             std::vector<PatchForce>& forces) const {
  std::vector<double> mine;
  Packer out(mine);
  for (size_t k = 0; k < w.patches.size(); ++k) {
    const ContactPatch& p = w.patches[k];
    if (!w.subset.owned[p.body_a]) continue;
    out.put(p.body_a);
    out.put(p.body_b);
    out.put(p.wall);
    out.put(p.point);
    out.put(p.normal);
    out.put(p.depth);
    out.put(w.forces.patch_forces[k].normal);
    out.put(w.forces.patch_forces[k].tangential);
  }
  const std::vector<std::vector<double>> all = gather_to_root(comm_, mine);
  patches.clear();
  forces.clear();
  if (rank_ != 0) return;
  std::vector<std::pair<ContactPatch, PatchForce>> gathered;
  for (const std::vector<double>& part : all) {
    Unpacker in(part);
    while (!in.done()) {
      ContactPatch p;
      p.body_a = in.integer();
      p.body_b = in.integer();
      p.wall = in.integer();
      p.point = in.vec3();
      p.normal = in.vec3();
      p.depth = in.number();
      PatchForce f;
      f.normal = in.number();
      f.tangential = in.number();
      gathered.push_back({std::move(p), f});
    }
  }
  // One process's order: entries with the same key come from one rank (the owner of body A)
  // in that rank's order, so a stable sort on the key restores it.
  std::stable_sort(gathered.begin(), gathered.end(), [](const auto& x, const auto& y) {
    return pair_key(x.first) < pair_key(y.first);
  });
  for (auto& [p, f] : gathered) {
    patches.push_back(std::move(p));
    forces.push_back(f);
  }
}

void Domain::gather_memory(const Model& model, const ContactForces& forces,
                           ContactForces& whole) const {
  std::vector<double> mine;
  Packer out(mine);
  // Called where a step begins, before exchange(): the memory of the last step's contacts of
  // this rank's bodies as body A (not the copies it evaluated for other ranks).
  const ForceModel& force = force_model(model.scene.contact);
  std::vector<MemoryRecord> records;
  force.save_memory(forces, records);
  for (const MemoryRecord& r : records)
    if (std::binary_search(owned_ids_.begin(), owned_ids_.end(), r.body_a)) pack(out, r);
  const std::vector<std::vector<double>> all = gather_to_root(comm_, mine);
  whole = ContactForces{};
  if (rank_ != 0) return;
  records.clear();
  for (const std::vector<double>& part : all) {
    Unpacker in(part);
    while (!in.done()) records.push_back(unpack_memory_record(in));
  }
  sort_records(records);
  force.load_memory(records, whole);
}

int Domain::first_non_finite_body(const State& state) const {
  int mine = std::numeric_limits<int>::max();
  for (int b : owned_ids_) {
    const BodyState& s = state.bodies[b];
    if (!s.x.allFinite() || !s.v.allFinite() || !s.g.allFinite() || !s.omega.allFinite()) {
      mine = b;
      break;
    }
  }
  int first = 0;
  MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, comm_);
  return first == std::numeric_limits<int>::max() ? -1 : first;
}

}  // namespace tem::distributed
