// The module `serosa._serosa` (imported by serosa/__init__.py): the Simulation class, the mesh
// reader and checker, and InputError, which every bad input (scene, mesh, override) raises with
// the file, key and line in its message and as attributes.
#include <pybind11/stl.h>

#include "app/mesh_check_report.h"
#include "app/version.h"
#include "engine/input_error.h"
#include "python/convert.h"

namespace serosa::python {

void bind_simulation(py::module_& m);

namespace {

py::dict load_mesh(const std::string& path) {
  const app::CheckedMesh c = app::check_mesh_file(path);
  if (!c.report.valid)
    throw InputError(path, 0, c.report.problems.empty() ? "invalid" : c.report.problems.front(),
                     "a valid tet mesh (serosa.check_mesh lists every problem)");
  py::dict d;
  d["rest_positions"] = vec3_array(c.mesh.rest);
  d["tets"] = tets_array(c.mesh.tets);
  d["groups"] = groups_array(c.mesh.group);
  d["group_names"] = c.read.group_names;
  d["format"] = c.read.format;
  return d;
}

}  // namespace

}  // namespace serosa::python

PYBIND11_MODULE(_serosa, m) {
  namespace py = pybind11;
  using namespace serosa::python;
  m.doc() = "Serosa: corotational FEM and exact cutting of tet meshes (docs/python.md)";
  // A handle that outlives nothing it points to: the module keeps the type alive, and a handle
  // (unlike a static py::object) is never released after the interpreter has gone.
  static const py::handle input_error =
      py::exception<serosa::InputError>(m, "InputError", PyExc_ValueError).release();
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const serosa::InputError& e) {
      py::object exc = input_error(e.what());
      exc.attr("file") = e.file();
      exc.attr("line") = e.line();
      exc.attr("reason") = e.message();
      exc.attr("expected") = e.expected();
      PyErr_SetObject(input_error.ptr(), exc.ptr());
    }
  });
  m.def("version", [] { return std::string(serosa::app::version_string()); });
  m.def("load_mesh", &load_mesh, py::arg("path"),
        "Read a tet mesh: rest_positions (n, 3) m, tets (m, 4) int32, groups (m,) int32, "
        "group_names, format");
  m.def(
      "check_mesh",
      [](const std::string& path) {
        return to_python(serosa::app::check_json(path, serosa::app::check_mesh_file(path)));
      },
      py::arg("path"), "The checks of `serosa check --json`, as a dict");
  bind_simulation(m);
}
