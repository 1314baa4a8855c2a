#include "io/checkpoint.hpp"

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <type_traits>

#include "io/scene_writer.hpp"
#include "mesh/mesh_body.hpp"
#include "support/fnv1a.hpp"

namespace tem {
namespace {

constexpr char kMagic[8] = {'T', 'E', 'M', 'C', 'K', 'P', 'T', '\n'};
// 2: the population of granular processes (body tags, inlets, sensors, driven work), the
// sizes of removed.csv and sensors.csv, and the rolling impulses of PatchFriction (roll1,
// roll2).
// 3: the sleep of bodies at rest (each body's rest_time, asleep, island), after the contact
// memory. Version 2 is still read: its bodies are awake, their rest timers at zero.
// 4: the pair cache's features (CachedFeatures), after the sleep. Versions 2 and 3 are still
// read, with an empty cache: the first resumed step searches every pair.
// 5: each cached feature's node past the rim (CachedFeatures::beyond_rim), after the features.
// Version 4 is still read, with none past the rim: such pairs are searched again.
// 6: the files the scene read and their content hashes (ReadFile), after the pair cache.
// Version 5 is still read, with no files to compare.
constexpr std::uint32_t kVersion = 7;
constexpr std::uint32_t kOldestVersion = 2;

// Appends values as their bytes: numbers, and vectors and matrices as their coefficients.
class Writer {
 public:
  template <class T>
  void value(const T& v) {
    static_assert(std::is_arithmetic_v<T> || std::is_enum_v<T>);
    raw(&v, sizeof v);
  }
  template <int R, int C>
  void value(const Eigen::Matrix<Real, R, C>& m) {
    raw(m.data(), sizeof(Real) * R * C);
  }
  std::string& bytes() { return bytes_; }

 private:
  void raw(const void* data, std::size_t size) {
    const char* p = static_cast<const char*>(data);
    bytes_.insert(bytes_.end(), p, p + size);
  }
  std::string bytes_;
};

// Reads them back, refusing to run past the end.
class Reader {
 public:
  Reader(const std::string& bytes, std::size_t end, const std::string& path)
      : bytes_(bytes), end_(end), path_(path) {}
  template <class T>
  void value(T& v) {
    if constexpr (std::is_arithmetic_v<T> || std::is_enum_v<T>) {
      take(&v, sizeof v);
    } else {
      take(v.data(), sizeof(Real) * v.size());
    }
  }
  template <class T>
  T value() {
    T v;
    value(v);
    return v;
  }
  // A count of records that each take at least `record_size` bytes.
  std::uint64_t count(std::size_t record_size) {
    const auto n = value<std::uint64_t>();
    if (n > (end_ - at_) / record_size) truncated();
    return n;
  }
  bool at_end() const { return at_ == end_; }
  std::string text(std::size_t size) {
    if (size > end_ - at_) truncated();
    std::string t(bytes_.data() + at_, size);
    at_ += size;
    return t;
  }

