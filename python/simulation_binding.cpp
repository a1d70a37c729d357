// serosa.Simulation: app::Simulation (the driver `serosa headless` runs) as a Python class.
// Arrays are numpy copies taken at the call (a cut renumbers tets and adds nodes, so a view
// would outlive its meaning); the GIL is released while the solver steps.
#include <pybind11/stl.h>

#include <cmath>
#include <memory>
#include <optional>
#include <stdexcept>

#include "app/headless.h"
#include "app/output_paths.h"
#include "app/simulation.h"
#include "engine/sim_state.h"
#include "python/convert.h"

namespace serosa::python {
namespace {

class PySimulation {
 public:
  PySimulation(const std::string& scene, const py::dict& overrides,
               std::optional<std::int64_t> steps, std::optional<std::string> record,
               bool validate_cuts) {
    app::HeadlessOptions o;
    o.scene = scene;
    o.overrides = overrides_from(overrides);
    o.steps = steps;
    o.progress = false;
    o.scene_record = false;  // a program records when it asks
    if (record) o.record = *record;
    o.validate_cuts = validate_cuts;
    m_sim = std::make_unique<app::Simulation>(o);
  }

  void step(std::int64_t n) {
    if (n < 0) throw std::invalid_argument("step(n): n = " + std::to_string(n) + " < 0");
    py::gil_scoped_release free;
    for (std::int64_t i = 0; i < n; ++i) m_sim->step();
  }

  [[nodiscard]] const SimState& state() const { return m_sim->state(); }
  [[nodiscard]] app::Simulation& sim() { return *m_sim; }

  std::size_t tool_index(const std::string& name) const {
    const auto& tools = m_sim->scene().tools;
    for (std::size_t i = 0; i < tools.size(); ++i)
      if (tools[i].name == name) return i;
    std::string names;
    for (const Tool& t : tools) names.append(names.empty() ? "" : ", ").append(t.name);
    throw py::key_error("no tool '" + name + "' in " + m_sim->scene().file.string() +
                        " (tools: " + names + ")");
  }

  py::dict tool(const std::string& name) const {
    const std::size_t i = tool_index(name);
    py::dict d = tool_dict(state().tools[i]);
    const Tool& t = m_sim->scene().tools[i];
    d["kind"] = std::string(tool_kind_name(t.kind));
    d["device"] = std::string(device_kind_name(t.device.kind));
    return d;
  }

  void set_tool(const std::string& name, const py::object& position, const py::object& orientation,
                const py::object& jaw, const py::object& buttons) {
    const std::size_t i = tool_index(name);
    ToolState t = m_sim->pose_set(i).value_or(state().tools[i]);
    if (!position.is_none()) {
      const std::vector<Vec3> p = points_from(py::make_tuple(position), "position");
      if (!p[0].allFinite()) throw std::invalid_argument("position: not finite");
      t.tip_m = {p[0].x(), p[0].y(), p[0].z()};
    }
    if (!orientation.is_none()) {
      const auto q = py::cast<std::vector<double>>(orientation);
      const double norm =
          q.size() == 4 ? std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]) : 0.0;
      if (!(norm > 1e-9) || !std::isfinite(norm))
        throw std::invalid_argument("orientation: a non-zero quaternion (w, x, y, z)");
      t.quat_wxyz = {q[0] / norm, q[1] / norm, q[2] / norm, q[3] / norm};
    }
    if (!jaw.is_none()) {
      const auto j = jaw.cast<double>();
      if (!std::isfinite(j) || j < 0.0)
        throw std::invalid_argument("jaw: an opening angle >= 0 in rad");
      t.jaw_rad = j;
    }
    if (!buttons.is_none()) t.buttons = buttons.cast<std::uint32_t>();
    m_sim->set_tool(i, t);
  }

  py::dict cut(const py::object& polygon) {
    const cutting::ConvexPolygon p(points_from(polygon, "polygon"));
    cutting::StrokeReport r;
    {
      py::gil_scoped_release free;
      r = m_sim->cut(p);
    }
    py::dict d;
    d["cuts"] = r.cuts;
    d["tets_crossed"] = r.tets_crossed;
    d["tets_added"] = r.tets_created;
    d["tets_removed"] = r.tets_crossed;
    d["min_quality"] = r.min_quality;
    d["swept_area_m2"] = r.swept_area_m2;
    d["crack_area_m2"] = r.crack_area_m2;
    d["step"] = r.last_step;
    return d;
  }

  py::bytes snapshot() const {
    const std::vector<std::uint8_t> b = m_sim->snapshot();
    return {reinterpret_cast<const char*>(b.data()), b.size()};
  }

  void restore(const py::bytes& bytes) {
    const std::string_view view = bytes;
    m_sim->restore(std::span(reinterpret_cast<const std::uint8_t*>(view.data()), view.size()),
                   "snapshot");
  }

