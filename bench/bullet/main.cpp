// tem_bullet: runs a TEM scene in Bullet (issue 6, side by side) and judges the result with
// TEM's own measures. The scene is read and built by TEM (same bodies, masses, inertia, walls,
// gravity, dt), then rebuilt in Bullet (bullet_world.hpp). Prints progress lines and one
// machine-readable summary line, read by tools/side_by_side.py.
//
//   tem_bullet SCENE.json [--steps N | --duration S] [--dt DT] [--report-every K]
//              [--margin M | --margin-rel F] [--friction MU] [--restitution E] [--no-sleep]
//              [--print-final]
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>

#include "bullet_world.hpp"
#include "io/scene_reader.hpp"
#include "tem_measures.hpp"

namespace {

struct Options {
  std::string scene;
  long long steps = -1;   // -1: from the duration
  double duration = -1;   // -1: the scene's
  double dt = -1;         // -1: the scene's
  long long report_every = 0;
  double margin = -1;       // absolute, scene units; -1: margin_rel x smallest body size
  double margin_rel = 0.02;
  double friction = -1;     // -1: the scene's contact.friction
  double restitution = -1;  // -1: the scene's contact.restitution
  bool sleeping = true;
  bool print_final = false;  // final centre of mass of every body, on stderr
};

[[noreturn]] void usage(const std::string& why) {
  std::cerr << "tem_bullet: " << why << "\n"
            << "usage: tem_bullet SCENE.json [--steps N | --duration S] [--dt DT] "
               "[--report-every K] [--margin M | --margin-rel F] [--friction MU] "
               "[--restitution E] [--no-sleep] [--print-final]\n";
  std::exit(2);
}

double number(const std::string& flag, const char* text) {
  char* end = nullptr;
  const double v = std::strtod(text, &end);
  if (end == text || *end != '\0' || !std::isfinite(v) || v < 0)
    usage(flag + " needs a non-negative number, got '" + text + "'");
  return v;
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> const char* {
      if (i + 1 >= argc) usage(a + " needs a value");
      return argv[++i];
    };
    if (a == "--steps") o.steps = std::llround(number(a, value()));
    else if (a == "--duration") o.duration = number(a, value());
    else if (a == "--dt") o.dt = number(a, value());
    else if (a == "--report-every") o.report_every = std::llround(number(a, value()));
    else if (a == "--margin") o.margin = number(a, value());
    else if (a == "--margin-rel") o.margin_rel = number(a, value());
    else if (a == "--friction") o.friction = number(a, value());
    else if (a == "--restitution") o.restitution = number(a, value());
    else if (a == "--no-sleep") o.sleeping = false;
    else if (a == "--print-final") o.print_final = true;
    else if (a == "-h" || a == "--help") usage("help");
    else if (!a.empty() && a[0] == '-') usage("unknown option " + a);
    else if (o.scene.empty()) o.scene = a;
    else usage("more than one scene given");
  }
  if (o.scene.empty()) usage("no scene given");
  if (o.steps >= 0 && o.duration >= 0) usage("--steps and --duration exclude each other");
  if (o.dt == 0) usage("--dt must be positive");
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace tem;
  const Options opt = parse(argc, argv);

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
    const Real smallest = bullet::smallest_body_size(model);

    bullet::BulletSettings settings;
    settings.margin = opt.margin >= 0 ? opt.margin : opt.margin_rel * smallest;
    settings.friction = opt.friction >= 0 ? opt.friction : scene.contact.friction;
    settings.restitution = opt.restitution >= 0 ? opt.restitution : scene.contact.restitution;
    settings.sleeping = opt.sleeping;
    bullet::BulletWorld world(model, initial, settings);

    // Only the steps are timed; TEM's measurements in between are not.
    ContactWorkspace workspace;
    Real worst_run = 0;
    double wall = 0;
    for (long long k = 0; k < steps;) {
      const long long chunk = opt.report_every > 0 ? std::min(opt.report_every, steps - k)
                                                   : steps - k;
      const auto start = std::chrono::steady_clock::now();
      for (long long j = 0; j < chunk; ++j) world.step(dt);
      wall += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      k += chunk;
      if (opt.report_every > 0 && k < steps) {
        const State s = world.state();
        const bullet::Overlap o = bullet::measure_overlap(model, s, workspace);
        worst_run = std::max(worst_run, o.worst);
        std::fprintf(stderr, "tem_bullet: step %lld t=%.6g outside=%d worst_overlap=%.4g\n", k,
                     k * dt, bullet::bodies_outside(model, s), o.worst);
      }
    }

    const State final_state = world.state();
    const bullet::Overlap o = bullet::measure_overlap(model, final_state, workspace);
    if (opt.print_final)
      for (size_t i = 0; i < model.bodies.size(); ++i) {
        const BodyState& b = final_state.bodies[i];
        const Vec3 up = b.g.transpose() * Vec3::UnitZ();  // world z in body axes
        std::fprintf(stderr, "tem_bullet: final %s x=%.6g y=%.6g z=%.6g up_body=(%.4f %.4f %.4f)\n",
                     model.bodies[i].name.c_str(), b.x.x(), b.x.y(), b.x.z(), up.x(), up.y(),
                     up.z());
      }
    worst_run = std::max(worst_run, o.worst);
    const double per_step = steps > 0 ? wall / static_cast<double>(steps) : 0;
    std::printf(
        "engine=bullet scene=%s bodies=%zu steps=%lld dt=%.9g us_per_step=%.4g "
        "body_steps_per_s=%.4g outside=%d worst_overlap=%.4g worst_overlap_rel=%.4g "
        "worst_overlap_bodies=%.4g worst_overlap_run=%.4g patches=%d sleeping=%d "
        "min_body_size=%.6g margin=%.4g friction=%.4g restitution=%.4g wall_s=%.4f\n",
        opt.scene.c_str(), model.bodies.size(), steps, dt, 1e6 * per_step,
        per_step > 0 ? static_cast<double>(model.bodies.size()) / per_step : 0.0,
        bullet::bodies_outside(model, final_state), o.worst, o.worst / smallest, o.worst_bodies,
        worst_run, o.patches, world.sleeping_bodies(), smallest, settings.margin,
        settings.friction, settings.restitution, wall);
  } catch (const std::exception& e) {
    std::cerr << opt.scene << ": " << e.what() << "\n";
    return 1;
  }
  return 0;
}
