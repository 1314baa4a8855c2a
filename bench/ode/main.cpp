// tem_ode: runs a TEM scene in ODE (the pour benchmark of tools/pour_bench.py) and
// judges the result with TEM's own measures. The scene is read and built by TEM (same bodies,
// masses, inertia, walls, gravity, dt), then rebuilt in ODE (ode_world.hpp). The driver, its
// common options and its summary line are shared with tem_bullet (bench/peers/peer_run.hpp).
//
//   tem_ode SCENE.json [common options of peer_run.hpp] [--stepper quick|step] [--iterations N]
//           [--erp E] [--cfm C] [--surface-layer D] [--max-contacts N]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <memory>
#include <vector>

#include "ode_world.hpp"
#include "peer_run.hpp"

int main(int argc, char** argv) {
  using namespace tem;
  ode::OdeSettings settings;
  // --stepper takes a word, not a number: picked out before the shared parser sees the rest.
  std::vector<char*> rest{argv[0]};
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--stepper") != 0) {
      rest.push_back(argv[i]);
      continue;
    }
    const char* word = i + 1 < argc ? argv[++i] : "";
    if (std::strcmp(word, "quick") == 0) settings.quick_step = true;
    else if (std::strcmp(word, "step") == 0) settings.quick_step = false;
    else {
      std::cerr << "tem_ode: --stepper takes 'quick' (dWorldQuickStep) or 'step' (dWorldStep), "
                << "got '" << word << "'\n";
      return 2;
    }
  }

  peers::PeerEngine engine;
  engine.name = "ode";
  engine.extra_usage =
      "[--stepper quick|step] [--iterations N] [--erp E] [--cfm C] [--surface-layer D] "
      "[--max-contacts N] [--trimesh 0|1]";
  engine.option = [&](const std::string& flag, const std::function<double()>& value) {
    if (flag == "--iterations") settings.iterations = static_cast<int>(std::lround(value()));
    else if (flag == "--erp") settings.erp = value();
    else if (flag == "--cfm") settings.cfm = value();
    else if (flag == "--surface-layer") settings.surface_layer = value();
    else if (flag == "--trimesh") settings.trimesh = value() != 0;
    else if (flag == "--max-contacts")
      settings.max_contacts = std::max(1, static_cast<int>(std::lround(value())));
    else return false;
    return true;
  };
  engine.make = [&](const Model& model, const State& initial, const peers::PeerSetup& setup) {
    settings.friction = setup.friction;
    settings.restitution = setup.restitution;
    settings.sleeping = setup.sleeping;
    return std::unique_ptr<peers::PeerWorld>(
        std::make_unique<ode::OdeWorld>(model, initial, settings));
  };
  engine.summary = [&] {
    char text[200];
    std::snprintf(text, sizeof text,
                  " stepper=%s iterations=%d erp=%.4g cfm=%.4g surface_layer=%.4g "
                  "max_contacts=%d geoms=%s",
                  settings.quick_step ? "quick" : "step", settings.iterations, settings.erp,
                  settings.cfm, settings.surface_layer, settings.max_contacts,
                  settings.trimesh ? "trimesh" : "convex");
    return std::string(text);
  };
  return peers::run_peer(static_cast<int>(rest.size()), rest.data(), engine);
}
