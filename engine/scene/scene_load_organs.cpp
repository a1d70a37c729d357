// The scene's organs and supports: [[organ]] (mesh, groups, material and its per-group
// overrides, fixed nodes, placement) and [[support]] (docs/scene-format.md).
#include "engine/scene/scene_loader.h"

#include <algorithm>
#include <charconv>
#include <limits>
#include <map>
#include <system_error>
#include <utility>

namespace serosa::scene_detail {

// Reads the material keys present in t into m (absent keys keep m's values).
void Loader::read_material(const toml::table& t, const std::string& p, Material& m) const {
  if (const auto* n = t.get("young")) {
    m.young_pa = ranged(*n, sub(p, "young"), 0.0, true, std::numeric_limits<double>::infinity(),
                        false, "Young's modulus in Pa > 0");
  }
  if (const auto* n = t.get("poisson")) {
    m.poisson = ranged(*n, sub(p, "poisson"), -1.0, true, 0.5, true,
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
      m.plasticity.yield =
          ranged(*v, sub(pp, "yield"), 0.0, false, inf, false, "elastic limit (strain norm) >= 0");
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
int Loader::group_ref(const Organ& organ, const std::string& ref, std::int64_t line,
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

void Loader::read_organs(const toml::table& root, Scene& scene) {
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
        fail(name_node, sub(p, "name"),
             "duplicate organ name \"" + organ.name + "\" (also organ[" + std::to_string(j) + "])",
             "unique organ names");
      }
    }
    const toml::node& mesh_node = required(t, "mesh", p, "a mesh file path (string)");
    organ.mesh =
        existing_file(mesh_node, sub(p, "mesh"),
                      string(mesh_node, sub(p, "mesh"), "a mesh file path (string)"), "mesh file");

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

void Loader::read_fixed(const toml::table& t, const std::string& p, Organ& organ) const {
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

void Loader::read_transform(const toml::table& t, const std::string& p, OrganTransform& tr) const {
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

void Loader::read_supports(const toml::table& root, Scene& scene) {
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
    s.point_m = vec3(required(t, "point", p, "[x, y, z] in m"), sub(p, "point"), "[x, y, z] in m");
    const toml::node& nn = required(t, "normal", p, "a direction [x, y, z]");
    const Vec3 normal = vec3(nn, sub(p, "normal"), "a direction [x, y, z]");
    if (!(normal.norm() > 1e-12))
      fail(nn, sub(p, "normal"), "zero normal", "a non-zero direction [x, y, z]");
    s.normal = normal.normalized();
    scene.supports.push_back(std::move(s));
  }
}

}  // namespace serosa::scene_detail