  void export_mesh(const std::string& path) {
    app::check_output_file("export", path);
    const app::MeshOutputFormat f = app::mesh_output_format("export", path);
    app::write_mesh_output(path, f, state().mesh, m_sim->assembled().group_names());
  }

 private:
  std::unique_ptr<app::Simulation> m_sim;
};

double rest_volume(const TetMesh& mesh) {
  double v = 0.0;
  for (std::int32_t t = 0; t < mesh.num_tets(); ++t) v += mesh.rest_volume(t);
  return v;
}

}  // namespace

void bind_simulation(py::module_& m) {
  py::class_<PySimulation>(m, "Simulation", "A scene loaded, composed and stepped (docs/python.md)")
      .def(py::init<const std::string&, const py::dict&, std::optional<std::int64_t>,
                    std::optional<std::string>, bool>(),
           py::arg("scene"), py::arg("overrides") = py::dict(), py::arg("steps") = py::none(),
           py::arg("record") = py::none(), py::arg("validate_cuts") = false,
           "Load a scene TOML with overrides {'solver.tolerance': 1e-4}; raises InputError "
           "naming the file, key and line")
      .def("step", &PySimulation::step, py::arg("n") = 1, "Take n solver steps")
      .def_property_readonly(
          "time", [](const PySimulation& s) { return s.state().time_s; }, "Simulated time, s")
      .def_property_readonly(
          "steps", [](const PySimulation& s) { return s.state().step; }, "Solver steps taken")
      .def_property_readonly(
          "dt", [](PySimulation& s) { return s.sim().scene().settings.dt_s; }, "Solver step, s")
      .def_property_readonly(
          "state_hash", [](const PySimulation& s) { return app::hash_hex(state_hash(s.state())); },
          "The state hash, as the headless report's state_hash")
      .def_property_readonly(
          "positions", [](const PySimulation& s) { return vec3_array(s.state().mesh.x); },
          "(nodes, 3) float64 copy of the current positions, m")
      .def_property_readonly(
          "rest_positions", [](const PySimulation& s) { return vec3_array(s.state().mesh.rest); },
          "(nodes, 3) float64 copy of the rest positions, m")
      .def_property_readonly(
          "velocities", [](const PySimulation& s) { return vec3_array(s.state().mesh.v); },
          "(nodes, 3) float64 copy of the velocities, m/s")
      .def_property_readonly(
          "tets", [](const PySimulation& s) { return tets_array(s.state().mesh.tets); },
          "(tets, 4) int32 copy of the tets' node ids")
      .def_property_readonly(
          "groups", [](const PySimulation& s) { return groups_array(s.state().mesh.group); },
          "(tets,) int32 copy of each tet's group id")
      .def_property_readonly(
          "group_names", [](PySimulation& s) { return s.sim().assembled().group_names(); },
          "{group id: name}")
      .def_property_readonly(
          "rest_volume", [](const PySimulation& s) { return rest_volume(s.state().mesh); },
          "Total rest volume of the tets, m^3")
      .def_property_readonly(
          "tools",
          [](PySimulation& s) {
            std::vector<std::string> names;
            for (const Tool& t : s.sim().scene().tools) names.push_back(t.name);
            return names;
          },
          "The scene's tool names, in scene order")
      .def("tool", &PySimulation::tool, py::arg("name"),
           "A tool's pose as the solver last consumed it, its kind and device")
      .def("set_tool", &PySimulation::set_tool, py::arg("name"), py::arg("position") = py::none(),
           py::arg("orientation") = py::none(), py::arg("jaw") = py::none(),
           py::arg("buttons") = py::none(),
           "Pose a tool whose device is \"python\" for the next step (what is not given stays)")
      .def("cut", &PySimulation::cut, py::arg("polygon"),
           "Cut a convex polygon (k >= 3 points, m) through the cutting stage in one step")
      .def("snapshot", &PySimulation::snapshot, "The whole state as bytes")
      .def("restore", &PySimulation::restore, py::arg("snapshot"),
           "Restore a snapshot: the run goes on bit for bit")
      .def(
          "report", [](PySimulation& s) { return to_python(s.sim().report()); },
          "The headless report so far, as a dict")
      .def(
          "finish", [](PySimulation& s) { return to_python(s.sim().finish()); },
          "End the run (closes a recording) and return the whole report")
      .def("export", &PySimulation::export_mesh, py::arg("path"),
           "Write the current mesh: .msh, .vtu or .obj by the name")
      .def("__repr__", [](PySimulation& s) {
        return "<serosa.Simulation " + s.sim().scene().file.string() + " at step " +
               std::to_string(s.state().step) + ">";
      });
}

}  // namespace serosa::python
