#include "peer_run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <stdexcept>
#include <vector>

#include "io/run_output.hpp"
#include "io/scene_reader.hpp"
#include "io/scene_writer.hpp"
#include "simulation/step.hpp"
#include "tem_measures.hpp"

namespace tem::peers {
namespace {

struct Options {
  std::string scene;
  long long steps = -1;   // -1: from the duration
  double duration = -1;   // -1: the scene's
  double dt = -1;         // -1: the scene's
  long long report_every = 0;
  double friction = -1;     // -1: the scene's
  double restitution = -1;  // -1: the scene's
  bool sleeping = true;
  bool print_final = false;  // final centre of mass of every body, on stderr
  std::string final_run;     // folder for the last poses as a run's files; empty: none
  std::string samples;       // CSV of the pour rules' measures; empty: none
  double sample_every = 0.01;
  double rest_speed = 0.1;
  double rest_window = 0.1;
  double creep_window = 0.5;
};

[[noreturn]] void usage(const PeerEngine& engine, const std::string& why) {
  const std::string program = "tem_" + engine.name;
  std::cerr << program << ": " << why << "\n"
            << "usage: " << program
            << " SCENE.json [--steps N | --duration S] [--dt DT] [--report-every K] "
               "[--friction MU] [--restitution E] [--no-sleep] [--print-final] [--final-run DIR] "
               "[--samples FILE] [--sample-every S] [--rest-speed V] [--rest-window W] "
               "[--creep-window W]"
            << (engine.extra_usage.empty() ? "" : " ") << engine.extra_usage << "\n";
  std::exit(2);
}

double number(const PeerEngine& engine, const std::string& flag, const char* text) {
  char* end = nullptr;
  const double v = std::strtod(text, &end);
  if (end == text || *end != '\0' || !std::isfinite(v) || v < 0)
    usage(engine, flag + " needs a non-negative number, got '" + text + "'");
  return v;
}

Options parse(int argc, char** argv, const PeerEngine& engine) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> double {
      if (i + 1 >= argc) usage(engine, a + " needs a value");
      return number(engine, a, argv[++i]);
    };
    if (a == "--steps") o.steps = std::llround(value());
    else if (a == "--duration") o.duration = value();
    else if (a == "--dt") o.dt = value();
    else if (a == "--report-every") o.report_every = std::llround(value());
    else if (a == "--friction") o.friction = value();
    else if (a == "--restitution") o.restitution = value();
    else if (a == "--no-sleep") o.sleeping = false;
    else if (a == "--print-final") o.print_final = true;
    else if (a == "--final-run") {
      if (i + 1 >= argc) usage(engine, a + " needs a folder");
      o.final_run = argv[++i];
    } else if (a == "--samples") {
      if (i + 1 >= argc) usage(engine, a + " needs a file name");
      o.samples = argv[++i];
    } else if (a == "--sample-every") o.sample_every = value();
    else if (a == "--rest-speed") o.rest_speed = value();
    else if (a == "--rest-window") o.rest_window = value();
    else if (a == "--creep-window") o.creep_window = value();
    else if (a == "-h" || a == "--help") usage(engine, "help");
    else if (!a.empty() && a[0] == '-') {
      if (!engine.option || !engine.option(a, value)) usage(engine, "unknown option " + a);
    } else if (o.scene.empty()) o.scene = a;
    else usage(engine, "more than one scene given");
  }
  if (o.scene.empty()) usage(engine, "no scene given");
  if (o.steps >= 0 && o.duration >= 0) usage(engine, "--steps and --duration exclude each other");
  if (o.dt == 0) usage(engine, "--dt must be positive");
  if (o.sample_every == 0) usage(engine, "--sample-every must be positive");
  return o;
}

