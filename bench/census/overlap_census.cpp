// The overlap census: why bodies of a scene overlap, step by step.
//
// A pour is judged by its deepest overlap (tools/pour_bench.py). An overlap after a step comes
// either from a pair the step's detection never saw (its margin did not reach, or the search
// dropped it) or from a pair it saw whose contact the solver did not hold (unconverged sweeps, a
// single point of an edge pair while the bodies turn). The two need different cures, so this
// program steps the scene and, after every step, finds every overlapping pair anew (margin 0),
// and counts those deeper than --share of the smaller body's size (body_size, as the pour
// benchmark's rule) by whether the step's patches held the pair, with the deepest of each kind.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdio>
#include <map>
#include <utility>

#include "contact/detect_contacts.hpp"
#include "io/scene_reader.hpp"
#include "simulation/step.hpp"

namespace {

using namespace tem;

struct Deepest {
  long long count = 0;
  Real share = 0;  // of the smaller body's size
  Real time = 0;
  int body_a = -1, body_b = -1;
  ManifoldFeature feature = ManifoldFeature::none;  // of the step's patch, where there was one
  Real start_share = 0;  // the patch's depth at the step's start (< 0: still apart), same unit
  long long already = 0;  // overlaps that were already deeper than the threshold at the start

  void add(Real s, Real t, int a, int b, ManifoldFeature f, Real start, Real threshold) {
    ++count;
    if (start > threshold) ++already;
    if (s <= share) return;
    share = s;
    time = t;
    body_a = a;
    body_b = b;
    feature = f;
    start_share = start;
  }
};

const char* feature_name(ManifoldFeature f) {
  switch (f) {
    case ManifoldFeature::edges: return "an edge pair";
    case ManifoldFeature::edges_past_rim: return "an edge pair past a face's rim";
    case ManifoldFeature::face_of_a: return "a face of A";
    case ManifoldFeature::face_of_b: return "a face of B";
    default: return "-";
  }
}

void print(const char* what, const Deepest& d) {
  std::printf("%s: %lld overlaps", what, d.count);
  if (d.count > 0)
    std::printf(", deepest %.3g %% at t = %.5g s (bodies %d and %d%s%s)", 100 * d.share, d.time,
                d.body_a, d.body_b, d.feature == ManifoldFeature::none ? "" : ", patch of ",
                d.feature == ManifoldFeature::none ? "" : feature_name(d.feature));
  if (d.feature != ManifoldFeature::none)
    std::printf("; %lld of them already as deep at the step's start, the deepest %.3g %% deep "
                "there", d.already, 100 * d.start_share);
  std::printf("\n");
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Overlaps after each step, sorted by whether the step's detection saw the pair"};
  std::string scene_file;
  double dt = 0, duration = 0, share = 0.01;
  int substeps = 0, max_substeps = 0;
  app.add_option("scene", scene_file, "scene file")->required()->check(CLI::ExistingFile);
  app.add_option("--dt", dt, "time step (default: the scene's)");
  app.add_option("--duration", duration, "simulated seconds (default: the scene's)");
  app.add_option("--substeps", substeps, "contact.substeps (default: the scene's)");
  app.add_option("--max-substeps", max_substeps, "contact.max_substeps (default: the scene's)");
  app.add_option("--share", share, "count overlaps deeper than this share of the smaller size");
  CLI11_PARSE(app, argc, argv);

  SceneReadResult read = read_scene_file(scene_file);
  if (!read.ok()) {
    for (const SceneProblem& p : read.problems) std::fprintf(stderr, "%s\n", format_problem(scene_file, p).c_str());
    return 1;
  }
  if (dt > 0) read.scene.time_step = dt;
  if (duration > 0) read.scene.duration = duration;
  if (substeps > 0) read.scene.contact.substeps = substeps;
  if (max_substeps > 0) read.scene.contact.max_substeps = max_substeps;
  const Model model = build_model(read.scene);
  State state = initial_state(model);
  Workspace w;
  ContactWorkspace probe;  // margin 0: the pairs that overlap
  std::vector<ContactPatch> overlaps;
  struct Seen {
    ManifoldFeature feature;
    Real depth;  // the patch's, at the step's start
  };
  std::map<std::pair<int, int>, Seen> seen;
  Deepest missed, held;
  const long long steps = std::llround(read.scene.duration / read.scene.time_step);
  for (long long k = 0; k < steps; ++k) {
    find_contact_forces(model, state, w);
    seen.clear();
    for (const ContactPatch& p : w.patches)
      if (p.wall < 0) {
        const Seen here{p.manifold.feature, p.depth};
        auto [it, fresh] = seen.try_emplace({p.body_a, p.body_b}, here);
        if (!fresh && p.depth > it->second.depth) it->second = here;
      }
    advance(model, state, w);
    probe.reach.assign(model.bodies.size(), 0);
    detect_contacts(model, state, patch_variant(model.scene), probe, overlaps);
    for (const ContactPatch& p : overlaps) {
      if (p.wall >= 0) continue;
      const Real size = std::min(body_size(model, p.body_a), body_size(model, p.body_b));
      if (p.depth <= share * size) continue;
      const auto it = seen.find({p.body_a, p.body_b});
      if (it == seen.end())
        missed.add(p.depth / size, state.time, p.body_a, p.body_b, ManifoldFeature::none, 0, 1);
      else
        held.add(p.depth / size, state.time, p.body_a, p.body_b, it->second.feature,
                 it->second.depth / size, share);
    }
  }
  std::printf("%s: %lld steps of %g s (%d sub-steps), overlaps deeper than %g %% of the smaller "
              "body's size after a step\n",
              scene_file.c_str(), steps, read.scene.time_step, read.scene.contact.substeps,
              100 * share);
  print("pairs the step's detection did not see", missed);
  print("pairs it saw, not held", held);
  std::printf("bodies that outran their margin: %lld; steps with unconverged sweeps: %lld; "
              "sub-steps a step: %.2f on average, %d at most\n",
              w.times.outran_margin, w.times.unconverged_steps,
              static_cast<double>(w.times.substeps) / static_cast<double>(std::max(steps, 1LL)),
              w.times.max_substeps);
  return 0;
}
