// The Python module `tem`: tem::Simulation (include/tem/simulation.hpp) for Python, with the
// bodies' state as numpy views on TEM's memory. Built by python/CMakeLists.txt; the docstrings
// below are the module's documentation (help(tem)).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstdint>
#include <string>
#include <vector>

#include "py_simulation.hpp"
#include "tem/simulation.hpp"

namespace tem_python {
namespace {

// One row of sim.contacts().
struct ContactRow {
  std::int32_t body_a;
  std::int32_t body_b;
  std::int32_t wall;
  double point[3];
  double normal[3];
  double depth;
  double fn;
  double ft;
};

// A str or os.PathLike argument as a path string.
std::string path_of(const py::object& path) {
  return py::module_::import("os").attr("fspath")(path).cast<std::string>();
}

// json.dumps(d), with numpy arrays and numbers turned into lists and floats.
std::string json_of(const py::object& d) {
  const py::cpp_function to_plain([](const py::object& o) -> py::object {
    if (py::hasattr(o, "tolist")) return o.attr("tolist")();
    throw py::type_error("Object of type " +
                         py::str(py::type::of(o).attr("__name__")).cast<std::string>() +
                         " is not JSON serializable");
  });
  return py::module_::import("json")
      .attr("dumps")(d, py::arg("default") = to_plain)
      .cast<std::string>();
}

py::array contacts_array(const tem::Simulation& sim) {
  const std::vector<tem::Contact> contacts = sim.contacts();
  py::array_t<ContactRow> out(static_cast<py::ssize_t>(contacts.size()));
  ContactRow* rows = out.mutable_data();
  for (size_t k = 0; k < contacts.size(); ++k) {
    const tem::Contact& c = contacts[k];
    ContactRow& r = rows[k];
    r.body_a = c.body_a;
    r.body_b = c.body_b;
    r.wall = c.wall;
    for (int i = 0; i < 3; ++i) {
      r.point[i] = c.point[i];
      r.normal[i] = c.normal[i];
    }
    r.depth = c.depth;
    r.fn = c.normal_force;
    r.ft = c.tangential_force;
  }
  return out;
}

std::string repr(PySimulation& s) {
  const tem::Simulation& sim = s.raw();
  const int n = sim.body_count();
  return "<tem.Simulation of " + std::to_string(n) + (n == 1 ? " body" : " bodies") + " at step " +
         std::to_string(sim.step_count()) + " of " + std::to_string(sim.total_steps()) +
         ", t = " + py::repr(py::float_(sim.time())).cast<std::string>() + ">";
}

const char* const kModuleDoc = R"doc(
TEM: rigid bodies of any shape, made of tetrahedral elements, that touch, collide, pile up and
come to rest (Python module over TEM's C++ API, include/tem/simulation.hpp).

    import tem
    sim = tem.Simulation("scenes/coin.json")      # or Simulation.from_dict({...})
    b = sim.bodies
    b.external_force[:] = [0, 0, -0.5]            # held for every step until changed
    sim.step(100)                                 # the GIL is released while stepping
    print(sim.time, b.position[0], sim.energies())

Arrays: sim.bodies.position, .velocity, .quaternion and .angular_velocity are read-only numpy
views on TEM's own state, in the scene's body order: no copy is made, each sees every new step,
and each stays valid while it exists (it keeps its Simulation alive). Copy to keep a step's
values. .external_force and .external_torque are writable views. Reading them while another
thread is inside step() shows a step half done.

Errors: a bad scene raises tem.SceneError (a ValueError) with every problem, one per line, as
`tem check` prints them (FILE: JSON.path: reason); unreadable or foreign checkpoints and
unwritable directories raise RuntimeError; a body index out of range raises IndexError.
)doc";

}  // namespace
}  // namespace tem_python