// The pour rules' measures of one state, as a row of the samples file; the window figures of
// the summary gathered on the way.
class Sampler {
 public:
  Sampler(const Model& model, const std::string& file, double end_time, const Options& o)
      : model_(model), out_(file), end_time_(end_time), options_(o),
        moving_(model.bodies.size(), 0) {
    if (!out_) throw std::runtime_error(file + ": cannot be written");
    out_ << "time,outside,max_depth,kinetic,potential,total,max_point_speed\n";
    for (int i = 0; i < static_cast<int>(model.bodies.size()); ++i)
      sizes_.push_back(body_size(model, i));
  }

  // Returns the deepest overlap, for the summary's worst over the run.
  Real sample(double time, const State& s, ContactWorkspace& workspace) {
    const Overlap o = measure_overlap(model_, s, workspace);
    const Energies e = system_energies(model_, s);
    // A little slack so that the sample at exactly end - window counts despite round-off.
    const double slack = 1e-9 * std::max(1.0, end_time_);
    const bool in_rest_window = time >= end_time_ - options_.rest_window - slack;
    const bool in_creep_window = time >= end_time_ - options_.creep_window - slack;
    Real fastest = 0;
    for (size_t i = 0; i < s.bodies.size(); ++i) {
      if (model_.bodies[i].driven()) continue;
      const BodyState& b = s.bodies[i];
      const Real speed = b.v.norm() + b.omega.norm() * sizes_[i];  // |omega| is frame-free
      fastest = std::max(fastest, speed);
      if (in_rest_window && speed >= options_.rest_speed) moving_[i] = 1;
    }
    if (in_creep_window) creep_ = std::max(creep_, fastest);
    char row[256];
    std::snprintf(row, sizeof row, "%.9g,%d,%.9g,%.17g,%.17g,%.17g,%.9g\n", time,
                  bodies_outside(model_, s), o.worst, e.kinetic, e.potential, e.total(), fastest);
    out_ << row;
    return o.worst;
  }

  long long moving_last() const {
    return std::count(moving_.begin(), moving_.end(), char(1));
  }
  Real creep() const { return creep_; }

 private:
  const Model& model_;
  std::ofstream out_;
  double end_time_;
  const Options& options_;
  std::vector<Real> sizes_;
  std::vector<char> moving_;
  Real creep_ = 0;
};

// The last poses as the files of a `tem run` that tools/settled_pile.py reads: scene.json (the
// scene as read) and bodies.csv with one row a body, so that a pile the engine made can be
// started in TEM.
void write_final_run(const std::string& folder, const SceneDef& scene, const Model& model,
                     const State& state) {
  std::error_code error;
  std::filesystem::create_directories(folder, error);
  if (error) throw std::runtime_error(folder + ": cannot be created: " + error.message());
  std::string message;
  if (!write_scene_file(scene, folder + "/scene.json", &message))
    throw std::runtime_error(message);
  std::string rows = std::string(kBodiesHeader) + "\n";
  append_body_rows(rows, model, state);
  std::ofstream bodies(folder + "/bodies.csv");
  bodies << rows;
  if (!bodies.flush()) throw std::runtime_error(folder + "/bodies.csv: cannot be written");
}

}  // namespace