 private:
  void take(void* out, std::size_t size) {
    if (size > end_ - at_) truncated();
    std::memcpy(out, bytes_.data() + at_, size);
    at_ += size;
  }
  [[noreturn]] void truncated() const {
    throw std::runtime_error(path_ + ": the checkpoint is truncated");
  }
  const std::string& bytes_;
  std::size_t end_, at_ = sizeof kMagic;
  const std::string& path_;
};

// Every record is written field by field, the same order for writing and reading: `fields`
// takes a function that it calls on each field in turn.
template <class F, class B>
void fields(B& b, F&& f) {
  if constexpr (std::is_same_v<std::remove_const_t<B>, BodyState>) {
    f(b.x), f(b.v), f(b.g), f(b.omega), f(b.prev_torque), f(b.has_prev_torque);
  } else if constexpr (std::is_same_v<std::remove_const_t<B>, ContactPoint>) {
    f(b.patch), f(b.body_a), f(b.body_b), f(b.wall), f(b.point), f(b.normal), f(b.tangent1),
        f(b.tangent2), f(b.depth);
  } else if constexpr (std::is_same_v<std::remove_const_t<B>, PointImpulse>) {
    f(b.normal);
  } else if constexpr (std::is_same_v<std::remove_const_t<B>, PatchFriction>) {
    f(b.first), f(b.last), f(b.body_a), f(b.body_b), f(b.wall), f(b.centre), f(b.normal),
        f(b.tangent1), f(b.tangent2), f(b.start_slip), f(b.t1), f(b.t2), f(b.twist), f(b.roll1),
        f(b.roll2);
  } else if constexpr (std::is_same_v<std::remove_const_t<B>, BodyTag>) {
    f(b.id), f(b.inlet), f(b.copy), f(b.scale);
  } else if constexpr (std::is_same_v<std::remove_const_t<B>, InletProgress>) {
    f(b.placed), f(b.draws);
  } else if constexpr (std::is_same_v<std::remove_const_t<B>, SensorTotals>) {
    f(b.count), f(b.mass), f(b.force), f(b.torque), f(b.steps);
  } else if constexpr (std::is_same_v<std::remove_const_t<B>, CachedFeatures>) {
    f(b.body_a), f(b.block_a), f(b.body_b), f(b.block_b), f(b.feature), f(b.feature_a),
        f(b.feature_b), f(b.rotation), f(b.offset);
  } else {
    static_assert(std::is_same_v<std::remove_const_t<B>, PenaltySpring>);
    f(b.body_a), f(b.body_b), f(b.wall), f(b.point), f(b.stretch);
  }
}

template <class T>
void write_records(Writer& w, const std::vector<T>& records) {
  w.value(static_cast<std::uint64_t>(records.size()));
  for (const T& r : records) fields(r, [&](const auto& field) { w.value(field); });
}

template <class T>
std::vector<T> read_records(Reader& r) {
  std::vector<T> records(r.count(1));
  for (T& record : records) fields(record, [&](auto& field) { r.value(field); });
  return records;
}

}  // namespace

std::uint64_t scene_fingerprint(const SceneDef& scene) {
  // The duration and the checkpoint interval may change on resuming: a run can be extended.
  SceneDef kept = scene;
  kept.duration = 0;
  kept.output.checkpoint_interval = 0;
  const std::string text = write_scene_text(kept);
  return fnv1a(text.data(), text.size());
}

namespace {

void add_shape_files(const ShapeDef& shape, std::vector<ReadFile>& files) {
  for (const ShapeDef& part : shape.parts) add_shape_files(part, files);
  if (shape.type != ShapeType::mesh || !shape.mesh) return;
  for (const ReadFile& f : files)
    if (f.path == shape.mesh->file_path) return;
  files.push_back({shape.mesh->file_path, shape.mesh->content_hash});
}

}  // namespace

std::vector<ReadFile> scene_files(const SceneDef& scene) {
  std::vector<ReadFile> files;
  for (const BodyDef& b : scene.bodies) add_shape_files(b.shape, files);
  for (const FillDef& f : scene.fill) add_shape_files(f.body.shape, files);
  for (const InletDef& i : scene.inlets) add_shape_files(i.body.shape, files);
  return files;
}

void require_same_files(const std::vector<ReadFile>& taken, const std::vector<ReadFile>& now,
                        const std::string& checkpoint) {
  for (const ReadFile& t : taken) {
    const auto same_path = [&](const ReadFile& f) { return f.path == t.path; };
    const auto found = std::find_if(now.begin(), now.end(), same_path);
    if (found == now.end())
      throw std::runtime_error(checkpoint + " was taken of a scene that read " + t.path +
                               ", which the scene no longer reads");
    if (found->content_hash != t.content_hash)
      throw std::runtime_error(t.path + " has changed since " + checkpoint +
                               " was taken (its contents differ): the run cannot be resumed "
                               "with it; start the run again or restore the file");
  }
}

Checkpoint make_checkpoint(const SceneDef& scene, const State& state, const ContactForces& forces,
                           const std::vector<CachedFeatures>& features, const OutputSizes& sizes) {
  Checkpoint c;
  c.scene_fingerprint = scene_fingerprint(scene);
  c.files = scene_files(scene);
  c.sizes = sizes;
  c.state = state;
  force_model(scene.contact).save_memory(forces, c.memory);
  c.features = features;
  return c;
}

void restore_memory(const Checkpoint& checkpoint, const ContactDef& contact, ContactForces& forces,
                    std::vector<CachedFeatures>& features) {
  features = checkpoint.features;
  if (checkpoint.version != 0 && checkpoint.version < 7) {
    forces.points = checkpoint.points;
    forces.impulses = checkpoint.impulses;
    forces.friction = checkpoint.friction;
    forces.springs = checkpoint.springs;
    return;
  }
  force_model(contact).load_memory(checkpoint.memory, forces);
}

void write_checkpoint(const std::string& path, const Checkpoint& c) {
  Writer w;
  w.bytes().assign(kMagic, sizeof kMagic);
  w.value(kVersion);
  w.value(c.scene_fingerprint);
  w.value(c.sizes.bodies);
  w.value(c.sizes.energy);
  w.value(c.sizes.contacts);
  w.value(c.sizes.removed);
  w.value(c.sizes.sensors);
  w.value(c.state.time);
  w.value(c.state.step);
  write_records(w, c.state.bodies);
  write_records(w, c.state.tags);
  w.value(c.state.next_id);
  write_records(w, c.state.inlets);
  write_records(w, c.state.sensors);
  w.value(c.state.driven_work);
  // The memory as ContactForces held it before version 7: empty since (the records at the end).
  for (int array = 0; array < 4; ++array) w.value(std::uint64_t{0});
  w.value(static_cast<std::uint64_t>(c.state.bodies.size()));
  for (const BodyState& b : c.state.bodies) {
    w.value(b.rest_time);
    w.value(b.asleep);
    w.value(b.island);
  }
  write_records(w, c.features);
  w.value(static_cast<std::uint64_t>(c.features.size()));
  for (const CachedFeatures& e : c.features) w.value(e.beyond_rim);
  w.value(static_cast<std::uint64_t>(c.files.size()));
  for (const ReadFile& f : c.files) {
    w.value(static_cast<std::uint64_t>(f.path.size()));
    w.bytes().append(f.path);
    w.value(f.content_hash);
  }
  // The contact memory (version 7 on): per record its keys, then its numbers.
  w.value(static_cast<std::uint64_t>(c.memory.size()));
  for (const MemoryRecord& m : c.memory) {
    w.value(static_cast<std::int32_t>(m.body_a));
    w.value(static_cast<std::int32_t>(m.body_b));
    w.value(static_cast<std::int32_t>(m.wall));
    w.value(static_cast<std::uint64_t>(m.values.size()));
    w.bytes().append(reinterpret_cast<const char*>(m.values.data()),
                     m.values.size() * sizeof(double));
  }
  w.value(fnv1a(w.bytes().data(), w.bytes().size()));

  const std::string temporary = path + ".tmp";
  {
    std::ofstream file(temporary, std::ios::binary | std::ios::trunc);
    file.write(w.bytes().data(), static_cast<std::streamsize>(w.bytes().size()));
    file.flush();
    if (!file) throw std::runtime_error(temporary + ": the checkpoint cannot be written");
  }
  std::error_code error;
  std::filesystem::rename(temporary, path, error);
  if (error) throw std::runtime_error(path + ": cannot be replaced: " + error.message());
}

bool is_checkpoint_file(const std::string& path) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) return false;
  std::ifstream file(path, std::ios::binary);
  char magic[sizeof kMagic] = {};
  file.read(magic, sizeof magic);
  return file && std::memcmp(magic, kMagic, sizeof kMagic) == 0;
}

