// ParaView output (io/paraview_output.hpp): what tem.pvd lists as frames are written, resumed
// and replaced, and how it grows; the frame files decoded (support/vtu_reader.hpp) and compared
// bit for bit with the state they show. tests/paraview/check_paraview.py reads the same files
// with a real reader (meshio) and checks their geometry and fields.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "collision/block_pose.hpp"
#include "io/paraview_frames.hpp"
#include "io/paraview_output.hpp"
#include "io/scene_reader.hpp"
#include "io/vtu_binary.hpp"
#include "support/tem_process.hpp"
#include "support/vtu_reader.hpp"
#include "support/parallel.hpp"

namespace tem {
namespace test_paraview {

namespace fs = std::filesystem;
using testing_support::read_vtu;
using testing_support::slurp;
using testing_support::VtuArray;
using testing_support::VtuFile;

Model drop_model() {
  const SceneReadResult read =
      read_scene_file(std::string(TEM_SOURCE_DIR) + "/tests/scenes/paraview_drop.json");
  EXPECT_TRUE(read.ok());
  return build_model(read.scene);
}

struct Listed {
  std::string time, file;
};

// The DataSet entries of tem.pvd, in order.
std::vector<Listed> listed(const std::string& dir) {
  std::vector<Listed> out;
  std::istringstream text(slurp(dir + "/tem.pvd"));
  std::string line;
  auto value = [](const std::string& tag, const std::string& key) {
    const size_t start = tag.find(key + "=\"") + key.size() + 2;
    return tag.substr(start, tag.find('"', start) - start);
  };
  while (std::getline(text, line))
    if (line.find("<DataSet") != std::string::npos)
      out.push_back({value(line, "timestep"), value(line, "file")});
  return out;
}

// The steps tem.pvd lists, each checked to have its bodies file (part 0) then contacts file.
std::vector<long long> listed_steps(const std::string& dir) {
  const std::vector<Listed> entries = listed(dir);
  std::vector<long long> steps;
  EXPECT_EQ(entries.size() % 2, 0u);
  for (size_t i = 0; i + 1 < entries.size(); i += 2) {
    const std::string& bodies = entries[i].file;
    const long long step = std::stoll(bodies.substr(bodies.size() - 16, 12));
    EXPECT_EQ(bodies, ParaviewOutput::bodies_file(step));
    EXPECT_EQ(entries[i + 1].file, ParaviewOutput::contacts_file(step));
    EXPECT_EQ(entries[i].time, entries[i + 1].time);
    EXPECT_TRUE(fs::exists(dir + "/" + entries[i].file)) << entries[i].file;
    EXPECT_TRUE(fs::exists(dir + "/" + entries[i + 1].file)) << entries[i + 1].file;
    steps.push_back(step);
  }
  return steps;
}

class ParaviewOutputTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = ::testing::TempDir() + "tem_paraview_" + std::to_string(getpid()) + "_" +
           ::testing::UnitTest::GetInstance()->current_test_info()->name();
    fs::remove_all(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // Steps the scene from its start, writing a frame every 10 steps up to `last`.
  void run(ParaviewOutput& output, long long last) {
    State state = initial_state(model_);
    Workspace workspace;
    for (long long k = 0; k <= last; ++k) {
      find_contact_forces(model_, state, workspace);
      if (k % 10 == 0) output.write(model_, state, workspace);
      advance(model_, state, workspace);
    }
  }

  Model model_ = drop_model();
  std::string dir_;
};

TEST_F(ParaviewOutputTest, ListsEveryFrameInOrderAndLeavesNoTemporaryFile) {
  ParaviewOutput output(dir_, model_, std::nullopt);
  EXPECT_TRUE(listed_steps(dir_).empty());  // a valid, empty collection from the start
  run(output, 30);
  EXPECT_EQ(listed_steps(dir_), (std::vector<long long>{0, 10, 20, 30}));
  EXPECT_FALSE(fs::exists(dir_ + "/tem.pvd.tmp"));
  // Times written with every digit: step 10 at time_step 1e-4.
  EXPECT_DOUBLE_EQ(std::stod(listed(dir_)[2].time), 10 * 1e-4);
  EXPECT_EQ(listed(dir_)[0].time, "0");
}

TEST_F(ParaviewOutputTest, ResumeKeepsOnlyTheEarlierFrames) {
  {
    ParaviewOutput output(dir_, model_, std::nullopt);
    run(output, 30);
  }
  const std::string times_before = listed(dir_)[2].time;
  ParaviewOutput resumed(dir_, model_, 15);
  EXPECT_EQ(listed_steps(dir_), (std::vector<long long>{0, 10}));
  EXPECT_EQ(listed(dir_)[2].time, times_before);
  EXPECT_FALSE(fs::exists(dir_ + "/" + ParaviewOutput::bodies_file(20)));
  EXPECT_FALSE(fs::exists(dir_ + "/" + ParaviewOutput::contacts_file(30)));
  run(resumed, 20);  // writes 0 and 10 again, then 20
  EXPECT_EQ(listed_steps(dir_), (std::vector<long long>{0, 10, 20}));
}

TEST_F(ParaviewOutputTest, ANewCollectionDropsTheFramesOfAnEarlierRun) {
  {
    ParaviewOutput output(dir_, model_, std::nullopt);
    run(output, 20);
  }
  ParaviewOutput again(dir_, model_, std::nullopt);
  EXPECT_TRUE(listed_steps(dir_).empty());
  EXPECT_FALSE(fs::exists(dir_ + "/" + ParaviewOutput::bodies_file(0)));
}

TEST_F(ParaviewOutputTest, RewritingAnEarlierStepReplacesItAndDropsLaterFrames) {
  ParaviewOutput output(dir_, model_, std::nullopt);
  run(output, 30);
  State state = initial_state(model_);
  state.step = 10;
  Workspace workspace;
  find_contact_forces(model_, state, workspace);
  output.write(model_, state, workspace);
  EXPECT_EQ(listed_steps(dir_), (std::vector<long long>{0, 10}));
}

TEST_F(ParaviewOutputTest, ThrowsNamingADirectoryThatCannotBeMade) {
  fs::create_directories(dir_);
  std::ofstream(dir_ + "/file") << "not a directory";
  try {
    ParaviewOutput output(dir_ + "/file/out", model_, std::nullopt);
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(dir_ + "/file/out/paraview"), std::string::npos)
        << e.what();
  }
}

// A frame is written over the closing tags: tem.pvd stays the same file (not a new one renamed
// over it), keeps what it held before the closing tags byte for byte, and is a complete
// collection after every frame.
TEST_F(ParaviewOutputTest, AFrameIsWrittenInPlaceOverTheClosingTags) {
  const std::string pvd = dir_ + "/tem.pvd", tail = "</Collection>\n</VTKFile>\n";
  ParaviewOutput output(dir_, model_, std::nullopt);
  State state = initial_state(model_);
  Workspace workspace;
  for (size_t frame = 1; frame <= 3; ++frame) {
    struct stat before {};
    ASSERT_EQ(stat(pvd.c_str(), &before), 0);
    const std::string old = slurp(pvd);
    ASSERT_EQ(old.substr(old.size() - tail.size()), tail);
    for (int k = 0; k < 10; ++k) {
      find_contact_forces(model_, state, workspace);
      if (k == 0) output.write(model_, state, workspace);
      advance(model_, state, workspace);
    }
    struct stat after {};
    ASSERT_EQ(stat(pvd.c_str(), &after), 0);
    EXPECT_EQ(after.st_ino, before.st_ino) << "tem.pvd was replaced, not written in place";
    const std::string now = slurp(pvd);
    const size_t kept = old.size() - tail.size();
    EXPECT_EQ(now.substr(0, kept), old.substr(0, kept));
    EXPECT_EQ(now.substr(now.size() - tail.size()), tail);
    EXPECT_EQ(listed_steps(dir_).size(), frame);
  }
  EXPECT_EQ(listed_steps(dir_), (std::vector<long long>{0, 10, 20}));
}

// `tem run --resume` of a finished run extended to a longer duration (as in test_resume.cpp):
// it drops the frame of the checkpoint's step and writes it again, and ends with tem.pvd and
// every frame file byte for byte those of a run that went the whole way.
TEST(ParaviewResume, AResumedRunWritesTheFilesOfAnUninterruptedOne) {
  using testing_support::run_tem;
  using testing_support::temp_path;
  const std::string scene = std::string(TEM_SOURCE_DIR) + "/tests/scenes/paraview_drop.json";
  const std::string whole = temp_path("pv_whole"), resumed = temp_path("pv_resumed");
  const std::string short_scene = temp_path("pv_short.json");
  std::string text = slurp(scene);
  text.replace(text.find("\"duration\": 0.05"), 16, "\"duration\": 0.02");
  std::ofstream(short_scene) << text;
  ASSERT_EQ(run_tem("run '" + scene + "' --out '" + whole + "'").status, 0);
  ASSERT_EQ(run_tem("run '" + short_scene + "' --out '" + resumed + "'").status, 0);
  const auto run = run_tem("run '" + scene + "' --out '" + resumed + "' --resume");
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_TRUE(testing_support::contains(run.err, "resuming at step")) << run.err;

  EXPECT_TRUE(slurp(whole + "/tem.pvd") == slurp(resumed + "/tem.pvd")) << "tem.pvd differs";
  EXPECT_EQ(listed_steps(resumed).size(), 6u);
  std::vector<std::string> names;
  for (const fs::directory_entry& entry : fs::directory_iterator(whole + "/paraview"))
    names.push_back(entry.path().filename().string());
  EXPECT_EQ(names.size(), 12u);
  for (const std::string& name : names)
    EXPECT_TRUE(slurp(whole + "/paraview/" + name) == slurp(resumed + "/paraview/" + name))
        << name << " differs";
  EXPECT_EQ(std::distance(fs::directory_iterator(resumed + "/paraview"), fs::directory_iterator()),
            12);
  fs::remove_all(whole);
  fs::remove_all(resumed);
  fs::remove(short_scene);
}

// The bits of doubles, so that a comparison sees every last bit and tells -0 from 0.
std::vector<std::uint64_t> bits(const std::vector<Real>& values) {
  std::vector<std::uint64_t> out;
  for (Real v : values) out.push_back(std::bit_cast<std::uint64_t>(v));
  return out;
}

// Vectors as a file stores them: x, y, z one after another, -0 as 0 (vtu_binary.hpp).
std::vector<Real> flat(const std::vector<Vec3>& vectors) {
  std::vector<Real> out;
  for (const Vec3& v : vectors)
    for (int k = 0; k < 3; ++k) out.push_back(v[k] + 0.0);
  return out;
}

// Scalars as a file stores them: -0 as 0.
std::vector<Real> stored(std::vector<Real> values) {
  for (Real& v : values) v += 0.0;
  return values;
}

struct Declared {
  std::string name, section, type;
  int components;
};

// The file is a binary VTK UnstructuredGrid with exactly these arrays, in this order, each where
// and as the ASCII files had it, and the time `time` to the bit.
void expect_arrays(const VtuFile& file, const std::vector<Declared>& declared, Real time) {
  EXPECT_EQ(file.root.at("type"), "UnstructuredGrid");
  EXPECT_EQ(file.root.at("byte_order"), "LittleEndian");
  EXPECT_EQ(file.root.at("header_type"), "UInt64");
  EXPECT_EQ(file.root.at("compressor"), "vtkZLibDataCompressor");
  std::vector<std::string> names{"TimeValue"};
  for (const Declared& d : declared) names.push_back(d.name);
  ASSERT_EQ(file.names, names);
  const VtuArray& time_value = file.arrays.at("TimeValue");
  EXPECT_EQ(time_value.section, "FieldData");
  EXPECT_EQ(bits(time_value.values<Real>()), bits({time}));
  for (const Declared& d : declared) {
    const VtuArray& a = file.arrays.at(d.name);
    EXPECT_EQ(a.section, d.section) << d.name;
    EXPECT_EQ(a.type, d.type) << d.name;
    EXPECT_EQ(a.components, d.components) << d.name;
  }
}

// A state with the bodies moving, turned and touching: the drop scene after 300 steps.
State moving_state(const Model& model, Workspace& workspace) {
  State state = initial_state(model);
  for (int k = 0; k < 300; ++k) {
    find_contact_forces(model, state, workspace);
    advance(model, state, workspace);
  }
  find_contact_forces(model, state, workspace);
  return state;
}

// Every node of every block instance, every triangle, and the fields of docs/figures.md, as the
// state gives them, to the bit.
TEST(ParaviewFrames, BodiesFileHoldsTheStateBitForBit) {
  const Model model = drop_model();
  Workspace workspace;
  const State state = moving_state(model, workspace);
  std::vector<Vec3> points, velocities, angular_velocities;
  std::vector<std::int64_t> connectivity, offsets;
  std::vector<int> body_ids, block_ids;
  int block_id = 0;  // counts block instances over all bodies
  for (size_t b = 0; b < model.bodies.size(); ++b) {
    const BodyState& s = state.bodies[b];
    const Vec3 w = s.angular_velocity_world();
    ASSERT_GT(w.norm(), 0);
    for (const BlockInstance& instance : model.bodies[b].blocks) {
      const Block& block = model.blocks[instance.block];
      const auto first = static_cast<std::int64_t>(points.size());
      for (const Vec3& node : block.nodes()) {
        points.push_back(block_pose(instance, s).to_world(node));
        velocities.push_back(s.v + w.cross(points.back() - s.x));
        angular_velocities.push_back(w);
      }
      for (const Triangle& t : block.triangles()) {
        for (int k = 0; k < 3; ++k) connectivity.push_back(first + t.nodes[k]);
        offsets.push_back(static_cast<std::int64_t>(connectivity.size()));
        body_ids.push_back(static_cast<int>(b));
        block_ids.push_back(block_id);
      }
      ++block_id;
    }
  }

  const VtuFile file = read_vtu(bodies_vtu(model, state));
  EXPECT_EQ(file.points, static_cast<long long>(points.size()));
  EXPECT_EQ(file.cells, static_cast<long long>(body_ids.size()));
  expect_arrays(file,
                {{"velocity", "PointData", "Float64", 3},
                 {"angular_velocity", "PointData", "Float64", 3},
                 {"body_id", "CellData", "Int32", 1},
                 {"block_id", "CellData", "Int32", 1},
                 {"Points", "Points", "Float64", 3},
                 {"connectivity", "Cells", "Int64", 1},
                 {"offsets", "Cells", "Int64", 1},
                 {"types", "Cells", "UInt8", 1}},
                state.time);
  EXPECT_EQ(bits(file.arrays.at("Points").values<Real>()), bits(flat(points)));
  EXPECT_EQ(bits(file.arrays.at("velocity").values<Real>()), bits(flat(velocities)));
  EXPECT_EQ(bits(file.arrays.at("angular_velocity").values<Real>()),
            bits(flat(angular_velocities)));
  EXPECT_EQ(file.arrays.at("body_id").values<int>(), body_ids);
  EXPECT_EQ(file.arrays.at("block_id").values<int>(), block_ids);
  EXPECT_EQ(file.arrays.at("connectivity").values<std::int64_t>(), connectivity);
  EXPECT_EQ(file.arrays.at("offsets").values<std::int64_t>(), offsets);
  EXPECT_EQ(file.arrays.at("types").values<std::uint8_t>(),
            std::vector<std::uint8_t>(body_ids.size(), 5));  // VTK_TRIANGLE
}

// One vertex per patch at the patch point, and the patch's fields and forces, to the bit.
TEST(ParaviewFrames, ContactsFileHoldsThePatchesBitForBit) {
  const Model model = drop_model();
  Workspace workspace;
  const State state = moving_state(model, workspace);
  const std::vector<ContactPatch>& patches = workspace.patches;
  const std::vector<PatchForce>& forces = workspace.forces.patch_forces;
  ASSERT_GE(patches.size(), 2u);
  ASSERT_EQ(forces.size(), patches.size());
  std::vector<Vec3> points, normals, force;
  std::vector<Real> depth, fn, ft;
  std::vector<int> body_a, body_b, wall;
  std::vector<std::int64_t> indices, offsets;
  for (size_t i = 0; i < patches.size(); ++i) {
    points.push_back(patches[i].point);
    normals.push_back(patches[i].normal);
    force.push_back(forces[i].normal * patches[i].normal);
    depth.push_back(patches[i].depth);
    fn.push_back(forces[i].normal);
    ft.push_back(forces[i].tangential);
    body_a.push_back(patches[i].body_a);
    body_b.push_back(patches[i].body_b);
    wall.push_back(patches[i].wall);
    indices.push_back(static_cast<std::int64_t>(i));
    offsets.push_back(static_cast<std::int64_t>(i + 1));
  }
  ASSERT_GT(*std::max_element(fn.begin(), fn.end()), 0);

  const VtuFile file = read_vtu(contacts_vtu(state.time, patches, forces));
  EXPECT_EQ(file.points, static_cast<long long>(patches.size()));
  EXPECT_EQ(file.cells, static_cast<long long>(patches.size()));
  expect_arrays(file,
                {{"normal", "PointData", "Float64", 3},
                 {"depth", "PointData", "Float64", 1},
                 {"fn", "PointData", "Float64", 1},
                 {"ft", "PointData", "Float64", 1},
                 {"force", "PointData", "Float64", 3},
                 {"body_a", "PointData", "Int32", 1},
                 {"body_b", "PointData", "Int32", 1},
                 {"wall", "PointData", "Int32", 1},
                 {"Points", "Points", "Float64", 3},
                 {"connectivity", "Cells", "Int64", 1},
                 {"offsets", "Cells", "Int64", 1},
                 {"types", "Cells", "UInt8", 1}},
                state.time);
  EXPECT_EQ(bits(file.arrays.at("Points").values<Real>()), bits(flat(points)));
  EXPECT_EQ(bits(file.arrays.at("normal").values<Real>()), bits(flat(normals)));
  EXPECT_EQ(bits(file.arrays.at("force").values<Real>()), bits(flat(force)));
  EXPECT_EQ(bits(file.arrays.at("depth").values<Real>()), bits(stored(depth)));
  EXPECT_EQ(bits(file.arrays.at("fn").values<Real>()), bits(stored(fn)));
  EXPECT_EQ(bits(file.arrays.at("ft").values<Real>()), bits(stored(ft)));
  EXPECT_EQ(file.arrays.at("body_a").values<int>(), body_a);
  EXPECT_EQ(file.arrays.at("body_b").values<int>(), body_b);
  EXPECT_EQ(file.arrays.at("wall").values<int>(), wall);
  EXPECT_EQ(file.arrays.at("connectivity").values<std::int64_t>(), indices);
  EXPECT_EQ(file.arrays.at("offsets").values<std::int64_t>(), offsets);
  EXPECT_EQ(file.arrays.at("types").values<std::uint8_t>(),
            std::vector<std::uint8_t>(patches.size(), 1));  // VTK_VERTEX
}

TEST(ParaviewFrames, AFrameWithoutContactsIsAnEmptyValidFile) {
  const VtuFile file = read_vtu(contacts_vtu(0.5, {}, {}));
  EXPECT_EQ(file.points, 0);
  EXPECT_EQ(file.cells, 0);
  EXPECT_EQ(file.names.size(), 13u);
  EXPECT_EQ(bits(file.arrays.at("TimeValue").values<Real>()), bits({0.5}));
  for (const std::string& name : file.names) {
    if (name == "TimeValue") continue;
    const VtuArray& a = file.arrays.at(name);
    EXPECT_TRUE(a.bytes.empty()) << name;
    EXPECT_EQ(a.blocks, 0u) << name;  // VTK's header for no bytes: 0 blocks, last block 0
    EXPECT_EQ(a.last_block, 0u) << name;
  }
}

// An array of more than one block: full blocks of VTK's 32768 bytes, the last one partial and
// its size in the header; one of exactly one block (last block size 0: it is full); extreme
// doubles kept to the bit, -0 stored as 0; stored and compressed arrays both read back.
TEST(VtuBinary, LongArraysAreCutIntoVtkBlocksAndEveryDoubleKept) {
  const std::vector<Real> extremes = {-0.0,
                                      1.0 / 3,
                                      std::numeric_limits<Real>::denorm_min(),
                                      std::numeric_limits<Real>::min(),
                                      std::numeric_limits<Real>::max(),
                                      std::numeric_limits<Real>::lowest(),
                                      std::numeric_limits<Real>::infinity(),
                                      -std::numeric_limits<Real>::infinity(),
                                      std::nextafter(1.0, 2.0)};
  std::vector<Vec3> long_array(10000);
  for (size_t i = 0; i < long_array.size(); ++i)
    long_array[i] = Vec3(extremes[i % extremes.size()], std::sqrt(Real(i)), -Real(i));
  const std::vector<Real> one_block(4096, 0.1);
  const std::vector<int> ints = {-1, 0, 2147483647};
  std::vector<Real> noise(5000);
  std::mt19937_64 random(1);
  std::uniform_real_distribution<Real> uniform(1, 2);
  for (Real& v : noise) v = uniform(random);

  // Not a consistent mesh (arrays of several lengths): the blocks are what is tested here.
  VtuBinary vtu(0.25, long_array.size(), 0);
  vtu.begin_point_data();
  vtu.vectors("long", long_array);
  vtu.reals("one block", one_block);
  vtu.ints("ints", ints);
  vtu.reals("noise", noise);
  vtu.end_point_data();
  vtu.points(long_array);
  vtu.cells({}, 1, kVtkVertex);
  const VtuFile file = read_vtu(vtu.finish());

  const VtuArray& long_values = file.arrays.at("long");
  EXPECT_EQ(long_values.blocks, 8u);  // 240,000 bytes: 7 full blocks and 10,624 bytes
  EXPECT_EQ(long_values.block_size, 32768u);
  EXPECT_EQ(long_values.last_block, 240000u - 7 * 32768u);
  EXPECT_EQ(bits(long_values.values<Real>()), bits(flat(long_array)));
  EXPECT_EQ(std::bit_cast<std::uint64_t>(long_values.values<Real>()[0]), 0u);  // -0 as 0
  EXPECT_EQ(bits(file.arrays.at("Points").values<Real>()), bits(flat(long_array)));
  const VtuArray& one = file.arrays.at("one block");
  EXPECT_EQ(one.blocks, 1u);
  EXPECT_EQ(one.last_block, 0u);
  EXPECT_EQ(one.values<Real>(), one_block);
  EXPECT_EQ(file.arrays.at("ints").values<int>(), ints);
  EXPECT_EQ(file.arrays.at("ints").last_block, 12u);
  EXPECT_EQ(file.arrays.at("connectivity").blocks, 0u);
  // Doubles with random mantissas are stored (zlib level 0: a few bytes more than raw); a
  // repeated value is compressed.
  const VtuArray& noise_values = file.arrays.at("noise");
  EXPECT_EQ(noise_values.values<Real>(), noise);
  EXPECT_GE(noise_values.compressed, noise_values.bytes.size());
  EXPECT_LT(noise_values.compressed, noise_values.bytes.size() + 100 * noise_values.blocks);
  EXPECT_LT(one.compressed, one.bytes.size() / 10);
}

// Blocks are compressed side by side on the threads, and the bytes do not depend on how many.
TEST(VtuBinary, TheBytesAreTheSameOnAnyNumberOfThreads) {
  std::vector<Vec3> values(20000);
  for (size_t i = 0; i < values.size(); ++i) values[i] = Vec3(std::sin(Real(i)), Real(i), 1);
  auto file = [&] {
    VtuBinary vtu(1, values.size(), 0);
    vtu.begin_point_data();
    vtu.vectors("v", values);
    vtu.end_point_data();
    vtu.points(values);
    vtu.cells({}, 1, kVtkVertex);
    return vtu.finish();
  };
  set_threads(1);
  const std::string one = file();
  set_threads(2);
  const std::string two = file();
  set_threads(1);
  EXPECT_TRUE(one == two);
  EXPECT_EQ(read_vtu(one).arrays.at("v").blocks, 15u);
}

}  // namespace test_paraview
}  // namespace tem