int run_peer(int argc, char** argv, PeerEngine& engine) {
  const Options opt = parse(argc, argv, engine);
  const std::string program = "tem_" + engine.name;

  SceneReadResult read = read_scene_file(opt.scene);
  if (!read.ok()) {
    for (const SceneProblem& p : read.problems)
      std::cerr << format_problem(opt.scene, p) << "\n";
    return 2;
  }
  SceneDef& scene = read.scene;
  if (opt.dt > 0) scene.time_step = opt.dt;
  const double dt = scene.time_step;
  const long long steps =
      opt.steps >= 0 ? opt.steps
                     : std::llround((opt.duration >= 0 ? opt.duration : scene.duration) / dt);

  try {
    const Model model = build_model(scene);
    const State initial = initial_state(model);
    const Real smallest = smallest_body_size(model);

    PeerSetup setup;
    setup.friction = opt.friction;
    setup.restitution = opt.restitution;
    setup.sleeping = opt.sleeping;
    std::unique_ptr<PeerWorld> world = engine.make(model, initial, setup);

    ContactWorkspace workspace;
    std::unique_ptr<Sampler> sampler;
    const long long sample_stride = std::max(1LL, std::llround(opt.sample_every / dt));
    if (!opt.samples.empty()) {
      sampler = std::make_unique<Sampler>(model, opt.samples, steps * dt, opt);
      sampler->sample(0, world->state(), workspace);
    }

    // Only the steps are timed; TEM's measurements in between are not.
    Real worst_run = 0;
    double wall = 0;
    auto next_multiple = [](long long k, long long stride) { return (k / stride + 1) * stride; };
    for (long long k = 0; k < steps;) {
      long long stop = steps;
      if (opt.report_every > 0) stop = std::min(stop, next_multiple(k, opt.report_every));
      if (sampler) stop = std::min(stop, next_multiple(k, sample_stride));
      const auto start = std::chrono::steady_clock::now();
      for (; k < stop; ++k) world->step(dt);
      wall += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      const bool report = opt.report_every > 0 && k % opt.report_every == 0 && k < steps;
      const bool sample = sampler && (k % sample_stride == 0 || k == steps);
      if (!report && !sample) continue;
      const State s = world->state();
      if (sample) worst_run = std::max(worst_run, sampler->sample(k * dt, s, workspace));
      if (report) {
        const Overlap o = measure_overlap(model, s, workspace);
        worst_run = std::max(worst_run, o.worst);
        std::fprintf(stderr, "%s: step %lld t=%.6g outside=%d worst_overlap=%.4g\n",
                     program.c_str(), k, k * dt, bodies_outside(model, s), o.worst);
      }
    }

    State final_state = world->state();
    final_state.time = static_cast<Real>(steps) * dt;
    if (!opt.final_run.empty()) write_final_run(opt.final_run, scene, model, final_state);
    const Overlap o = measure_overlap(model, final_state, workspace);
    if (opt.print_final)
      for (size_t i = 0; i < model.bodies.size(); ++i) {
        const BodyState& b = final_state.bodies[i];
        const Vec3 up = b.g.transpose() * Vec3::UnitZ();  // world z in body axes
        std::fprintf(stderr, "%s: final %s x=%.6g y=%.6g z=%.6g up_body=(%.4f %.4f %.4f)\n",
                     program.c_str(), model.bodies[i].name.c_str(), b.x.x(), b.x.y(), b.x.z(),
                     up.x(), up.y(), up.z());
      }
    worst_run = std::max(worst_run, o.worst);
    const double per_step = steps > 0 ? wall / static_cast<double>(steps) : 0;
    std::printf(
        "engine=%s scene=%s bodies=%zu steps=%lld dt=%.9g us_per_step=%.4g "
        "body_steps_per_s=%.4g outside=%d worst_overlap=%.4g worst_overlap_rel=%.4g "
        "worst_overlap_bodies=%.4g worst_overlap_run=%.4g patches=%d sleeping=%d "
        "min_body_size=%.6g",
        engine.name.c_str(), opt.scene.c_str(), model.bodies.size(), steps, dt, 1e6 * per_step,
        per_step > 0 ? static_cast<double>(model.bodies.size()) / per_step : 0.0,
        bodies_outside(model, final_state), o.worst, o.worst / smallest, o.worst_bodies,
        worst_run, o.patches, world->sleeping_bodies(), smallest);
    if (sampler)
      std::printf(" moving_last=%lld creep=%.4g", sampler->moving_last(), sampler->creep());
    std::printf("%s wall_s=%.4f\n", engine.summary ? engine.summary().c_str() : "", wall);
  } catch (const std::exception& e) {
    std::cerr << opt.scene << ": " << e.what() << "\n";
    return 1;
  }
  return 0;
}

}  // namespace tem::peers
