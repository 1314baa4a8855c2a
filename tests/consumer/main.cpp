// A client of the installed TEM package (find_package(TEM), TEM::tem): builds a scene in code,
// loads one from a file, steps both and checks what they do against physics. Exit status 0 when
// every check holds; each failed check prints one line.
//
//   consumer SCENE_FILE     (tests/scenes/drop_box.json: a box tilted by 5 degrees, just above
//                            the floor of a 1 cm container)
#include <tem/scene_def.hpp>
#include <tem/simulation.hpp>
#include <tem/types.hpp>

#include <cmath>
#include <cstdio>
#include <exception>
#include <string>

namespace {

int failures = 0;

void check(bool ok, const std::string& what) {
  std::printf("%s  %s\n", ok ? "ok  " : "FAIL", what.c_str());
  if (!ok) ++failures;
}

bool near(double a, double b, double tol) { return std::abs(a - b) <= tol; }

std::string num(double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

// A 2 x 1.5 x 1 cm box of density 2.5, turned about the vertical by 0.3 rad, 7.5 cm above the
// floor of a 10 cm container, dropped under Earth's gravity (cgs) with steps of 1e-4 s.
tem::SceneDef box_drop_scene() {
  tem::SceneDef scene;
  scene.source = "box_drop (built in code)";
  scene.time_step = 1e-4;
  scene.duration = 1.0;
  scene.container = tem::ContainerDef{tem::Vec3::Zero(), tem::Vec3::Constant(10)};
  tem::BodyDef box;
  box.name = "box";
  box.shape.type = tem::ShapeType::box;
  box.shape.size = tem::Vec3(2, 1.5, 1);
  box.density = 2.5;
  box.position = tem::Vec3(5, 5, 8);
  box.rotation = tem::rotation_z(0.3);  // from libtem.so's core, not the API class
  scene.bodies.push_back(box);
  return scene;
}

void scene_in_code() {
  std::printf("-- a box built in code, dropped onto the floor\n");
  const tem::SceneDef scene = box_drop_scene();
  tem::Simulation sim = tem::Simulation::from_scene(scene);
  check(sim.body_count() == 1 && sim.body_index("box") == 0, "one body, named box");

  const double m = 2 * 1.5 * 1 * 2.5;
  check(near(sim.mass(0), m, 1e-12 * m), "mass " + num(sim.mass(0)) + " = 7.5");
  const double ixx = m / 12 * (1.5 * 1.5 + 1 * 1);  // body axes: the box's own edges
  check(near(sim.inertia_body(0)(0, 0), ixx, 1e-12 * ixx),
        "inertia_body xx " + num(sim.inertia_body(0)(0, 0)) + " = m (b^2 + c^2) / 12 = " +
            num(ixx));

  // Free fall for 0.1 s (1000 steps): 4.9 cm down, still 2.6 cm above the floor.
  const tem::Vec3 x0 = sim.position(0);
  const double g = tem::earth_gravity_cgs;
  sim.step(1000);
  const double t = sim.time();
  check(near(t, 0.1, 1e-12), "time " + num(t) + " after 1000 steps of 1e-4");
  const double drop = x0.z() - sim.position(0).z();
  const double expected_drop = g * t * t / 2;
  check(near(drop, expected_drop, 1e-9 * expected_drop),
        "free fall: drop " + num(drop) + " = g t^2/2 = " + num(expected_drop) + " (1e-9)");
  check(near(sim.velocity(0).z(), -g * t, 1e-9 * g * t),
        "free fall: v_z " + num(sim.velocity(0).z()) + " = -g t = " + num(-g * t) + " (1e-9)");
  check(near(sim.position(0).x(), x0.x(), 1e-12) && near(sim.position(0).y(), x0.y(), 1e-12),
        "free fall: no horizontal drift");
  check(sim.contacts().empty(), "free fall: no contact yet");

  // Lands at about 0.124 s; by 0.6 s it lies on the floor, at rest, its centre at half height.
  sim.step(5000);
  const tem::Vec3 x = sim.position(0);
  check(near(x.z(), 0.5, 0.01 * 1.0),
        "at rest: centre at z " + num(x.z()) + " = half height 0.5 (1 % of the height)");
  check(sim.velocity(0).norm() < 1e-3 && sim.angular_velocity(0).norm() < 1e-3,
        "at rest: |v| " + num(sim.velocity(0).norm()) + " cm/s, |w| " +
            num(sim.angular_velocity(0).norm()) + " rad/s");
  const tem::Quat q = sim.attitude(0);
  const tem::Quat q0(tem::rotation_z(0.3));
  check(q.angularDistance(q0) < 1e-3,
        "at rest: flat, still turned 0.3 rad about z (off by " + num(q.angularDistance(q0)) +
            " rad)");
  bool on_floor = !sim.contacts().empty();
  for (const tem::Contact& c : sim.contacts())
    on_floor = on_floor && c.body_a == 0 && c.wall >= 0 && std::abs(c.normal.z()) > 0.999;
  check(on_floor, "at rest: " + std::to_string(sim.contacts().size()) +
                      " contact patch(es), all with the floor");
  const tem::SystemEnergies e = sim.energies();
  check(e.kinetic < 1e-6 * m * g, "at rest: kinetic energy " + num(e.kinetic));
}

void scene_from_file(const std::string& file) {
  std::printf("-- %s, loaded from its file\n", file.c_str());
  tem::Simulation sim = tem::Simulation::load(file);
  check(sim.body_count() == 1 && sim.body_index("box") == 0, "one body, named box");
  check(sim.total_steps() == 500, "total_steps " + std::to_string(sim.total_steps()) + " = 500");
  // The scene as read, fed back in code, runs bit for bit the same.
  tem::Simulation twin = tem::Simulation::from_scene(sim.scene());
  sim.step(sim.total_steps());
  twin.step(twin.total_steps());
  check(sim.state_hash() == twin.state_hash() && sim.state_hash_hex() == twin.state_hash_hex(),
        "file and its SceneDef: same state hash " + sim.state_hash_hex());
  // 0.2 x 0.2 x 0.1 box tilted by 5 degrees just above the floor: it tips onto its face.
  sim.step(4500);  // to 0.5 s
  const double z = sim.position(0).z();
  check(near(z, 0.05, 0.01 * 0.1), "at rest: centre at z " + num(z) + " = 0.05 (1 % of 0.1)");
  check(sim.velocity(0).norm() < 1e-3, "at rest: |v| " + num(sim.velocity(0).norm()));
}

void bad_scene() {
  std::printf("-- a scene with a negative size\n");
  tem::SceneDef scene = box_drop_scene();
  scene.bodies[0].shape.size = tem::Vec3(2, -1.5, 1);
  try {
    tem::Simulation sim = tem::Simulation::from_scene(scene);
    check(false, "from_scene threw nothing");
  } catch (const tem::SceneLoadError& e) {
    const std::string what = e.what();
    std::printf("      message: %s\n", what.c_str());
    check(what.find("bodies[0].shape.size[1]") != std::string::npos,
          "SceneLoadError names the JSON path bodies[0].shape.size[1]");
  }
  try {
    tem::Simulation sim = tem::Simulation::from_json(R"({"bodies": [{"name": "a",
        "shape": {"type": "box", "size": [1, 1, 1]}, "position": [0, 0, 0], "density": -2}]})",
                                                     "text");
    check(false, "from_json threw nothing");
  } catch (const tem::SceneLoadError& e) {
    const std::string what = e.what();
    std::printf("      message: %s\n", what.c_str());
    check(what.find("text: bodies[0].density") != std::string::npos,
          "SceneLoadError names the origin and the JSON path bodies[0].density");
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s SCENE_FILE\n", argv[0]);
    return 2;
  }
  try {
    scene_in_code();
    scene_from_file(argv[1]);
    bad_scene();
  } catch (const std::exception& e) {
    std::printf("FAIL  unexpected exception: %s\n", e.what());
    return 1;
  }
  std::printf("%s\n", failures == 0 ? "all checks passed" : "some checks FAILED");
  return failures == 0 ? 0 : 1;
}
