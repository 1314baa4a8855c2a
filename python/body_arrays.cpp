// sim.bodies: numpy arrays over TEM's own memory, one row per body in the scene's order.
#include <string>
#include <utility>

#include "py_simulation.hpp"

namespace tem_python {
namespace {

// The object behind sim.bodies: the Python Simulation it reads, which it keeps alive.
struct Bodies {
  py::object owner;
  PySimulation& sim() const { return owner.cast<PySimulation&>(); }
  py::ssize_t count() const { return sim().raw().body_count(); }
};

constexpr py::ssize_t kReal = sizeof(double);

py::array vec3_view(const Bodies& b, const double* data, py::ssize_t row_stride, bool writeable) {
  return make_view(b.owner, py::dtype::of<double>(), data, {b.count(), 3}, {row_stride, kReal},
                   writeable);
}

py::array external_view(const Bodies& b, bool torque) {
  tem::Simulation& sim = b.sim().raw();
  return vec3_view(b, torque ? sim.external_torque_data() : sim.external_force_data(), 3 * kReal,
                   true);
}

// `bodies.external_force = F`: F (N x 3, or anything numpy broadcasts to it) copied in.
void assign_external(const Bodies& b, bool torque, const py::object& value) {
  py::array view = external_view(b, torque);
  view.attr("__setitem__")(py::ellipsis(), value);
}

}  // namespace

py::object make_bodies(py::object owner) { return py::cast(Bodies{std::move(owner)}); }

void bind_bodies(py::module_& m) {
  py::class_<Bodies>(m, "Bodies", R"doc(
The bodies of a Simulation (``sim.bodies``), one row per body in the scene's order.

The state arrays (position, velocity, quaternion, angular_velocity) are read-only views on
TEM's own memory: no copy is made, the same array shows every later step's values, and it
stays valid (keeping its Simulation alive) as long as it exists. Copy one
(``sim.bodies.position.copy()``) to keep a step's values. external_force and external_torque
are writable views: what is written into them is applied at every later step until changed.
mass, volume, fixed and inertia_body are read-only views on constants; inertia is a copy.
Units are the scene's (cm, g, s by default).

Where bodies come and go (inlets, outlets, removed_at: docs/processes.md) the rows follow the
live bodies in the order of their ids: a step can add rows at the end and take rows out, the
others moving up. An array taken before such a step keeps its length and its memory stays
valid, but its rows then belong to the bodies now at those places: read ``sim.bodies`` (and
its names) again after a step that changed ``len(sim)``.
)doc")
      .def("__len__", &Bodies::count)
      .def("__repr__",
           [](const Bodies& b) {
             return "<tem.Bodies: " + std::to_string(b.count()) +
                    (b.count() == 1 ? " body>" : " bodies>");
           })
      .def_property_readonly(
          "names",
          [](const Bodies& b) {
            const tem::Simulation& sim = b.sim().raw();
            py::list names;
            for (int i = 0; i < sim.body_count(); ++i) names.append(sim.body_name(i));
            return names;
          },
          "The bodies' names (list of str; fill's copies are NAME_0, NAME_1, ...).")
      .def_property_readonly(
          "position",
          [](const Bodies& b) {
            const tem::Simulation& sim = b.sim().raw();
            return vec3_view(b, sim.position_data(), sim.state_stride(), false);
          },
          "(N, 3) centres of mass, world axes. Read-only view, no copy: sees every new step.")
      .def_property_readonly(
          "velocity",
          [](const Bodies& b) {
            const tem::Simulation& sim = b.sim().raw();
            return vec3_view(b, sim.velocity_data(), sim.state_stride(), false);
          },
          "(N, 3) velocities of the centres of mass. Read-only view, no copy: sees every new "
          "step.")
      .def_property_readonly(
          "quaternion",
          [](const Bodies& b) {
            return make_view(b.owner, py::dtype::of<double>(), b.sim().raw().quaternion_data(),
                             {b.count(), 4}, {4 * kReal, kReal}, false);
          },
          "(N, 4) attitudes [w, x, y, z] (w >= 0), body to world. Read-only view, refreshed "
          "by TEM after every step.")
      .def_property_readonly(
          "angular_velocity",
          [](const Bodies& b) {
            return vec3_view(b, b.sim().raw().angular_velocity_data(), 3 * kReal, false);
          },
          "(N, 3) angular velocities, world axes. Read-only view, refreshed by TEM after every "
          "step.")
      .def_property(
          "external_force", [](const Bodies& b) { return external_view(b, false); },
          [](const Bodies& b, const py::object& v) { assign_external(b, false, v); },
          "(N, 3) external forces, world axes, through the centres of mass. Writable view: "
          "what is written (bodies.external_force[i] = f, or bodies.external_force = F) is "
          "applied at every later step until changed. Zero at the start; fixed bodies ignore "
          "it.")
      .def_property(
          "external_torque", [](const Bodies& b) { return external_view(b, true); },
          [](const Bodies& b, const py::object& v) { assign_external(b, true, v); },
          "(N, 3) external torques about the centres of mass, world axes. Writable view, held "
          "like external_force.")
      .def_property_readonly(
          "mass",
          [](const Bodies& b) {
            return make_view(b.owner, py::dtype::of<double>(), b.sim().masses().data(), {b.count()},
                             {kReal}, false);
          },
          "(N,) masses. Read-only.")
      .def_property_readonly(
          "volume",
          [](const Bodies& b) {
            return make_view(b.owner, py::dtype::of<double>(), b.sim().volumes().data(),
                             {b.count()}, {kReal}, false);
          },
          "(N,) volumes. Read-only.")
      .def_property_readonly(
          "fixed",
          [](const Bodies& b) {
            return make_view(b.owner, py::dtype::of<bool>(), b.sim().fixed(), {b.count()},
                             {static_cast<py::ssize_t>(sizeof(bool))}, false);
          },
          "(N,) bool: bodies that never move. Read-only.")
      .def_property_readonly(
          "inertia_body",
          [](const Bodies& b) {
            return make_view(b.owner, py::dtype::of<double>(), b.sim().inertia_body().data(),
                             {b.count(), 3, 3}, {9 * kReal, 3 * kReal, kReal}, false);
          },
          "(N, 3, 3) inertia tensors about the centres of mass, body axes. Read-only.")
      .def_property_readonly(
          "inertia",
          [](const Bodies& b) {
            tem::Simulation& sim = b.sim().get();
            const py::ssize_t n = b.count();
            py::array_t<double> out({n, py::ssize_t{3}, py::ssize_t{3}});
            auto a = out.mutable_unchecked<3>();
            for (py::ssize_t i = 0; i < n; ++i) {
              const tem::Mat3 j = sim.inertia_world(static_cast<int>(i));
              for (py::ssize_t r = 0; r < 3; ++r)
                for (py::ssize_t c = 0; c < 3; ++c) a(i, r, c) = j(r, c);
            }
            return out;
          },
          "(N, 3, 3) inertia tensors about the centres of mass, world axes, at the current "
          "step: a new copy at every access (it changes as the bodies turn).");
}

}  // namespace tem_python
