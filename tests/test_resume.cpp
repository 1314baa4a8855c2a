// Long runs (interface.md): a run stopped by Ctrl-C, or killed outright, and resumed with
// `tem run --resume` gives the same bytes as a run that was never stopped; a finished run can be
// extended. The scene (tests/scenes/resume_pile.json) has three bodies that collide, slide and
// come to rest on the floor and on each other, so the contact solver's memory (warm start,
// friction) matters: a resume that lost it would differ in the last bits.
#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include "io/checkpoint.hpp"
#include "support/tem_process.hpp"

namespace tem {
namespace test_resume {

using testing_support::contains;
using testing_support::lines;
using testing_support::run_tem;
using testing_support::slurp;
using testing_support::temp_path;
using testing_support::TemProcess;
using testing_support::TemRun;

const std::string kScene = std::string(TEM_SOURCE_DIR) + "/tests/scenes/resume_pile.json";

std::string quoted(const std::string& s) { return "'" + s + "'"; }

// The reference: the scene run once without stopping.
struct Reference {
  std::string bodies, energy, contacts, hash;
};

const Reference& reference() {
  static const Reference ref = [] {
    const std::string dir = temp_path("resume_ref");
    const TemRun run =
        run_tem("run " + quoted(kScene) + " --out " + quoted(dir) + " --contacts --hash");
    EXPECT_EQ(run.status, 0) << run.err;
    Reference r{slurp(dir + "/bodies.csv"), slurp(dir + "/energy.csv"),
                slurp(dir + "/contacts.csv"), lines(run.out).empty() ? "" : lines(run.out).back()};
    std::filesystem::remove_all(dir);
    return r;
  }();
  return ref;
}

// Waits until the run has written rows up to at least `time` (energy.csv), or 60 s.
void wait_for_time(const std::string& dir, double time) {
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (std::chrono::steady_clock::now() < give_up) {
    const auto rows = lines(slurp(dir + "/energy.csv"));
    if (rows.size() > 1 && std::stod(rows.back().substr(0, rows.back().find(','))) >= time) return;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
}

void expect_same_as_reference(const std::string& dir, const TemRun& resumed) {
  const Reference& ref = reference();
  ASSERT_EQ(resumed.status, 0) << resumed.err;
  EXPECT_TRUE(contains(resumed.err, "resuming at step")) << resumed.err;
  EXPECT_EQ(lines(resumed.out).back(), ref.hash);
  EXPECT_TRUE(slurp(dir + "/bodies.csv") == ref.bodies) << "bodies.csv differs";
  EXPECT_TRUE(slurp(dir + "/energy.csv") == ref.energy) << "energy.csv differs";
  EXPECT_TRUE(slurp(dir + "/contacts.csv") == ref.contacts) << "contacts.csv differs";
}

TEST(Resume, ReferenceRunComesToRestWithContacts) {
  // What makes the test meaningful: the bodies touch (contact rows) for most of the run.
  const auto contact_rows = lines(reference().contacts);
  EXPECT_GT(contact_rows.size(), 150u);
  EXPECT_EQ(reference().hash.size(), 6u + 16u);
}

// Ctrl-C: the run stops where it is with a checkpoint of that very step and exit status 130;
// the files hold complete rows; --resume finishes it with the reference's bytes.
TEST(Resume, AfterCtrlCTheResultIsBitIdentical) {
  const std::string dir = temp_path("resume_int");
  std::filesystem::remove_all(dir);
  TemProcess process({"run", kScene, "--out", dir, "--contacts", "--hash"});
  ASSERT_TRUE(process.started());
  wait_for_time(dir, 0.15);
  process.signal(SIGINT);
  const TemRun stopped = process.wait();
  ASSERT_EQ(stopped.status, 130) << "the run ended before the signal: " << stopped.err;
  EXPECT_TRUE(contains(stopped.err, "--resume")) << stopped.err;
  const Checkpoint at = read_checkpoint(dir + "/checkpoint.bin");
  EXPECT_GE(at.state.time, 0.15);
  EXPECT_LT(at.state.time, 1.0);
  // Every line written so far is whole.
  const std::string energy = slurp(dir + "/energy.csv");
  ASSERT_FALSE(energy.empty());
  EXPECT_EQ(energy.back(), '\n');
  EXPECT_EQ(reference().energy.substr(0, energy.size()), energy);

  expect_same_as_reference(dir, run_tem("run " + quoted(kScene) + " --out " + quoted(dir) +
                                        " --contacts --hash --resume"));
  std::filesystem::remove_all(dir);
}

// A run killed without warning (SIGKILL, a power cut) resumes from its last periodic checkpoint
// (every 0.1 s of simulated time); the rows written after it are cut off and written again.
TEST(Resume, AfterAKillTheResultIsBitIdentical) {
  const std::string dir = temp_path("resume_kill");
  std::filesystem::remove_all(dir);
  TemProcess process({"run", kScene, "--out", dir, "--contacts", "--hash"});
  ASSERT_TRUE(process.started());
  wait_for_time(dir, 0.35);
  process.signal(SIGKILL);
  ASSERT_EQ(process.wait().status, 128 + SIGKILL);
  const Checkpoint at = read_checkpoint(dir + "/checkpoint.bin");
  EXPECT_GE(at.state.time, 0.3 - 1e-12);
  EXPECT_LT(at.state.time, 1.0);
  EXPECT_EQ(at.state.step % 1000, 0);

  expect_same_as_reference(dir, run_tem("run " + quoted(kScene) + " --out " + quoted(dir) +
                                        " --contacts --hash --resume"));
  std::filesystem::remove_all(dir);
}

// A run that finished at 0.4 s, resumed with the duration raised to 1 s, equals the 1 s run.
TEST(Resume, AFinishedRunCanBeExtended) {
  const std::string dir = temp_path("resume_ext");
  const std::string short_scene = temp_path("resume_short.json");
  std::string text = slurp(kScene);
  text.replace(text.find("\"duration\": 1.0"), 15, "\"duration\": 0.4");
  std::ofstream(short_scene) << text;
  ASSERT_EQ(run_tem("run " + quoted(short_scene) + " --out " + quoted(dir) + " --contacts").status,
            0);
  expect_same_as_reference(dir, run_tem("run " + quoted(kScene) + " --out " + quoted(dir) +
                                        " --contacts --hash --resume"));
  std::filesystem::remove_all(dir);
  std::filesystem::remove(short_scene);
}

// The same with contact.solver "newton": a run of 0.4 s resumed to 1 s equals the 1 s run
// (Newton keeps no memory between steps but the warm start the checkpoint holds).
TEST(Resume, NewtonSolverResumesBitIdentical) {
  std::string text = slurp(kScene);
  const std::string model = R"("model": "semm",)";
  text.replace(text.find(model), model.size(), model + R"( "solver": "newton",)");
  const std::string scene = temp_path("resume_newton.json");
  std::ofstream(scene) << text;
  const std::string whole = temp_path("resume_newton_whole");
  const TemRun reference_run =
      run_tem("run " + quoted(scene) + " --out " + quoted(whole) + " --hash");
  ASSERT_EQ(reference_run.status, 0) << reference_run.err;
  const std::string short_scene = temp_path("resume_newton_short.json");
  std::string short_text = text;
  short_text.replace(short_text.find("\"duration\": 1.0"), 15, "\"duration\": 0.4");
  std::ofstream(short_scene) << short_text;
  const std::string dir = temp_path("resume_newton_ext");
  ASSERT_EQ(run_tem("run " + quoted(short_scene) + " --out " + quoted(dir)).status, 0);
  const TemRun resumed =
      run_tem("run " + quoted(scene) + " --out " + quoted(dir) + " --hash --resume");
  ASSERT_EQ(resumed.status, 0) << resumed.err;
  EXPECT_EQ(lines(resumed.out).back(), lines(reference_run.out).back());
  EXPECT_TRUE(slurp(dir + "/bodies.csv") == slurp(whole + "/bodies.csv")) << "bodies.csv differs";
  for (const std::string& d : {whole, dir}) std::filesystem::remove_all(d);
  std::filesystem::remove(scene);
  std::filesystem::remove(short_scene);
}

// What resuming refuses, each with a message that says why.
TEST(Resume, RefusesWhatItCannotContinue) {
  const std::string dir = temp_path("resume_bad");
  std::filesystem::remove_all(dir);
  const TemRun none = run_tem("run " + quoted(kScene) + " --out " + quoted(dir) + " --resume");
  EXPECT_NE(none.status, 0);
  EXPECT_TRUE(contains(none.err, "no checkpoint to resume from")) << none.err;

  ASSERT_EQ(run_tem("run " + quoted(kScene) + " --out " + quoted(dir)).status, 0);
  // Another scene (here: other friction) in the same directory.
  const std::string other = temp_path("resume_other.json");
  std::string text = slurp(kScene);
  text.replace(text.find("\"friction\": 0.3"), 15, "\"friction\": 0.4");
  std::ofstream(other) << text;
  const TemRun wrong_scene =
      run_tem("run " + quoted(other) + " --out " + quoted(dir) + " --resume");
  EXPECT_NE(wrong_scene.status, 0);
  EXPECT_TRUE(contains(wrong_scene.err, "another scene")) << wrong_scene.err;
  // A checkpoint taken with the rows solver, the default of earlier builds, resumed with the
  // scene that names no solver (now Newton): refused, and the message says how to resume it.
  {
    const std::string rows_scene = temp_path("resume_rows.json");
    std::string rows_text = slurp(kScene);
    rows_text.replace(rows_text.find("\"model\": \"semm\""), 15,
                      "\"model\": \"semm\", \"solver\": \"rows\"");
    rows_text.replace(rows_text.find("\"duration\": 1.0"), 15, "\"duration\": 0.01");
    std::ofstream(rows_scene) << rows_text;
    const std::string rows_dir = temp_path("resume_rows");
    ASSERT_EQ(run_tem("run " + quoted(rows_scene) + " --out " + quoted(rows_dir)).status, 0);
    const TemRun by_default =
        run_tem("run " + quoted(kScene) + " --out " + quoted(rows_dir) + " --resume");
    EXPECT_NE(by_default.status, 0);
    EXPECT_TRUE(contains(by_default.err, R"(add "solver": "rows")")) << by_default.err;
    std::filesystem::remove_all(rows_dir);
    std::filesystem::remove(rows_scene);
  }
  // With --contacts when the run was started without.
  const TemRun flags =
      run_tem("run " + quoted(kScene) + " --out " + quoted(dir) + " --contacts --resume");
  EXPECT_NE(flags.status, 0);
  EXPECT_TRUE(contains(flags.err, "resume it the same way")) << flags.err;
  // A damaged checkpoint.
  {
    std::fstream file(dir + "/checkpoint.bin", std::ios::in | std::ios::out | std::ios::binary);
    file.seekp(40);
    file.put('\x7f');
  }
  const TemRun corrupted = run_tem("run " + quoted(kScene) + " --out " + quoted(dir) + " --resume");
  EXPECT_NE(corrupted.status, 0);
  EXPECT_TRUE(contains(corrupted.err, "corrupted")) << corrupted.err;
  // A byte flipped in the version number (right after the 8-byte magic) is damage too, not a
  // checkpoint of another version.
  ASSERT_EQ(run_tem("run " + quoted(kScene) + " --out " + quoted(dir)).status, 0);
  {
    std::fstream file(dir + "/checkpoint.bin", std::ios::in | std::ios::out | std::ios::binary);
    file.seekp(10);
    file.put('\x10');
  }
  const TemRun version = run_tem("run " + quoted(kScene) + " --out " + quoted(dir) + " --resume");
  EXPECT_NE(version.status, 0);
  EXPECT_TRUE(contains(version.err, "corrupted")) << version.err;
  EXPECT_FALSE(contains(version.err, "version")) << version.err;
  // checkpoint.bin a folder: the message names it.
  std::filesystem::remove(dir + "/checkpoint.bin");
  std::filesystem::create_directory(dir + "/checkpoint.bin");
  const TemRun folder = run_tem("run " + quoted(kScene) + " --out " + quoted(dir) + " --resume");
  EXPECT_NE(folder.status, 0);
  EXPECT_TRUE(contains(folder.err, "checkpoint.bin: is a folder")) << folder.err;
  std::filesystem::remove_all(dir);
  std::filesystem::remove(other);
}

// A mesh file changed between a run and its resume (same path, vertices scaled 1.5 times): the
// scene's text is the same, its bodies are not, so the resume is refused naming the file.
TEST(Resume, RefusesAMeshFileChangedSinceTheCheckpoint) {
  const std::string dir = temp_path("resume_mesh");
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir + "/out");
  const auto write_cube = [&](double h) {
    std::ofstream obj(dir + "/cube.obj");
    for (int i = 0; i < 8; ++i)
      obj << "v " << (i & 1 ? h : -h) << ' ' << (i & 2 ? h : -h) << ' ' << (i & 4 ? h : -h) << '\n';
    // Outward faces of the cube of corners 1..8 (bit 0: x, bit 1: y, bit 2: z).
    obj << "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n";
  };
  write_cube(0.5);
  std::ofstream(dir + "/scene.json") << R"({"time_step": 1e-3, "duration": 0.05,
    "walls": [{"point": [0, 0, 0], "normal": [0, 0, 1]}],
    "bodies": [{"name": "cube", "shape": {"type": "mesh", "file": "cube.obj"},
                "position": [0, 0, 0.6]}]})";
  const std::string run = "run " + quoted(dir + "/scene.json") + " --out " + quoted(dir + "/out");
  const TemRun first = run_tem(run);
  ASSERT_EQ(first.status, 0) << first.err;
  // Unchanged: the run resumes (and, finished, has nothing left to do).
  const TemRun same = run_tem(run + " --resume");
  EXPECT_EQ(same.status, 0) << same.err;
  write_cube(0.75);
  const TemRun changed = run_tem(run + " --resume");
  EXPECT_NE(changed.status, 0);
  EXPECT_TRUE(contains(changed.err, "cube.obj has changed since")) << changed.err;
  std::filesystem::remove_all(dir);
}

// Progress goes to a terminal only: with stderr in a file there is no carriage-return line.
TEST(Resume, NoProgressLineWhenNotATerminal) {
  const std::string dir = temp_path("resume_quiet");
  const TemRun run = run_tem("run " + quoted(kScene) + " --out " + quoted(dir));
  EXPECT_EQ(run.status, 0);
  EXPECT_FALSE(contains(run.err, "\r")) << run.err;
  std::filesystem::remove_all(dir);
}

}  // namespace test_resume
}  // namespace tem
