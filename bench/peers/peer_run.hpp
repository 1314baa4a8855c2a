// The driver shared by the side-by-side programs (tem_bullet, tem_ode): reads the scene with
// TEM's reader, builds the Model, asks the engine for its world, steps it (only the steps are
// timed), measures with TEM's own code, and prints one machine-readable summary line
// "engine=NAME key=value ..." on stdout (read by tools/side_by_side.py and tools/pour_bench.py).
//
// Options every engine takes:
//   SCENE.json [--steps N | --duration S] [--dt DT] [--report-every K] [--friction MU]
//   [--restitution E] [--no-sleep] [--print-final] [--final-run DIR]
//   [--samples FILE] [--sample-every S] [--rest-speed V] [--rest-window W] [--creep-window W]
//
// --final-run DIR writes the last poses as a run's scene.json and bodies.csv (one row a body),
// which tools/settled_pile.py turns into a scene: a pile the engine made, for TEM to start from.
// --samples FILE writes one CSV row every S seconds of simulated time (default 0.01), first at
// t = 0: what the pour rules need (docs/benchmarks.md "Pour side by side"):
//   time, outside (centres outside the container box), max_depth (deepest contact patch by
//   TEM's detection), kinetic, potential, total (TEM's system_energies), max_point_speed (the
//   largest |v| + |omega| * body_size over the free bodies).
// With samples, the summary line adds moving_last: bodies whose point speed reached
// --rest-speed (default 0.1) at some sample of the last --rest-window seconds (default 0.1), and
// creep: the largest point speed at the samples of the last --creep-window seconds (0.5).
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "peer_world.hpp"
#include "world/model.hpp"

namespace tem::peers {

// What every engine is told, resolved from the scene and the common options.
struct PeerSetup {
  // Negative: each pair's coefficients from the scene (contact.friction, materials); else one
  // value for every pair, body-body and body-wall.
  Real friction = -1;
  Real restitution = -1;
  bool sleeping = true;  // let bodies at rest be deactivated (the engine's own rule)
};

struct PeerEngine {
  std::string name;         // "bullet": the summary's engine=, the prefix of messages
  std::string extra_usage;  // the engine's own options, for the usage text
  // Offered every option the common parser does not know: true when taken. `value()` reads the
  // option's number (non-negative, finite) and fails with a usage message otherwise.
  std::function<bool(const std::string& flag, const std::function<double()>& value)> option;
  std::function<std::unique_ptr<PeerWorld>(const Model&, const State&, const PeerSetup&)> make;
  // Extra " key=value" fields of the summary line (the engine's settings as used).
  std::function<std::string()> summary;
};

// The whole program: returns main's exit status (2: bad options or scene, 1: failure).
int run_peer(int argc, char** argv, PeerEngine& engine);

}  // namespace tem::peers
