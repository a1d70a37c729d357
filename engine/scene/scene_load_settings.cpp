// The scene's settings tables: [solver], [render] (and its looks), [record], [cutting] and
// [headless] (docs/scene-format.md).
#include "engine/scene/scene_loader.h"

#include <algorithm>
#include <limits>
#include <numbers>

namespace serosa::scene_detail {

void Loader::read_solver(const toml::table& t, SolverSettings& s) const {
  const std::string p = "solver";
  check_keys(
      t, p,
      {"kind", "tolerance", "max_iterations", "refresh_iterations", "factor_lag_steps", "threads",
       "after_cut", "urgent_lag_steps", "cut_lag_steps", "misfit_rad", "patch_rings"});
  if (const auto* n = t.get("kind")) {
    s.kind = enum_value<SolverKind>(*n, sub(p, "kind"), solver_kind_from_name,
                                    "pcg, cholmod, pcg-cholmod, pcg-lagged");
  }
  if (const auto* n = t.get("tolerance")) {
    s.tolerance =
        ranged(*n, sub(p, "tolerance"), 0.0, true, 1.0, true, "a relative residual in (0, 1)");
  }
  if (const auto* n = t.get("max_iterations")) {
    s.max_iterations = static_cast<int>(
        ranged_int(*n, sub(p, "max_iterations"), 1, 1000000, "an integer within [1, 1000000]"));
  }
  if (const auto* n = t.get("refresh_iterations")) {
    s.refresh_iterations = static_cast<int>(
        ranged_int(*n, sub(p, "refresh_iterations"), 0, 1000000, "an integer within [0, 1000000]"));
  }
  if (const auto* n = t.get("threads")) {
    s.threads = static_cast<int>(
        ranged_int(*n, sub(p, "threads"), 1, 256, "a number of threads within [1, 256]"));
  }
  if (const auto* n = t.get("urgent_lag_steps")) {
    s.urgent_lag_steps = static_cast<int>(ranged_int(*n, sub(p, "urgent_lag_steps"), 1, 10000,
                                                     "a number of steps within [1, 10000]"));
  }
  if (const auto* n = t.get("cut_lag_steps")) {
    s.cut_lag_steps = static_cast<int>(
        ranged_int(*n, sub(p, "cut_lag_steps"), 1, 10000, "a number of steps within [1, 10000]"));
  }
  if (const auto* n = t.get("misfit_rad")) {
    s.misfit_rad = ranged(*n, sub(p, "misfit_rad"), 0.0, false, std::numbers::pi, false,
                          "an angle within [0, pi] rad (0: never)");
  }
  if (const auto* n = t.get("patch_rings")) {
    s.patch_rings = static_cast<int>(
        ranged_int(*n, sub(p, "patch_rings"), 0, 8, "a number of rings within [0, 8]"));
  }
  if (const auto* n = t.get("after_cut")) {
    const std::string v = string(*n, sub(p, "after_cut"), "\"patch\" or \"factor\"");
    if (v != "patch" && v != "factor")
      fail(*n, sub(p, "after_cut"), "unknown value '" + v + "'", "\"patch\" or \"factor\"");
    s.patch_after_cut = v == "patch";
  }
  if (const auto* n = t.get("factor_lag_steps")) {
    s.factor_lag_steps = static_cast<int>(ranged_int(*n, sub(p, "factor_lag_steps"), 1, 10000,
                                                     "a number of steps within [1, 10000]"));
  }
}

// looks = { GROUP = "TISSUE", ... }: the group must be one the organs name (checked once all
// are read), the tissue one of kTissueLooks.
void Loader::read_looks(const toml::table& t, const std::string& p, RenderSettings& r) {
  std::string known;
  for (const std::string_view l : kTissueLooks)
    known += (known.empty() ? "" : ", ") + std::string(l);
  for (auto&& [key, value] : t) {
    const std::string kp = sub(p, key.str());
    const std::string& look = string(value, kp, "a tissue name (string)");
    if (std::find(kTissueLooks.begin(), kTissueLooks.end(), look) == kTissueLooks.end())
      fail(value, kp, "unknown tissue \"" + look + "\"", "one of: " + known);
    r.looks[std::string(key.str())] = look;
    m_group_refs.push_back({line_of(key), kp, std::string(key.str())});
  }
}

void Loader::read_render(const toml::table& t, RenderSettings& r) {
  const std::string p = "render";
  check_keys(t, p, {"tessellation", "shape_factor", "width", "height", "surroundings", "looks"});
  if (const auto* looks = opt_table(t, "looks", p)) read_looks(*looks, sub(p, "looks"), r);
  if (const auto* n = t.get("surroundings")) {
    r.surroundings = enum_value<Surroundings>(*n, sub(p, "surroundings"), surroundings_from_name,
                                              "none, abdomen");
    m_surroundings_line = line_of(*n);
  }
  if (const auto* n = t.get("tessellation")) {
    r.tessellation = static_cast<int>(
        ranged_int(*n, sub(p, "tessellation"), 1, 16, "a tessellation level within [1, 16]"));
  }
  if (const auto* n = t.get("shape_factor")) {
    r.shape_factor = ranged(*n, sub(p, "shape_factor"), 0.0, false, 1.0, false,
                            "a Phong shape factor within [0, 1]");
  }
  if (const auto* n = t.get("width")) {
    r.width =
        static_cast<int>(ranged_int(*n, sub(p, "width"), 1, 16384, "pixels within [1, 16384]"));
  }
  if (const auto* n = t.get("height")) {
    r.height =
        static_cast<int>(ranged_int(*n, sub(p, "height"), 1, 16384, "pixels within [1, 16384]"));
  }
}

void Loader::read_record(const toml::table& t, RecordSettings& r) const {
  const std::string p = "record";
  check_keys(t, p, {"path", "hash_every", "snapshot_every_s"});
  if (const auto* n = t.get("path")) {
    const std::string& rel = string(*n, sub(p, "path"), "a .lapr path relative to the scene");
    if (rel.empty()) fail(*n, sub(p, "path"), "empty path", "a .lapr path relative to the scene");
    r.path = resolve(rel);
  }
  if (const auto* n = t.get("hash_every")) {
    r.hash_every = ranged_int(*n, sub(p, "hash_every"), 1, std::numeric_limits<std::int64_t>::max(),
                              "a number of solver steps >= 1");
  }
  if (const auto* n = t.get("snapshot_every_s"))
    r.snapshot_every_s = ranged(*n, sub(p, "snapshot_every_s"), 0.0, false, 1e9, false,
                                "seconds >= 0 (0: no snapshots)");
}

void Loader::read_cutting(const toml::table& t, CuttingSettings& c) const {
  const std::string p = "cutting";
  check_keys(t, p, {"method", "tolerance", "strokes"});
  if (const auto* n = t.get("method")) {
    c.method =
        enum_value<CutMethod>(*n, sub(p, "method"), cut_method_from_name, "pattern, remove, snap");
  }
  if (const auto* n = t.get("tolerance")) {
    c.tolerance = ranged(*n, sub(p, "tolerance"), 0.0, false, 0.5, true,
                         "a tolerance relative to the tet's mean edge length within [0, 0.5)");
  }
  if (const auto* n = t.get("strokes")) {
    c.strokes = enum_value<StrokeSurfaceKind>(*n, sub(p, "strokes"), stroke_surface_from_name,
                                              "swept, plane");
  }
}

void Loader::read_headless(const toml::table& t, HeadlessSettings& h) const {
  const std::string p = "headless";
  check_keys(t, p, {"steps"});
  if (const auto* n = t.get("steps")) {
    h.steps = ranged_int(*n, sub(p, "steps"), 1, std::numeric_limits<std::int64_t>::max(),
                         "a number of solver steps >= 1");
  }
}

}  // namespace serosa::scene_detail
