// load_scene / parse_scene_text: TOML -> validated Scene (docs/scene-format.md).
//
// Every table is checked against its list of allowed keys before its values are read, so a typo
// is an error that lists what was meant. Every error names the file, the line of the offending key
// or value (toml++ source regions) and the key path ("organ[0].young"); a missing key names the
// line of the table that should hold it.
#include <toml++/toml.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <initializer_list>
#include <limits>
#include <map>
#include <numbers>
#include <sstream>
#include <system_error>
#include <utility>

#include "engine/hook.h"
#include "engine/input_error.h"
#include "engine/presets.h"
#include "engine/scene.h"
#include "engine/tool_path.h"

namespace serosa {
namespace {

using Keys = std::initializer_list<std::string_view>;

std::string fmt_num(double v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

std::string join_keys(Keys keys) {
  std::string s;
  for (const auto k : keys) {
    if (!s.empty()) s += ", ";
    s += k;
  }
  return s;
}

std::string sub(const std::string& path, std::string_view key) {
  return path.empty() ? std::string(key) : path + "." + std::string(key);
}

std::string at(const std::string& path, std::size_t i) {
  return path + "[" + std::to_string(i) + "]";
}

std::int64_t line_of(const toml::node& n) {
  return static_cast<std::int64_t>(n.source().begin.line);
}
std::int64_t line_of(const toml::key& k) {
  return static_cast<std::int64_t>(k.source().begin.line);
}

std::string_view type_name(const toml::node& n) {
  switch (n.type()) {
    case toml::node_type::table:
      return "a table";
    case toml::node_type::array:
      return "an array";
    case toml::node_type::string:
      return "a string";
    case toml::node_type::integer:
      return "an integer";
    case toml::node_type::floating_point:
      return "a float";
    case toml::node_type::boolean:
      return "a boolean";
    case toml::node_type::date:
      return "a date";
    case toml::node_type::time:
      return "a time";
    case toml::node_type::date_time:
      return "a date-time";
    case toml::node_type::none:
      break;
  }
  return "nothing";
}

// Reads one scene document. One instance per load; holds the file name for errors, the folder
// relative paths resolve against, and what cross-table checks need.
class Loader {
 public:
  explicit Loader(const std::filesystem::path& scene_path)
      : m_file(scene_path.string()),
        m_dir(std::filesystem::absolute(scene_path).lexically_normal().parent_path()) {}

  Scene load(const std::string& text) {
    toml::table root;
    try {
      root = toml::parse(text, m_file);
    } catch (const toml::parse_error& e) {
      throw InputError(m_file, static_cast<std::int64_t>(e.source().begin.line),
                       "TOML syntax error: " + std::string(e.description()), "valid TOML");
    }

    Scene scene;
    scene.file = m_file;
    check_keys(root, "",
               {"scene", "organ", "support", "solver", "render", "tool", "record", "cutting",
                "headless", "metrics"});

    const toml::node* effects_node = nullptr;
    if (const auto* t = opt_table(root, "scene", "")) {
      read_scene(*t, scene, effects_node);
    }
    // The default solver, then presets; explicit [solver] and [render] keys, read below, win.
    scene.solver = scene_default_solver();
    if (scene.settings.quality && !scene.settings.accuracy_target) {
      scene.settings.accuracy_target = quality_accuracy_target(*scene.settings.quality);
    }
    if (const auto choice = scene_preset(scene.settings)) {
      apply_preset(*choice, scene.solver, scene.render);
    }
    read_organs(root, scene);
    read_supports(root, scene);
    if (const auto* t = opt_table(root, "solver", "")) read_solver(*t, scene.solver);
    if (const auto* t = opt_table(root, "render", "")) read_render(*t, scene.render);
    read_tools(root, scene);
    if (const auto* t = opt_table(root, "record", "")) read_record(*t, scene.record);
    if (const auto* t = opt_table(root, "cutting", "")) read_cutting(*t, scene.cutting);
    if (const auto* t = opt_table(root, "headless", "")) read_headless(*t, scene.headless);
    if (const auto* t = opt_table(root, "metrics", "")) read_metrics(*t, scene.metrics);
    check_dependencies(scene, effects_node);
    check_group_refs(scene);
    check_rubric(scene);
    return scene;
  }

 private:
  // ---- errors ----

  [[noreturn]] void fail(std::int64_t line, const std::string& path, const std::string& message,
                         const std::string& expected) const {
    throw InputError(m_file, line, path.empty() ? message : path + ": " + message, expected);
  }
  [[noreturn]] void fail(const toml::node& n, const std::string& path, const std::string& message,
                         const std::string& expected) const {
    fail(line_of(n), path, message, expected);
  }

  // Every key of t must be in `allowed`.
  void check_keys(const toml::table& t, const std::string& path, Keys allowed) const {
    for (auto&& [key, value] : t) {
      bool known = false;
      for (const auto a : allowed) known = known || key.str() == a;
      if (!known) {
        fail(line_of(key), sub(path, key.str()), "unknown key", "one of: " + join_keys(allowed));
      }
    }
  }

  // ---- typed access ----

  const toml::table* opt_table(const toml::table& t, std::string_view key,
                               const std::string& path) const {
    const toml::node* n = t.get(key);
    if (n == nullptr) return nullptr;
    if (!n->is_table()) {
      fail(*n, sub(path, key), std::string("expected a table, got ") + std::string(type_name(*n)),
           "a table [" + sub(path, key) + "] or { ... }");
    }
    return n->as_table();
  }

  const toml::node& required(const toml::table& t, std::string_view key, const std::string& path,
                             const std::string& expected) const {
    const toml::node* n = t.get(key);
    if (n == nullptr) fail(line_of(t), sub(path, key), "missing required key", expected);
    return *n;
  }

  double number(const toml::node& n, const std::string& path, const std::string& expected) const {
    double v = 0.0;
    if (const auto* f = n.as_floating_point()) {
      v = f->get();
    } else if (const auto* i = n.as_integer()) {
      v = static_cast<double>(i->get());
    } else {
      fail(n, path, "expected a number, got " + std::string(type_name(n)), expected);
    }
    if (!std::isfinite(v)) fail(n, path, "must be finite, got " + fmt_num(v), expected);
    return v;
  }

  std::int64_t integer(const toml::node& n, const std::string& path,
                       const std::string& expected) const {
    const auto* i = n.as_integer();
    if (i == nullptr)
      fail(n, path, "expected an integer, got " + std::string(type_name(n)), expected);
    return i->get();
  }

  const std::string& string(const toml::node& n, const std::string& path,
                            const std::string& expected) const {
    const auto* s = n.as_string();
    if (s == nullptr)
      fail(n, path, "expected a string, got " + std::string(type_name(n)), expected);
    return s->get();
  }

  const toml::array& array(const toml::node& n, const std::string& path,
                           const std::string& expected) const {
    const auto* a = n.as_array();
    if (a == nullptr)
      fail(n, path, "expected an array, got " + std::string(type_name(n)), expected);
    return *a;
  }

  Vec3 vec3(const toml::node& n, const std::string& path, const std::string& expected) const {
    const toml::array& a = array(n, path, expected);
    if (a.size() != 3) {
      fail(n, path, "expected 3 numbers, got " + std::to_string(a.size()), expected);
    }
    Vec3 v;
    for (std::size_t i = 0; i < 3; ++i)
      v[static_cast<Eigen::Index>(i)] = number(a[i], at(path, i), expected);
    return v;
  }

  // A number in [lo, hi] (bounds open where the flag says so).
  double ranged(const toml::node& n, const std::string& path, double lo, bool lo_open, double hi,
                bool hi_open, const std::string& expected) const {
    const double v = number(n, path, expected);
    const bool lo_ok = lo_open ? v > lo : v >= lo;
    const bool hi_ok = hi_open ? v < hi : v <= hi;
    if (!lo_ok)
      fail(n, path,
           "must be " + std::string(lo_open ? "> " : ">= ") + fmt_num(lo) + ", got " + fmt_num(v),
           expected);
    if (!hi_ok)
      fail(n, path,
           "must be " + std::string(hi_open ? "< " : "<= ") + fmt_num(hi) + ", got " + fmt_num(v),
           expected);
    return v;
  }

  std::int64_t ranged_int(const toml::node& n, const std::string& path, std::int64_t lo,
                          std::int64_t hi, const std::string& expected) const {
    const std::int64_t v = integer(n, path, expected);
    if (v < lo || v > hi) {
      fail(n, path,
           "must be within [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " +
               std::to_string(v),
           expected);
    }
    return v;
  }

  // A string naming one enum value; `from_name` maps it, `names` lists the allowed spellings.
  template <class E, class F>
  E enum_value(const toml::node& n, const std::string& path, F from_name,
               const std::string& names) const {
    const std::string& s = string(n, path, "one of: " + names);
    const std::optional<E> e = from_name(s);
    if (!e) fail(n, path, "unknown value \"" + s + "\"", "one of: " + names);
    return *e;
  }

  // A path relative to the scene file's folder (absolute paths stay as they are).
  std::filesystem::path resolve(const std::string& rel) const {
    return (m_dir / std::filesystem::path(rel)).lexically_normal();
  }

  // An existing regular file, named by the string at node n.
  std::filesystem::path existing_file(const toml::node& n, const std::string& path,
                                      const std::string& rel, const std::string& what) const {
    if (rel.empty()) fail(n, path, "empty path", what + " path relative to the scene file");
    const std::filesystem::path p = resolve(rel);
    std::error_code ec;
    if (!std::filesystem::is_regular_file(p, ec)) {
      fail(n, path, what + " \"" + rel + "\" not found (looked for " + p.string() + ")",
           "an existing " + what + " path relative to the scene file");
    }
    return p;
  }

  // ---- [scene] ----

  void read_scene(const toml::table& t, Scene& scene, const toml::node*& effects_node) const {
    const std::string p = "scene";
    check_keys(t, p, {"dt", "gravity", "effects", "quality", "accuracy_target"});
    SceneSettings& s = scene.settings;
    if (const auto* n = t.get("dt")) {
      s.dt_s = ranged(*n, sub(p, "dt"), 0.0, true, 1.0, false, "a solver step in s, 0 < dt <= 1");
    }
    if (const auto* n = t.get("gravity")) {
      s.gravity_mps2 = vec3(*n, sub(p, "gravity"), "[x, y, z] in m/s^2");
    }
    if (const auto* n = t.get("quality")) {
      s.quality =
          enum_value<Quality>(*n, sub(p, "quality"), quality_from_name, "fast, balanced, accurate");
    }
    if (const auto* n = t.get("accuracy_target")) {
      s.accuracy_target = ranged(*n, sub(p, "accuracy_target"), 0.0, true, 1.0, true,
                                 "a relative displacement error in (0, 1), e.g. 0.01");
    }
    if (const auto* n = t.get("effects")) {
      effects_node = n;
      const std::string all = [] {
        std::string names;
        for (const Effect e : kAllEffects)
          names += (names.empty() ? "" : ", ") + std::string(effect_name(e));
        return names;
      }();
      const toml::array& a = array(*n, sub(p, "effects"), "an array of effect names");
      s.effects.clear();
      for (std::size_t i = 0; i < a.size(); ++i) {
        const std::string ip = at(sub(p, "effects"), i);
        const Effect e = enum_value<Effect>(a[i], ip, effect_from_name, all);
        if (!s.effects.insert(e).second) {
          fail(a[i], ip, "effect \"" + std::string(effect_name(e)) + "\" listed twice",
               "each effect at most once");
        }
      }
    }
  }

  // ---- [[organ]] ----

  // Reads the material keys present in t into m (absent keys keep m's values).
  void read_material(const toml::table& t, const std::string& p, Material& m) const {
    if (const auto* n = t.get("young")) {
      m.young_pa = ranged(*n, sub(p, "young"), 0.0, true, std::numeric_limits<double>::infinity(),
                          false, "Young's modulus in Pa > 0");
    }
    if (const auto* n = t.get("poisson")) {
      m.poisson =
          ranged(*n, sub(p, "poisson"), -1.0, true, 0.5, true,
                 "Poisson's ratio in (-1, 0.5); 0.5 is incompressible and locks linear tets");
    }
    if (const auto* n = t.get("density")) {
      m.density_kgpm3 =
          ranged(*n, sub(p, "density"), 0.0, true, std::numeric_limits<double>::infinity(), false,
                 "density in kg/m^3 > 0");
    }
    const double inf = std::numeric_limits<double>::infinity();
    if (const auto* n = opt_table(t, "damping", p)) {
      const std::string dp = sub(p, "damping");
      check_keys(*n, dp, {"mass", "stiffness"});
      if (const auto* v = n->get("mass")) {
        m.damping.mass_per_s = ranged(*v, sub(dp, "mass"), 0.0, false, inf, false,
                                      "Rayleigh mass coefficient in 1/s >= 0");
      }
      if (const auto* v = n->get("stiffness")) {
        m.damping.stiffness_s = ranged(*v, sub(dp, "stiffness"), 0.0, false, inf, false,
                                       "Rayleigh stiffness coefficient in s >= 0");
      }
    }
    if (const auto* n = opt_table(t, "plasticity", p)) {
      const std::string pp = sub(p, "plasticity");
      check_keys(*n, pp, {"yield", "creep", "max"});
      if (const auto* v = n->get("yield")) {
        m.plasticity.yield = ranged(*v, sub(pp, "yield"), 0.0, false, inf, false,
                                    "elastic limit (strain norm) >= 0");
      }
      if (const auto* v = n->get("creep")) {
        m.plasticity.creep_per_s =
            ranged(*v, sub(pp, "creep"), 0.0, false, inf, false, "creep rate in 1/s >= 0");
      }
      if (const auto* v = n->get("max")) {
        m.plasticity.max =
            ranged(*v, sub(pp, "max"), 0.0, false, inf, false, "plastic strain norm cap >= 0");
      }
    }
  }

  // A group named by a key or value: an integer id (taken as is), or a name from `groups`.
  int group_ref(const Organ& organ, const std::string& ref, std::int64_t line,
                const std::string& path) const {
    int id = 0;
    const auto r = std::from_chars(ref.data(), ref.data() + ref.size(), id);
    if (!ref.empty() && r.ec == std::errc() && r.ptr == ref.data() + ref.size()) {
      if (id < 0 || id > 65535) {
        fail(line, path, "group id " + ref + " out of range", "a group id within [0, 65535]");
      }
      return id;
    }
    if (const auto g = organ.group_id(ref)) return *g;
    std::string names;
    for (const auto& [gid, gname] : organ.groups) names += (names.empty() ? "" : ", ") + gname;
    fail(line, path, "unknown group \"" + ref + "\"",
         names.empty() ? std::string("a group id (this organ names no groups)")
                       : "a group id or one of: " + names);
  }

  void read_organs(const toml::table& root, Scene& scene) {
    const toml::node* n = root.get("organ");
    const std::string expected = "one or more [[organ]] tables";
    if (n == nullptr) fail(0, "organ", "the scene has no organ", expected);
    const auto* arr = n->as_array();
    if (arr != nullptr && arr->empty()) fail(*n, "organ", "the scene has no organ", expected);
    if (arr == nullptr || !arr->is_array_of_tables()) {
      fail(*n, "organ", "expected an array of tables [[organ]], got " + std::string(type_name(*n)),
           expected);
    }
    std::map<int, std::size_t> group_owner;  // group id -> organ index (ids are scene-wide)
    for (std::size_t i = 0; i < arr->size(); ++i) {
      const toml::table& t = *(*arr)[i].as_table();
      const std::string p = at("organ", i);
      check_keys(t, p,
                 {"name", "mesh", "groups", "young", "poisson", "density", "damping", "plasticity",
                  "material", "fixed", "transform"});
      Organ organ;

      // name, mesh
      const toml::node& name_node = required(t, "name", p, "an organ name (string)");
      organ.name = string(name_node, sub(p, "name"), "an organ name (string)");
      if (organ.name.empty()) fail(name_node, sub(p, "name"), "empty name", "a non-empty name");
      for (std::size_t j = 0; j < scene.organs.size(); ++j) {
        if (scene.organs[j].name == organ.name) {
          fail(
              name_node, sub(p, "name"),
              "duplicate organ name \"" + organ.name + "\" (also organ[" + std::to_string(j) + "])",
              "unique organ names");
        }
      }
      const toml::node& mesh_node = required(t, "mesh", p, "a mesh file path (string)");
      organ.mesh = existing_file(mesh_node, sub(p, "mesh"),
                                 string(mesh_node, sub(p, "mesh"), "a mesh file path (string)"),
                                 "mesh file");

      // groups = { 1 = "appendix", ... }
      if (const auto* g = opt_table(t, "groups", p)) {
        const std::string gp = sub(p, "groups");
        for (auto&& [key, value] : *g) {
          const std::string kp = sub(gp, key.str());
          int id = 0;
          const std::string_view k = key.str();
          const auto r = std::from_chars(k.data(), k.data() + k.size(), id);
          if (k.empty() || r.ec != std::errc() || r.ptr != k.data() + k.size() || id < 0 ||
              id > 65535) {
            fail(line_of(key), kp, "group key \"" + std::string(k) + "\" is not a group id",
                 "an integer group id (Gmsh physical tag) within [0, 65535]");
          }
          const std::string& gname = string(value, kp, "a group name (string)");
          if (gname.empty()) fail(value, kp, "empty group name", "a non-empty name");
          if (organ.group_id(gname)) {
            fail(value, kp, "group name \"" + gname + "\" used twice", "unique group names");
          }
          if (const auto owner = group_owner.find(id); owner != group_owner.end()) {
            fail(line_of(key), kp,
                 "group id " + std::to_string(id) + " already belongs to organ[" +
                     std::to_string(owner->second) + "]",
                 "group ids unique across organs (all organs share one mesh)");
          }
          organ.groups[id] = gname;
        }
        for (const auto& [id, gname] : organ.groups) group_owner[id] = scene.organs.size();
      }

      // material: organ-wide keys, then per-group overrides [organ.material.GROUP]
      read_material(t, p, organ.material);
      if (const auto* mt = opt_table(t, "material", p)) {
        const std::string mp = sub(p, "material");
        for (auto&& [key, value] : *mt) {
          const std::string kp = sub(mp, key.str());
          const int id = group_ref(organ, std::string(key.str()), line_of(key), kp);
          const auto* gt = value.as_table();
          if (gt == nullptr) {
            fail(value, kp, "expected a table, got " + std::string(type_name(value)),
                 "a material table { young = ..., poisson = ... }");
          }
          check_keys(*gt, kp, {"young", "poisson", "density", "damping", "plasticity"});
          if (organ.group_materials.count(id) != 0) {
            fail(line_of(key), kp, "group " + std::to_string(id) + " has two material tables",
                 "one material table per group");
          }
          Material m = organ.material;
          read_material(*gt, kp, m);
          organ.group_materials[id] = m;
        }
      }

      if (const auto* ft = opt_table(t, "fixed", p)) read_fixed(*ft, sub(p, "fixed"), organ);
      if (const auto* tt = opt_table(t, "transform", p)) {
        read_transform(*tt, sub(p, "transform"), organ.transform);
      }
      scene.organs.push_back(std::move(organ));
    }
  }

  void read_fixed(const toml::table& t, const std::string& p, Organ& organ) const {
    check_keys(t, p, {"box", "groups", "nodes"});
    if (const auto* n = t.get("box")) {
      const std::string bp = sub(p, "box");
      const std::string expected = "[[xmin, ymin, zmin], [xmax, ymax, zmax]] in m";
      const toml::array& a = array(*n, bp, expected);
      if (a.size() != 2)
        fail(*n, bp, "expected 2 corners, got " + std::to_string(a.size()), expected);
      Box box;
      box.min_m = vec3(a[0], at(bp, 0), expected);
      box.max_m = vec3(a[1], at(bp, 1), expected);
      if ((box.min_m.array() > box.max_m.array()).any()) {
        fail(*n, bp, "min corner exceeds max corner", expected);
      }
      organ.fixed.box = box;
    }
    if (const auto* n = t.get("groups")) {
      const std::string gp = sub(p, "groups");
      const toml::array& a = array(*n, gp, "an array of group names or ids");
      for (std::size_t i = 0; i < a.size(); ++i) {
        const std::string ip = at(gp, i);
        int id = 0;
        if (a[i].is_integer()) {
          id = static_cast<int>(ranged_int(a[i], ip, 0, 65535, "a group id within [0, 65535]"));
        } else {
          id = group_ref(organ, string(a[i], ip, "a group name or id"), line_of(a[i]), ip);
        }
        organ.fixed.groups.push_back(id);
      }
      std::sort(organ.fixed.groups.begin(), organ.fixed.groups.end());
      organ.fixed.groups.erase(std::unique(organ.fixed.groups.begin(), organ.fixed.groups.end()),
                               organ.fixed.groups.end());
    }
    if (const auto* n = t.get("nodes")) {
      const std::string np = sub(p, "nodes");
      const toml::array& a = array(*n, np, "an array of 0-based node ids");
      for (std::size_t i = 0; i < a.size(); ++i) {
        organ.fixed.nodes.push_back(static_cast<std::int32_t>(
            ranged_int(a[i], at(np, i), 0, std::numeric_limits<std::int32_t>::max(),
                       "a 0-based node id (mesh file order)")));
      }
      std::sort(organ.fixed.nodes.begin(), organ.fixed.nodes.end());
      organ.fixed.nodes.erase(std::unique(organ.fixed.nodes.begin(), organ.fixed.nodes.end()),
                              organ.fixed.nodes.end());
    }
  }

  void read_transform(const toml::table& t, const std::string& p, OrganTransform& tr) const {
    check_keys(t, p, {"translate", "rotate_deg", "scale"});
    if (const auto* n = t.get("translate")) {
      tr.translate_m = vec3(*n, sub(p, "translate"), "[x, y, z] in m");
    }
    if (const auto* n = t.get("rotate_deg")) {
      tr.rotate_deg = vec3(*n, sub(p, "rotate_deg"), "[rx, ry, rz] in degrees");
    }
    if (const auto* n = t.get("scale")) {
      tr.scale = ranged(*n, sub(p, "scale"), 0.0, true, std::numeric_limits<double>::infinity(),
                        false, "a uniform scale factor > 0");
    }
  }

  // ---- [solver] [render] [record] [cutting] [headless] ----

  void read_solver(const toml::table& t, SolverSettings& s) const {
    const std::string p = "solver";
    check_keys(t, p,
               {"kind", "tolerance", "max_iterations", "refresh_iterations", "factor_lag_steps",
                "threads", "after_cut", "urgent_lag_steps", "cut_lag_steps", "misfit_rad"});
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
      s.refresh_iterations = static_cast<int>(ranged_int(
          *n, sub(p, "refresh_iterations"), 0, 1000000, "an integer within [0, 1000000]"));
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
  void read_looks(const toml::table& t, const std::string& p, RenderSettings& r) {
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

  void read_render(const toml::table& t, RenderSettings& r) {
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

  void read_record(const toml::table& t, RecordSettings& r) const {
    const std::string p = "record";
    check_keys(t, p, {"path", "hash_every", "snapshot_every_s"});
    if (const auto* n = t.get("path")) {
      const std::string& rel = string(*n, sub(p, "path"), "a .lapr path relative to the scene");
      if (rel.empty()) fail(*n, sub(p, "path"), "empty path", "a .lapr path relative to the scene");
      r.path = resolve(rel);
    }
    if (const auto* n = t.get("hash_every")) {
      r.hash_every =
          ranged_int(*n, sub(p, "hash_every"), 1, std::numeric_limits<std::int64_t>::max(),
                     "a number of solver steps >= 1");
    }
    if (const auto* n = t.get("snapshot_every_s"))
      r.snapshot_every_s = ranged(*n, sub(p, "snapshot_every_s"), 0.0, false, 1e9, false,
                                  "seconds >= 0 (0: no snapshots)");
  }

  void read_cutting(const toml::table& t, CuttingSettings& c) const {
    const std::string p = "cutting";
    check_keys(t, p, {"method", "tolerance", "strokes"});
    if (const auto* n = t.get("method")) {
      c.method = enum_value<CutMethod>(*n, sub(p, "method"), cut_method_from_name,
                                       "pattern, remove, snap");
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

  void read_headless(const toml::table& t, HeadlessSettings& h) const {
    const std::string p = "headless";
    check_keys(t, p, {"steps"});
    if (const auto* n = t.get("steps")) {
      h.steps = ranged_int(*n, sub(p, "steps"), 1, std::numeric_limits<std::int64_t>::max(),
                           "a number of solver steps >= 1");
    }
  }

  void read_metrics(const toml::table& t, MetricsSettings& m) {
    const std::string p = "metrics";
    check_keys(t, p,
               {"planned_cut", "cut_band", "force_limit", "tear_stress", "view_targets", "artery",
                "protected", "clip_target", "transfer", "procedure", "rubric"});
    if (const auto* n = t.get("transfer")) read_transfer(*n, sub(p, "transfer"), m);
    if (const auto* n = t.get("procedure")) read_procedure(*n, sub(p, "procedure"), m);
    if (const auto* n = t.get("artery")) {
      m.artery = string(*n, sub(p, "artery"), "a group name");
      m_group_refs.push_back({line_of(*n), sub(p, "artery"), *m.artery});
    }
    if (const auto* n = t.get("clip_target")) {
      m.clip_target_m = vec3(*n, sub(p, "clip_target"), "[x, y, z] in m (at rest)");
      m_clip_target_line = line_of(*n);
    }
    if (const auto* n = t.get("protected")) {
      const std::string expected = "a list of group names";
      const toml::array& a = array(*n, sub(p, "protected"), expected);
      for (std::size_t i = 0; i < a.size(); ++i) {
        m.protected_groups.push_back(string(a[i], at(sub(p, "protected"), i), expected));
        m_group_refs.push_back(
            {line_of(a[i]), at(sub(p, "protected"), i), m.protected_groups.back()});
      }
    }
    if (const auto* n = t.get("planned_cut")) {
      const std::string expected = "a polyline [[x, y, z], [x, y, z], ...] of >= 2 points in m";
      const auto* a = n->as_array();
      if (a == nullptr || a->size() < 2)
        fail(*n, sub(p, "planned_cut"), "not a polyline", expected);
      for (std::size_t i = 0; i < a->size(); ++i)
        m.planned_cut_m.push_back(vec3((*a)[i], at(sub(p, "planned_cut"), i), expected));
    }
    if (const auto* n = t.get("view_targets")) {
      const std::string expected = "a list of points [[x, y, z], ...] (at least one) in m";
      const auto* a = n->as_array();
      if (a == nullptr || a->empty()) fail(*n, sub(p, "view_targets"), "not a list", expected);
      for (std::size_t i = 0; i < a->size(); ++i)
        m.view_targets_m.push_back(vec3((*a)[i], at(sub(p, "view_targets"), i), expected));
    }
    if (const auto* n = t.get("cut_band")) {
      m.cut_band_m = ranged(*n, sub(p, "cut_band"), 0.0, true,
                            std::numeric_limits<double>::infinity(), false, "a distance > 0 in m");
    }
    if (const auto* n = t.get("tear_stress"))
      m.tear_stress_pa =
          ranged(*n, sub(p, "tear_stress"), 0.0, true, std::numeric_limits<double>::infinity(),
                 false, "a stress > 0 in Pa");
    if (const auto* n = t.get("force_limit")) {
      m.force_limit_n = ranged(*n, sub(p, "force_limit"), 0.0, true,
                               std::numeric_limits<double>::infinity(), false, "a force > 0 in N");
    }
    if (const auto* n = t.get("rubric")) {
      const std::string rel = string(*n, sub(p, "rubric"), "a rubric file's path");
      m.rubric = load_rubric(resolve(rel));
      m_rubric_line = line_of(*n);
    }
  }

  void read_transfer(const toml::node& n, const std::string& p, MetricsSettings& m) {
    const auto* t = n.as_table();
    if (t == nullptr)
      fail(n, p, "not a table", "{ object = \"group\", target = [x, y, z], radius = r }");
    check_keys(*t, p, {"object", "target", "radius"});
    TransferSettings s;
    const toml::node& object = required(*t, "object", p, "a group name");
    s.object = string(object, sub(p, "object"), "a group name");
    m_group_refs.push_back({line_of(object), sub(p, "object"), s.object});
    s.target_m =
        vec3(required(*t, "target", p, "[x, y, z] in m"), sub(p, "target"), "[x, y, z] in m");
    if (const auto* r = t->get("radius"))
      s.radius_m = ranged(*r, sub(p, "radius"), 0.0, true, std::numeric_limits<double>::infinity(),
                          false, "a radius > 0 in m");
    m.transfer = s;
  }

  void read_procedure(const toml::node& n, const std::string& p, MetricsSettings& m) {
    const std::string expected = "{ specimen = GROUP, base = GROUP, mesentery = GROUP }";
    const auto* t = n.as_table();
    if (t == nullptr) fail(n, p, "expected a table, got " + std::string(type_name(n)), expected);
    check_keys(*t, p, {"specimen", "base", "mesentery"});
    ProcedureGroups g;
    for (auto [key, out] : {std::pair<const char*, std::string*>{"specimen", &g.specimen},
                            {"base", &g.base},
                            {"mesentery", &g.mesentery}}) {
      const toml::node& v = required(*t, key, p, "a group name");
      *out = string(v, sub(p, key), "a group name");
      m_group_refs.push_back({line_of(v), sub(p, key), *out});
    }
    m.procedure = g;
    m_procedure_line = line_of(n);
  }

  // The rubric's metrics name tools and groups of this scene, and some need an effect or a key.
  void check_rubric(const Scene& scene) const {
    if (!scene.metrics.rubric) return;
    const std::string p = "metrics.rubric";
    std::size_t hands = 0;
    for (const Tool& tool : scene.tools) hands += tool.kind != ToolKind::kEndoscope ? 1 : 0;
    for (const RubricMetric& m : scene.metrics.rubric->metrics) {
      std::string family, suffix;
      (void)known_metric(m.name, family, suffix);
      const std::string what = "the rubric's metric '" + m.name + "' (" +
                               scene.metrics.rubric->file.string() + ":" + std::to_string(m.line) +
                               ")";
      const bool tool = std::any_of(scene.tools.begin(), scene.tools.end(),
                                    [&](const Tool& x) { return x.name == suffix; });
      if ((family == "path_length_m" || family == "force_max_n") && !suffix.empty() && !tool)
        fail(m_rubric_line, p, what + " names no tool of this scene", "a [[tool]] name");
      if ((family == "force_max_n" || family == "force_over_s") &&
          !scene.settings.has(Effect::kContact))
        fail(m_rubric_line, p, what + " needs effect \"contact\"", "\"contact\" listed");
      if (family.rfind("cut.", 0) == 0 && scene.metrics.planned_cut_m.empty())
        fail(m_rubric_line, p, what + " needs a planned cut", "metrics.planned_cut");
      if (family == "bimanual_fraction" && hands < 2)
        fail(m_rubric_line, p, what + " needs two hand instruments", "two non-endoscope tools");
      if (family == "pieces" && !has_group(scene, suffix))
        fail(m_rubric_line, p, what + " names no group of this scene", "an organ's group name");
      const bool scope = std::any_of(scene.tools.begin(), scene.tools.end(),
                                     [](const Tool& x) { return x.kind == ToolKind::kEndoscope; });
      if ((family == "out_of_view_s" || family.rfind("targets_", 0) == 0) && !scope)
        fail(m_rubric_line, p, what + " needs an endoscope", "a [[tool]] of kind endoscope");
      if (family == "out_of_view_s" && !suffix.empty() && !tool)
        fail(m_rubric_line, p, what + " names no tool of this scene", "a [[tool]] name");
      if (family.rfind("targets_", 0) == 0 && scene.metrics.view_targets_m.empty())
        fail(m_rubric_line, p, what + " needs targets to look at", "metrics.view_targets");
      if (family == "bleeding_events" && !scene.metrics.artery)
        fail(m_rubric_line, p, what + " needs an artery to watch", "metrics.artery");
      if (family == "thermal_injuries" && scene.metrics.protected_groups.empty())
        fail(m_rubric_line, p, what + " needs protected tissue to watch", "metrics.protected");
      const bool steps = family.rfind("procedure.", 0) == 0 ||
                         family == "transections_above_securing" || family == "specimens_dropped";
      if (steps && !scene.metrics.procedure)
        fail(m_rubric_line, p, what + " needs the procedure's steps followed", "metrics.procedure");
      check_rubric_task(scene, family, suffix, what);
    }
  }

  // The families the curriculum's tasks add: the procedure's steps, clips.
  void check_rubric_task(const Scene& scene, const std::string& family, const std::string& suffix,
                         const std::string& what) const {
    const std::string p = "metrics.rubric";
    if (family == "step_time_s" || family == "step_path_length_m") {
      if (!scene.metrics.procedure)
        fail(m_rubric_line, p, what + " needs the procedure's steps followed", "metrics.procedure");
      if (std::find(kProcedureSteps.begin(), kProcedureSteps.end(), suffix) ==
          kProcedureSteps.end())
        fail(m_rubric_line, p, what + " names no step of the procedure",
             "expose, divide_mesentery, secure_base, transect or extract");
    }
    const bool clips = family == "clips_on_artery" || family == "clips_off_artery" ||
                       family == "clip_target_error_m";
    if (clips && !scene.settings.has(Effect::kClips))
      fail(m_rubric_line, p, what + " needs effect \"clips\"", "\"clips\" listed");
    if (clips && !scene.metrics.artery)
      fail(m_rubric_line, p, what + " needs an artery to watch", "metrics.artery");
    if (family == "clip_target_error_m" && !scene.metrics.clip_target_m)
      fail(m_rubric_line, p, what + " needs where the clip should go", "metrics.clip_target");
    if (family == "tears" && !scene.metrics.tear_stress_pa)
      fail(m_rubric_line, p, what + " needs the stress at which tissue tears",
           "metrics.tear_stress");
    if (family.rfind("transfer.", 0) == 0 && !scene.metrics.transfer)
      fail(m_rubric_line, p, what + " needs a transfer to follow", "metrics.transfer");
    if (family.rfind("transfer.", 0) == 0 && !scene.settings.has(Effect::kContact))
      fail(m_rubric_line, p, what + " needs effect \"contact\" (grasps)", "\"contact\" listed");
  }

  static bool has_group(const Scene& scene, const std::string& name) {
    for (const Organ& o : scene.organs)
      for (const auto& [id, g] : o.groups)
        if (g == name) return true;
    return false;
  }

  // ---- [[support]] ----

  void read_supports(const toml::table& root, Scene& scene) {
    const toml::node* n = root.get("support");
    if (n == nullptr) return;
    const auto* arr = n->as_array();
    if (arr == nullptr || !arr->is_array_of_tables() || arr->empty()) {
      fail(*n, "support", "expected an array of tables, got " + std::string(type_name(*n)),
           "[[support]] tables");
    }
    m_support_line = line_of(*n);
    for (std::size_t i = 0; i < arr->size(); ++i) {
      const toml::table& t = *(*arr)[i].as_table();
      const std::string p = at("support", i);
      check_keys(t, p, {"name", "point", "normal"});
      Support s;
      const toml::node& name_node = required(t, "name", p, "a support name (string)");
      s.name = string(name_node, sub(p, "name"), "a support name (string)");
      for (const Support& other : scene.supports)
        if (other.name == s.name)
          fail(name_node, sub(p, "name"), "duplicate support name \"" + s.name + "\"",
               "unique support names");
      s.point_m =
          vec3(required(t, "point", p, "[x, y, z] in m"), sub(p, "point"), "[x, y, z] in m");
      const toml::node& nn = required(t, "normal", p, "a direction [x, y, z]");
      const Vec3 normal = vec3(nn, sub(p, "normal"), "a direction [x, y, z]");
      if (!(normal.norm() > 1e-12))
        fail(nn, sub(p, "normal"), "zero normal", "a non-zero direction [x, y, z]");
      s.normal = normal.normalized();
      scene.supports.push_back(std::move(s));
    }
  }

  // ---- [[tool]] ----

  const ToolPath& tool_path(const std::filesystem::path& file) {
    auto it = m_paths.find(file);
    if (it == m_paths.end()) it = m_paths.emplace(file, read_tool_path(file)).first;
    return it->second;
  }

  void read_tools(const toml::table& root, Scene& scene) {
    const toml::node* n = root.get("tool");
    if (n == nullptr) return;
    const auto* arr = n->as_array();
    if (arr != nullptr && arr->empty()) return;
    if (arr == nullptr || !arr->is_array_of_tables()) {
      fail(*n, "tool", "expected an array of tables, got " + std::string(type_name(*n)),
           "[[tool]] tables");
    }
    for (std::size_t i = 0; i < arr->size(); ++i) {
      const toml::table& t = *(*arr)[i].as_table();
      const std::string p = at("tool", i);
      check_keys(t, p, {"name", "kind", "device", "hand", "trocar"});
      Tool tool;
      const toml::node& name_node = required(t, "name", p, "a tool name (string)");
      tool.name = string(name_node, sub(p, "name"), "a tool name (string)");
      if (tool.name.empty() || tool.name.find_first_of(", \t\r\n") != std::string::npos) {
        fail(name_node, sub(p, "name"), "bad tool name \"" + tool.name + "\"",
             "a non-empty name without commas or spaces (it is a tool path CSV column)");
      }
      if (const auto j = scene.tool_index(tool.name)) {
        fail(name_node, sub(p, "name"),
             "duplicate tool name \"" + tool.name + "\" (also tool[" + std::to_string(*j) + "])",
             "unique tool names");
      }
      const std::string kinds = "scissors, grasper, endoscope, clip-applier, hook, endoloop";
      tool.kind = enum_value<ToolKind>(required(t, "kind", p, kinds), sub(p, "kind"),
                                       tool_kind_from_name, kinds);
      m_kind_lines.push_back(line_of(*t.get("kind")));

      // device = "rig" | "rig-emulated[:FILE]" | "mouse" | "script:FILE" | "python"
      const std::string dev_expected = "rig, rig-emulated[:FILE], mouse, script:FILE or python";
      const toml::node& dev_node = required(t, "device", p, dev_expected);
      const std::string dp = sub(p, "device");
      const std::string& dev = string(dev_node, dp, dev_expected);
      const bool script = dev.rfind("script:", 0) == 0;
      if (script || dev.rfind("rig-emulated:", 0) == 0) {
        // A script the solver plays, or the one the emulated rig's handles play.
        const std::size_t colon = dev.find(':');
        tool.device.kind = script ? DeviceKind::kScript : DeviceKind::kRigEmulated;
        tool.device.script = existing_file(dev_node, dp, dev.substr(colon + 1), "script file");
        const ToolPath& path = tool_path(tool.device.script);
        if (!path.index_of(tool.name)) {
          fail(dev_node, dp,
               "script " + tool.device.script.string() + " has no rows for tool \"" + tool.name +
                   "\"",
               "a tool path CSV with rows whose tool column is \"" + tool.name + "\"");
        }
        // A script drives only what the tool has: a cautery pedal for a hook alone (a rig's
        // pedal is a pedal under the trainee's foot, whatever instrument the hand holds).
        const auto& rows = path.samples[*path.index_of(tool.name)];
        const auto pressed = std::find_if(rows.begin(), rows.end(), [](const ToolState& r) {
          return (r.buttons & kPedalButton) != 0;
        });
        if (script && tool.kind != ToolKind::kHook && pressed != rows.end()) {
          fail(dev_node, dp,
               "script " + tool.device.script.string() +
                   " presses the cautery pedal (buttons bit " + "1) for tool \"" + tool.name +
                   "\", a " + std::string(tool_kind_name(tool.kind)) + ", which has none",
               "the pedal only on a tool of kind hook");
        }
      } else {
        const auto k = device_kind_from_name(dev);
        if (!k || *k == DeviceKind::kScript) {
          fail(dev_node, dp, "unknown device \"" + dev + "\"", dev_expected);
        }
        tool.device.kind = *k;
      }

      if (const auto* h = t.get("hand")) {
        tool.hand = enum_value<Hand>(*h, sub(p, "hand"), hand_from_name, "left, right");
      }
      if (const auto* tr = t.get("trocar")) {
        tool.trocar_m = vec3(*tr, sub(p, "trocar"), "[x, y, z] in m");
      }
      scene.tools.push_back(std::move(tool));
    }
  }

  // [metrics] names groups of the scene's organs.
  void check_group_refs(const Scene& scene) const {
    std::string names;
    for (const Organ& o : scene.organs)
      for (const auto& [id, name] : o.groups) names += (names.empty() ? "" : ", ") + name;
    for (const GroupRef& r : m_group_refs) {
      const bool known = std::any_of(scene.organs.begin(), scene.organs.end(), [&](const Organ& o) {
        return o.group_id(r.name).has_value();
      });
      if (!known)
        fail(r.line, r.path, "unknown group \"" + r.name + "\"",
             names.empty() ? std::string("a group the organs name (they name none)")
                           : "one of: " + names);
    }
  }

  // ---- effects ----

  void check_dependencies(const Scene& scene, const toml::node* effects_node) const {
    const SceneSettings& s = scene.settings;
    const std::int64_t line = effects_node != nullptr ? line_of(*effects_node) : 0;
    const std::string p = "scene.effects";
    auto need = [&](Effect e, Effect dep) {
      if (s.has(e) && !s.has(dep)) {
        fail(line, p,
             "effect \"" + std::string(effect_name(e)) + "\" needs effect \"" +
                 std::string(effect_name(dep)) + "\"",
             "\"" + std::string(effect_name(dep)) + "\" listed too");
      }
    };
    need(Effect::kGravity, Effect::kFem);
    need(Effect::kPlasticity, Effect::kFem);
    need(Effect::kContact, Effect::kFem);
    need(Effect::kContact, Effect::kSurface);
    need(Effect::kRender, Effect::kSurface);
    need(Effect::kClips, Effect::kContact);
    need(Effect::kLoops, Effect::kContact);
    need(Effect::kSupports, Effect::kFem);
    need(Effect::kSmoke, Effect::kCautery);
    // Supports and their effect come together: a plane nothing simulates would be a false promise.
    if (s.has(Effect::kSupports) && scene.supports.empty())
      fail(line, p, "effect \"supports\" is listed but the scene has no [[support]]",
           "a [[support]] plane, or \"supports\" not listed");
    if (!s.has(Effect::kSupports) && !scene.supports.empty())
      fail(m_support_line, "support", "a [[support]] plane, but effect \"supports\" is not listed",
           "\"supports\" in scene.effects");
    if (s.has(Effect::kBleeding) && !scene.metrics.artery)
      fail(line, p, "effect \"bleeding\" is listed but no artery is named to bleed",
           "metrics.artery, or \"bleeding\" not listed");
    if (scene.metrics.clip_target_m && !scene.metrics.artery)
      fail(m_clip_target_line, "metrics.clip_target", "a clip target, but no artery is named",
           "metrics.artery");
    if (scene.metrics.procedure && !scene.metrics.artery)
      fail(m_procedure_line, "metrics.procedure",
           "the procedure's steps include securing the artery, but no artery is named",
           "metrics.artery");
    if (scene.render.surroundings == Surroundings::kAbdomen && scene.supports.empty())
      fail(m_surroundings_line, "render.surroundings",
           "an abdomen is drawn on the organs' support, but the scene has no [[support]]",
           "a [[support]] plane (the posterior abdominal wall)");
    // A clip applier or a hook acts only where its effect is simulated: say so rather than let
    // the instrument do nothing.
    for (std::size_t i = 0; i < scene.tools.size(); ++i) {
      if (scene.tools[i].kind == ToolKind::kClipApplier && !s.has(Effect::kClips)) {
        fail(m_kind_lines[i], at("tool", i) + ".kind",
             "a clip-applier places clips, but effect \"clips\" is not listed",
             "\"clips\" in scene.effects (with \"contact\", \"surface\" and \"fem\")");
      }
      if (scene.tools[i].kind == ToolKind::kEndoloop && !s.has(Effect::kLoops)) {
        fail(m_kind_lines[i], at("tool", i) + ".kind",
             "an endoloop ligates tissue, but effect \"loops\" is not listed",
             "\"loops\" in scene.effects (with \"contact\", \"surface\" and \"fem\")");
      }
      if (scene.tools[i].kind == ToolKind::kStapler &&
          (!s.has(Effect::kClips) || !s.has(Effect::kCutting))) {
        fail(m_kind_lines[i], at("tool", i) + ".kind",
             "a stapler lays staple lines (effect \"clips\") and divides between them (effect "
             "\"cutting\"), but they are not both listed",
             "\"clips\" and \"cutting\" in scene.effects (with \"contact\", \"surface\" and "
             "\"fem\")");
      }
      if (scene.tools[i].kind == ToolKind::kHook && !s.has(Effect::kCautery)) {
        fail(m_kind_lines[i], at("tool", i) + ".kind",
             "a hook divides and coagulates tissue, but effect \"cautery\" is not listed",
             "\"cautery\" in scene.effects");
      }
    }
    if (s.has(Effect::kHaptics)) {
      bool device = false;
      for (const Tool& tool : scene.tools)
        device = device || tool.kind != ToolKind::kEndoscope;  // a script plays in real time
      if (!device) {
        fail(line, p, "effect \"haptics\" needs a tool driven by a device, but no tool has one",
             "a grasper or scissors [[tool]] (device rig, rig-emulated, mouse or script)");
      }
    }
  }

  std::string m_file;                      // scene file as given, for errors
  std::filesystem::path m_dir;             // folder relative paths resolve against
  std::int64_t m_rubric_line = 0;          // where [metrics] rubric is
  std::int64_t m_support_line = 0;         // where [[support]] begins
  std::int64_t m_procedure_line = 0;       // where [metrics] procedure is
  std::int64_t m_clip_target_line = 0;     // where [metrics] clip_target is
  std::int64_t m_surroundings_line = 0;    // where [render] surroundings is
  std::vector<std::int64_t> m_kind_lines;  // (tools) where each tool's kind is
  struct GroupRef {
    std::int64_t line = 0;
    std::string path, name;
  };
  std::vector<GroupRef> m_group_refs;  // group names [metrics] gives, checked once all are read
  std::map<std::filesystem::path, ToolPath> m_paths;  // script files read so far
};

}  // namespace

Scene parse_scene_text(const std::string& toml, const std::filesystem::path& scene_path) {
  return Loader(scene_path).load(toml);
}

Scene load_scene(const std::filesystem::path& path) {
  // A directory opens as a stream that reads nothing, which would parse as an empty scene.
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw InputError(path.string(), 0, "is a directory", "a scene TOML file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string(), 0, "cannot open scene file", "a readable TOML file");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) throw InputError(path.string(), 0, "read error", "a readable TOML file");
  return parse_scene_text(buffer.str(), path);
}

}  // namespace serosa