Checkpoint read_checkpoint(const std::string& path) {
  std::error_code error;
  if (std::filesystem::is_directory(path, error))
    throw std::runtime_error(path + ": is a folder, not a checkpoint file");
  std::ifstream file(path, std::ios::binary);
  if (!file) throw std::runtime_error(path + ": no checkpoint to resume from");
  const std::string bytes{std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
  if (bytes.size() < sizeof kMagic || std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0)
    throw std::runtime_error(path + ": not a TEM checkpoint");
  constexpr std::size_t kSum = sizeof(std::uint64_t);
  if (bytes.size() < sizeof kMagic + sizeof kVersion + kSum)
    throw std::runtime_error(path + ": the checkpoint is truncated");
  const std::size_t end = bytes.size() - kSum;
  std::uint64_t stored;
  std::memcpy(&stored, bytes.data() + end, kSum);
  // The checksum first: a damaged version number is damage, not another version.
  if (stored != fnv1a(bytes.data(), end))
    throw std::runtime_error(path + ": the checkpoint is corrupted (checksum mismatch)");
  Reader r(bytes, end, path);
  const auto version = r.value<std::uint32_t>();
  if (version < kOldestVersion || version > kVersion)
    throw std::runtime_error(path + ": checkpoint version " + std::to_string(version) +
                             ", this tem reads versions " + std::to_string(kOldestVersion) +
                             " to " + std::to_string(kVersion));

  Checkpoint c;
  c.scene_fingerprint = r.value<std::uint64_t>();
  c.sizes.bodies = r.value<std::int64_t>();
  c.sizes.energy = r.value<std::int64_t>();
  c.sizes.contacts = r.value<std::int64_t>();
  c.sizes.removed = r.value<std::int64_t>();
  c.sizes.sensors = r.value<std::int64_t>();
  c.state.time = r.value<Real>();
  c.state.step = r.value<long long>();
  c.state.bodies = read_records<BodyState>(r);
  c.state.tags = read_records<BodyTag>(r);
  c.state.next_id = r.value<long long>();
  c.state.inlets = read_records<InletProgress>(r);
  c.state.sensors = read_records<SensorTotals>(r);
  c.state.driven_work = r.value<Real>();
  c.version = version;
  c.points = read_records<ContactPoint>(r);
  c.impulses = read_records<PointImpulse>(r);
  c.friction = read_records<PatchFriction>(r);
  c.springs = read_records<PenaltySpring>(r);
  if (version >= 3) {
    if (r.count(sizeof(Real) + sizeof(bool) + sizeof(long long)) != c.state.bodies.size())
      throw std::runtime_error(path + ": the checkpoint's sleep records do not match its bodies");
    for (BodyState& b : c.state.bodies) {
      r.value(b.rest_time);
      r.value(b.asleep);
      r.value(b.island);
    }
  }
  if (version >= 4) {
    c.features = read_records<CachedFeatures>(r);
    for (const CachedFeatures& e : c.features)
      if (e.feature != ManifoldFeature::edges && e.feature != ManifoldFeature::face_of_a &&
          e.feature != ManifoldFeature::face_of_b)
        throw std::runtime_error(path + ": the checkpoint's pair cache holds an unknown feature");
  }
  if (version >= 5) {
    if (r.count(sizeof(Real)) != c.features.size())
      throw std::runtime_error(path + ": the checkpoint's pair cache records do not match");
    for (CachedFeatures& e : c.features) {
      r.value(e.beyond_rim);
      if (!(e.beyond_rim >= 0))
        throw std::runtime_error(path + ": the checkpoint's pair cache holds a negative depth");
    }
  }
  if (version >= 6) {
    c.files.resize(r.count(2 * sizeof(std::uint64_t)));
    for (ReadFile& f : c.files) {
      f.path = r.text(r.count(1));
      r.value(f.content_hash);
    }
  }
  if (version >= 7) {
    c.memory.resize(r.count(3 * sizeof(std::int32_t) + sizeof(std::uint64_t)));
    const auto bodies = static_cast<std::int64_t>(c.state.bodies.size());
    for (MemoryRecord& m : c.memory) {
      const auto a = r.value<std::int32_t>(), b = r.value<std::int32_t>(),
                 wall = r.value<std::int32_t>();
      if (a < 0 || a >= bodies || b < -1 || b >= bodies || wall < -1 || (b >= 0) == (wall >= 0))
        throw std::runtime_error(path + ": the checkpoint's contact memory names a body or "
                                 "wall that is not there");
      m.body_a = a;
      m.body_b = b;
      m.wall = wall;
      m.values.resize(r.count(sizeof(double)));
      r.value(m.values);
    }
  }
  if (!r.at_end()) throw std::runtime_error(path + ": the checkpoint has trailing bytes");
  return c;
}

}  // namespace tem