PYBIND11_MODULE(tem, m) {
  using namespace tem_python;
  m.doc() = kModuleDoc;
  m.attr("__version__") = TEM_VERSION;
  PYBIND11_NUMPY_DTYPE(ContactRow, body_a, body_b, wall, point, normal, depth, fn, ft);

  // tem::SceneLoadError derives from std::runtime_error; translators registered later are tried
  // first, so it does not end as a RuntimeError.
  py::register_exception<tem::SceneLoadError>(m, "SceneError", PyExc_ValueError);
  m.attr("SceneError").attr("__doc__") =
      "A scene that cannot be loaded (a ValueError). str(e) holds every problem, one per line, "
      "as `tem check` prints them: 'FILE: JSON.path: reason'.";

  m.def("set_threads", &set_threads, py::arg("threads"),
        "Threads for the step's shared work (OpenMP; 0: one per core). The results do not "
        "depend on it. Process-wide: it holds for step() called from any Python thread. "
        "Without it, OpenMP's default: OMP_NUM_THREADS, or one per core.");

  bind_bodies(m);

  py::class_<PySimulation>(m, "Simulation", R"doc(
One simulation of rigid bodies, loaded from a scene (docs/scene_format.md), stepped, read and
pushed from Python. Simulation(path) loads a scene file; see also from_dict, from_json, resume.
One Simulation is used from one thread at a time.
)doc")
      .def(py::init([](const py::object& path) {
             return PySimulation(tem::Simulation::load(path_of(path)));
           }),
           py::arg("path"), "Loads the scene file `path`. Raises SceneError for a bad scene.")
      .def_static(
          "from_dict",
          [](const py::object& scene) {
            return PySimulation(tem::Simulation::from_json(json_of(scene), "<dict>"));
          },
          py::arg("scene"),
          "The scene given as a dict of the scene file's keys (numpy arrays are accepted as "
          "lists). Errors name the scene '<dict>'.")
      .def_static(
          "from_json",
          [](const std::string& text, const std::string& origin) {
            return PySimulation(tem::Simulation::from_json(text, origin));
          },
          py::arg("text"), py::arg("origin") = "<json>",
          "The scene given as JSON text; `origin` names it in error messages.")
      .def_static(
          "resume",
          [](const py::object& scene, const py::object& checkpoint) {
            return PySimulation(tem::Simulation::resume(path_of(scene), path_of(checkpoint)));
          },
          py::arg("scene"), py::arg("checkpoint"),
          "The scene at a checkpoint written by write_checkpoint() or `tem run` (only duration "
          "and output.checkpoint_interval may differ from the scene it was taken of). Stepping "
          "on continues bit for bit. RuntimeError when the checkpoint cannot be read or belongs "
          "to another scene.")
      .def_static(
          "resume_recording",
          [](const py::object& scene, const py::object& directory, bool contacts) {
            return PySimulation(
                tem::Simulation::resume_recording(path_of(scene), path_of(directory), contacts));
          },
          py::arg("scene"), py::arg("directory"), py::arg("contacts") = false,
          "Continues a run that `tem run` or record() left in `directory` from its "
          "checkpoint.bin, recording on into the same files.")
      .def("step", &PySimulation::step, py::arg("n") = 1,
           "Takes n whole steps of time_step. The GIL is released meanwhile (other Python "
           "threads run); Ctrl-C stops it at the end of a step with KeyboardInterrupt.")
      .def_property_readonly(
          "time", [](PySimulation& s) { return s.raw().time(); }, "Simulated time now.")
      .def_property_readonly(
          "step_count", [](PySimulation& s) { return s.raw().step_count(); },
          "Steps taken since the scene's start.")
      .def_property_readonly(
          "time_step", [](PySimulation& s) { return s.raw().time_step(); },
          "The scene's time step.")
      .def_property_readonly(
          "total_steps", [](PySimulation& s) { return s.raw().total_steps(); },
          "Steps `tem run` takes for the scene's duration: round(duration / time_step).")
      .def_property_readonly(
          "bodies", [](const py::object& self) { return make_bodies(self); },
          "The bodies' arrays (tem.Bodies); see help(tem.Bodies).")
      .def_property_readonly(
          "warnings",
          [](PySimulation& s) {
            const std::vector<std::string>& w = s.raw().warnings();
            return py::list(py::cast(w));
          },
          "Warnings about accepted defects of the scene (list of str).")
      .def(
          "inlet_deliveries",
          [](PySimulation& s) {
            py::list out;
            for (const tem::Simulation::InletDelivery& d : s.raw().inlet_deliveries())
              out.append(py::dict(py::arg("name") = d.name, py::arg("placed") = d.placed,
                                  py::arg("due") = d.due, py::arg("count") = d.count));
            return out;
          },
          "Per inlet, in the scene's order: a dict of its name, the copies it has placed, those "
          "due by now and its count.")
      .def(
          "body_index",
          [](PySimulation& s, const std::string& name) {
            const int i = s.raw().body_index(name);
            if (i < 0) throw py::key_error("no body is named '" + name + "'");
            return i;
          },
          py::arg("name"), "The index of the body `name`; KeyError when there is none.")
      .def(
          "body_name", [](PySimulation& s, int i) { return s.raw().body_name(i); },
          py::arg("index"), "The name of body `index`; IndexError when out of range.")
      .def(
          "first_non_finite_body", [](PySimulation& s) { return s.get().first_non_finite_body(); },
          "The first body whose state stopped being finite (a blown-up scene), or -1.")
      .def(
          "clear_external_loads", [](PySimulation& s) { s.get().clear_external_loads(); },
          "Sets every external force and torque to zero.")
      .def(
          "contacts", [](PySimulation& s) { return contacts_array(s.get()); },
          R"doc(The contact patches of the last step taken (empty before the first), as a
numpy structured array (a copy) with fields body_a, body_b (-1 for a wall), wall (the wall's
index, the container's six faces first, or -1), point (3; at the step's start), normal (3;
unit, from body_a into body_b), depth (negative: still a gap apart), fn and ft (magnitudes of
the normal and tangential forces on body_a, averaged over the step: forces, not impulses).)doc")
      .def(
          "energies",
          [](PySimulation& s) {
            const tem::SystemEnergies e = s.get().energies();
            py::dict d;
            d["kinetic"] = e.kinetic;
            d["potential"] = e.potential;
            d["total"] = e.total();
            d["driven_work"] = e.driven_work;
            return d;
          },
          "dict with kinetic, potential (of gravity) and total energy of the bodies that move "
          "freely, and driven_work: the work bodies with a prescribed motion have done on them "
          "since the start (total - driven_work never rises without external loads).")
      .def(
          "state_hash", [](PySimulation& s) { return s.get().state_hash_hex(); },
          "Hash of the state's exact bits, 16 hex digits, as `tem run --hash` prints it.")
      .def(
          "write_checkpoint",
          [](PySimulation& s, const py::object& path) { s.get().write_checkpoint(path_of(path)); },
          py::arg("path"),
          "Writes the state and the contact solver's memory to `path`; resume() continues "
          "from it bit for bit.")
      .def(
          "record",
          [](PySimulation& s, const py::object& directory, bool contacts) {
            return s.get().record(path_of(directory), contacts);
          },
          py::arg("directory"), py::arg("contacts") = false,
          "Writes `tem run`'s files into `directory` (bodies.csv, energy.csv, scene.json; "
          "contacts.csv with contacts=True; checkpoints and ParaView files when the scene asks) "
          "from now on: a row now, then every output interval. Call finish_recording() at the "
          "end. Returns the names of an earlier run's files it removed from `directory` "
          "(those this run would not write again, so none passes for this run's).")
      .def(
          "finish_recording", [](PySimulation& s) { s.get().finish_recording(); },
          "Writes the last state's row and closes the files record() opened.")
      .def_property_readonly(
          "recording", [](PySimulation& s) { return s.raw().recording(); },
          "Whether record() is writing files.")
      .def("__len__", [](PySimulation& s) { return s.raw().body_count(); })
      .def("__repr__", &repr);
}
