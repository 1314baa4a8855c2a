// tem_bullet: runs a TEM scene in Bullet (side by side, and the pour benchmark) and
// judges the result with TEM's own measures. The scene is read and built by TEM (same bodies,
// masses, inertia, walls, gravity, dt), then rebuilt in Bullet (bullet_world.hpp). The driver,
// its common options and its summary line are shared with tem_ode (bench/peers/peer_run.hpp).
//
//   tem_bullet SCENE.json [common options of peer_run.hpp] [--margin M | --margin-rel F]
#include <cstdio>
#include <memory>

#include "bullet_world.hpp"
#include "peer_run.hpp"
#include "tem_measures.hpp"

int main(int argc, char** argv) {
  using namespace tem;
  double margin = -1;  // absolute, scene units; -1: margin_rel x smallest body size
  double margin_rel = 0.02;
  bullet::BulletSettings used;

  peers::PeerEngine engine;
  engine.name = "bullet";
  engine.extra_usage = "[--margin M | --margin-rel F]";
  engine.option = [&](const std::string& flag, const std::function<double()>& value) {
    if (flag == "--margin") margin = value();
    else if (flag == "--margin-rel") margin_rel = value();
    else return false;
    return true;
  };
  engine.make = [&](const Model& model, const State& initial, const peers::PeerSetup& setup) {
    // Bullet gets one friction and one restitution for every contact: the scene's contact
    // defaults unless overridden (materials are not carried over).
    used.margin = margin >= 0 ? margin : margin_rel * peers::smallest_body_size(model);
    used.friction = setup.friction >= 0 ? setup.friction : model.scene.contact.friction;
    used.restitution =
        setup.restitution >= 0 ? setup.restitution : model.scene.contact.restitution;
    used.sleeping = setup.sleeping;
    return std::unique_ptr<peers::PeerWorld>(
        std::make_unique<bullet::BulletWorld>(model, initial, used));
  };
  engine.summary = [&] {
    char text[160];
    std::snprintf(text, sizeof text, " margin=%.4g friction=%.4g restitution=%.4g", used.margin,
                  used.friction, used.restitution);
    return std::string(text);
  };
  return peers::run_peer(argc, argv, engine);
}
