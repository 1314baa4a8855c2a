// The force models behind one interface (forces/force_model.hpp): which model a scene gets, and
// their contact memory as records (forces/contact_memory.hpp), which the population stage
// renumbers, checkpoints save and MPI ranks send without knowing what a record holds.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "api/simulation_impl.hpp"
#include "forces/contact_forces.hpp"
#include "forces/force_model.hpp"
#include "io/checkpoint.hpp"
#include "io/scene_writer.hpp"
#include "support/coin_column.hpp"
#include "support/tem_process.hpp"
#include "tem/simulation.hpp"

namespace tem {
namespace test_force_models {

using testing_support::temp_path;

ContactDef contact(ContactModel model, ContactSolver solver = ContactSolver::rows) {
  ContactDef c;
  c.model = model;
  c.solver = solver;
  return c;
}

// What each model tells the rest of the step: the default-mode SEMM solvers are followed by the
// overlap correction, the penalty model's ranks compute their ghosts' contacts too, and over MPI
// only the rows solver and the penalty model run.
TEST(ForceModels, EachSceneGetsTheModelItNames) {
  const ForceModel& rows = force_model(contact(ContactModel::semm));
  const ForceModel& blocks = force_model(contact(ContactModel::semm, ContactSolver::blocks));
  const ForceModel& newton = force_model(contact(ContactModel::semm, ContactSolver::newton));
  const ForceModel& paper = force_model(contact(ContactModel::semm_paper));
  const ForceModel& penalty = force_model(contact(ContactModel::penalty));
  const ForceModel* all[] = {&rows, &blocks, &newton, &paper, &penalty};
  for (int i = 0; i < 5; ++i)
    for (int j = i + 1; j < 5; ++j) EXPECT_NE(all[i], all[j]);
  // The solver key means nothing to the paper's and the penalty model.
  EXPECT_EQ(&force_model(contact(ContactModel::penalty, ContactSolver::newton)), &penalty);
  EXPECT_EQ(&force_model(contact(ContactModel::semm_paper, ContactSolver::blocks)), &paper);

  for (const ForceModel* m : {&rows, &blocks, &newton}) EXPECT_TRUE(m->corrects_overlap());
  EXPECT_FALSE(paper.corrects_overlap());
  EXPECT_FALSE(penalty.corrects_overlap());
  for (const ForceModel* m : {&rows, &blocks, &newton, &paper}) EXPECT_TRUE(m->solves_across_ranks());
  EXPECT_FALSE(penalty.solves_across_ranks());
  EXPECT_TRUE(rows.not_distributed_because().empty());
  EXPECT_TRUE(penalty.not_distributed_because().empty());
  EXPECT_TRUE(testing_support::contains(blocks.not_distributed_because(), "'blocks'"));
  EXPECT_TRUE(testing_support::contains(newton.not_distributed_because(), R"("newton")"));
  EXPECT_TRUE(testing_support::contains(paper.not_distributed_because(), "'semm-paper'"));
}

// Records of bodies gone are dropped and the others renumbered, in their order: body 1 of
// three leaves.
TEST(ForceModels, RecordsOfBodiesGoneAreDroppedAndTheRestRenumbered) {
  std::vector<MemoryRecord> records = {
      {0, 1, -1, {1.0}}, {0, 2, -1, {2.0}}, {0, -1, 3, {3.0}}, {1, -1, 0, {4.0}}, {2, -1, 0, {5.0}}};
  renumber_records({0, -1, 1}, records);
  ASSERT_EQ(records.size(), 3u);
  EXPECT_EQ(records[0].body_a, 0);
  EXPECT_EQ(records[0].body_b, 1);
  EXPECT_EQ(records[0].values[0], 2.0);
  EXPECT_EQ(records[1].wall, 3);
  EXPECT_EQ(records[1].values[0], 3.0);
  EXPECT_EQ(records[2].body_a, 1);
  EXPECT_EQ(records[2].values[0], 5.0);
}

// Two columns of three coins (penalty: two coins) sliding at 1 cm/s and turning on the floor,
// for each model with a memory: stepped straight on, and resumed from a checkpoint that holds the model's records,
// the state is the same to the last bit. The memory matters: a coin's warm start, or its
// tangential spring, carries its friction from step to step.
class MemoryRecords : public testing::TestWithParam<std::pair<ContactModel, ContactSolver>> {};

TEST_P(MemoryRecords, ACheckpointCarriesTheMemoryBitForBit) {
  const auto [model, solver] = GetParam();
  const bool penalty = model == ContactModel::penalty;
  // Penalty: one coin a column (its face-on-face springs rock a column of coins apart).
  SceneDef scene = testing_support::coin_lattice(2, penalty ? 1 : 3, penalty ? 5e-5 : 5e-4);
  scene.contact.model = model;
  scene.contact.solver = solver;
  if (penalty) {
    scene.contact.stiffness = 1e5;
    scene.contact.damping = 30;  // about 0.6 of critical for a coin on the floor: it settles
  }
  for (BodyDef& coin : scene.bodies) {
    coin.velocity = Vec3(1, 0.3, 0);
    coin.angular_velocity = Vec3(0, 0, 2);
  }
  scene.duration = 1;
  const std::string file = temp_path("force_model_memory") + ".json";
  std::string error;
  ASSERT_TRUE(write_scene_file(scene, file, &error)) << error;
  const int steps = penalty ? 1000 : 100;

  Simulation straight = Simulation::load(file);
  straight.step(steps);
  // Memory there is: contacts between the coins and with the floor.
  std::vector<MemoryRecord> records;
  force_model(scene.contact).save_memory(straight.impl().workspace.forces, records);
  EXPECT_GE(records.size(), penalty ? 1u : 6u);
  const std::string checkpoint = temp_path("force_model_memory") + ".bin";
  straight.write_checkpoint(checkpoint);
  EXPECT_EQ(read_checkpoint(checkpoint).memory.size(), records.size());
  straight.step(steps);

  Simulation resumed = Simulation::resume(file, checkpoint);
  resumed.step(steps);
  EXPECT_EQ(resumed.state_hash(), straight.state_hash());
  std::filesystem::remove(file);
  std::filesystem::remove(checkpoint);
}

std::string model_name(const testing::TestParamInfo<std::pair<ContactModel, ContactSolver>>& info) {
  if (info.param.first == ContactModel::penalty) return "penalty";
  const ContactSolver solver = info.param.second;
  return solver == ContactSolver::rows ? "rows" : solver == ContactSolver::blocks ? "blocks" : "newton";
}

INSTANTIATE_TEST_SUITE_P(Models, MemoryRecords,
                         testing::Values(std::pair{ContactModel::semm, ContactSolver::rows},
                                         std::pair{ContactModel::semm, ContactSolver::blocks},
                                         std::pair{ContactModel::semm, ContactSolver::newton},
                                         std::pair{ContactModel::penalty, ContactSolver::rows}),
                         model_name);

// A checkpoint whose memory names a body the state does not have is refused on reading, before
// any model sees it.
TEST(ForceModels, ACheckpointsMemoryNamingNoBodyIsRefused) {
  Checkpoint c;
  c.state.bodies.resize(2);
  c.memory = {{0, 1, -1, {1.0, 2.0}}, {5, -1, 0, {}}};
  const std::string file = temp_path("force_model_bad_memory") + ".bin";
  write_checkpoint(file, c);
  try {
    read_checkpoint(file);
    ADD_FAILURE() << "read";
  } catch (const std::runtime_error& e) {
    EXPECT_TRUE(testing_support::contains(e.what(), "contact memory names a body"))
        << e.what();
  }
  c.memory.pop_back();
  write_checkpoint(file, c);
  const Checkpoint back = read_checkpoint(file);
  ASSERT_EQ(back.memory.size(), 1u);
  EXPECT_EQ(back.memory[0].body_b, 1);
  EXPECT_EQ(back.memory[0].values, (std::vector<double>{1.0, 2.0}));
  std::filesystem::remove(file);
}

}  // namespace test_force_models
}  // namespace tem
