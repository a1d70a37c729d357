// Conversions between the engine's arrays and Python's: numpy copies of node and tet arrays,
// JSON reports as dicts, Python values as TOML scene overrides, tool poses as dicts.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/math.h"
#include "engine/scene/scene_override.h"
#include "engine/tool_state.h"

namespace serosa::python {

namespace py = pybind11;

/// (n, 3) float64 copy of `v` (m, or m/s).
[[nodiscard]] py::array_t<double> vec3_array(std::span<const Vec3> v);
/// (m, 4) int32 copy of the tets' node ids.
[[nodiscard]] py::array_t<std::int32_t> tets_array(std::span<const Tet> tets);
/// (m,) int32 copy of each tet's group id.
[[nodiscard]] py::array_t<std::int32_t> groups_array(std::span<const std::uint16_t> groups);
/// (k, 3) points in m from any sequence of 3-sequences (a list, a numpy array). Throws
/// std::invalid_argument naming `what` on another shape.
[[nodiscard]] std::vector<Vec3> points_from(py::handle points, const std::string& what);

/// A JSON value as the Python value json.loads gives.
[[nodiscard]] py::object to_python(const nlohmann::json& j);
/// {"solver.tolerance": 1e-4, ...} as scene overrides: bool, int, float, str and lists of them.
/// Throws std::invalid_argument naming the key for another type.
[[nodiscard]] std::vector<SceneOverride> overrides_from(const py::dict& overrides);

/// A tool's pose as a dict: position (m), orientation (w, x, y, z), jaw (rad), buttons, time (s).
[[nodiscard]] py::dict tool_dict(const ToolState& t);

}  // namespace serosa::python
