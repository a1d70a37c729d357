#include "python/convert.h"

#include <pybind11/stl.h>

#include <cstdio>
#include <stdexcept>

namespace serosa::python {

py::array_t<double> vec3_array(std::span<const Vec3> v) {
  py::array_t<double> a({static_cast<py::ssize_t>(v.size()), py::ssize_t{3}});
  auto w = a.mutable_unchecked<2>();
  for (std::size_t i = 0; i < v.size(); ++i)
    for (py::ssize_t k = 0; k < 3; ++k) w(static_cast<py::ssize_t>(i), k) = v[i][k];
  return a;
}

py::array_t<std::int32_t> tets_array(std::span<const Tet> tets) {
  py::array_t<std::int32_t> a({static_cast<py::ssize_t>(tets.size()), py::ssize_t{4}});
  auto w = a.mutable_unchecked<2>();
  for (std::size_t i = 0; i < tets.size(); ++i)
    for (std::size_t k = 0; k < 4; ++k)
      w(static_cast<py::ssize_t>(i), static_cast<py::ssize_t>(k)) = tets[i][k];
  return a;
}

py::array_t<std::int32_t> groups_array(std::span<const std::uint16_t> groups) {
  py::array_t<std::int32_t> a(static_cast<py::ssize_t>(groups.size()));
  auto w = a.mutable_unchecked<1>();
  for (std::size_t i = 0; i < groups.size(); ++i) w(static_cast<py::ssize_t>(i)) = groups[i];
  return a;
}

std::vector<Vec3> points_from(py::handle points, const std::string& what) {
  std::vector<Vec3> out;
  for (py::handle p : points) {
    const auto xyz = py::cast<std::vector<double>>(p);
    if (xyz.size() != 3)
      throw std::invalid_argument(what + ": point " + std::to_string(out.size() + 1) + " has " +
                                  std::to_string(xyz.size()) +
                                  " coordinates, not 3 (x, y, z in m)");
    out.emplace_back(xyz[0], xyz[1], xyz[2]);
  }
  return out;
}

py::object to_python(const nlohmann::json& j) {
  return py::module_::import("json").attr("loads")(j.dump());
}

namespace {

// A Python value as TOML text.
std::string toml_text(py::handle v, const std::string& key) {
  if (py::isinstance<py::bool_>(v)) return v.cast<bool>() ? "true" : "false";
  if (py::isinstance<py::int_>(v)) return std::to_string(v.cast<long long>());
  if (py::isinstance<py::float_>(v)) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.17g", v.cast<double>());
    return buf;
  }
  if (py::isinstance<py::str>(v)) return nlohmann::json(v.cast<std::string>()).dump();
  if (py::isinstance<py::list>(v) || py::isinstance<py::tuple>(v)) {
    std::string s = "[";
    for (py::handle e : v) s.append(s.size() > 1 ? ", " : "").append(toml_text(e, key));
    return s + "]";
  }
  throw std::invalid_argument("override '" + key + "': a " +
                              py::str(py::type::of(v).attr("__name__")).cast<std::string>() +
                              " is not a scene value (bool, int, float, str or a list of them)");
}

}  // namespace

std::vector<SceneOverride> overrides_from(const py::dict& overrides) {
  std::vector<SceneOverride> out;
  for (const auto& [k, v] : overrides) {
    const auto key = py::str(k).cast<std::string>();
    out.push_back(parse_override(key + "=" + toml_text(v, key), "overrides"));
  }
  return out;
}

py::dict tool_dict(const ToolState& t) {
  py::dict d;
  d["position"] = py::make_tuple(t.tip_m[0], t.tip_m[1], t.tip_m[2]);
  d["orientation"] = py::make_tuple(t.quat_wxyz[0], t.quat_wxyz[1], t.quat_wxyz[2], t.quat_wxyz[3]);
  d["jaw"] = t.jaw_rad;
  d["buttons"] = t.buttons;
  d["time"] = t.time_s;
  return d;
}

}  // namespace serosa::python
