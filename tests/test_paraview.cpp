// ParaView output (io/paraview_output.hpp): what tem.pvd lists as frames are written, resumed
// and replaced, and the counts in the frame files. tests/paraview/check_paraview.py reads the
// same files with a real reader (meshio) and checks their geometry and fields.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "io/paraview_frames.hpp"
#include "io/paraview_output.hpp"
#include "io/scene_reader.hpp"

namespace tem {
namespace {

namespace fs = std::filesystem;

std::string slurp(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

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

// The counts a reader checks first: every node of every block instance, every triangle.
TEST(ParaviewFrames, BodiesFileHoldsEveryBlockInstancesNodesAndTriangles) {
  const Model model = drop_model();
  size_t nodes = 0, triangles = 0;
  for (const Body& body : model.bodies)
    for (const BlockInstance& instance : body.blocks) {
      nodes += model.blocks[instance.block].nodes().size();
      triangles += model.blocks[instance.block].triangles().size();
    }
  const std::string text = bodies_vtu(model, initial_state(model));
  EXPECT_NE(text.find("<Piece NumberOfPoints=\"" + std::to_string(nodes) +
                      "\" NumberOfCells=\"" + std::to_string(triangles) + "\">"),
            std::string::npos);
  EXPECT_NE(text.find("Name=\"velocity\""), std::string::npos);
  EXPECT_NE(text.find("Name=\"block_id\""), std::string::npos);
  EXPECT_EQ(text.substr(text.size() - 11), "</VTKFile>\n");
}

TEST(ParaviewFrames, AFrameWithoutContactsIsAnEmptyValidFile) {
  const std::string text = contacts_vtu(0.5, {}, {});
  EXPECT_NE(text.find("<Piece NumberOfPoints=\"0\" NumberOfCells=\"0\">"), std::string::npos);
  EXPECT_NE(text.find("Name=\"TimeValue\""), std::string::npos);
  EXPECT_NE(text.find("\n0.5\n"), std::string::npos);
}

}  // namespace
}  // namespace tem
