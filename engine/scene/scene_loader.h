// The scene loader's inner workings (load_scene, engine/scene/scene.h, is the interface): one
// Loader per document, with typed access to its TOML that names the file, line and key path of
// every error, and one reader per part of the document, each in a file of its own (scene_load.cpp:
// the order of reading and the checks across tables; scene_load_organs.cpp,
// scene_load_settings.cpp, scene_load_metrics.cpp, scene_load_tools.cpp).
#pragma once

#include <toml++/toml.h>

#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "engine/input_error.h"
#include "engine/scene/scene.h"
#include "engine/scene/tool_path.h"

namespace serosa::scene_detail {

using Keys = std::initializer_list<std::string_view>;

/// v as the shortest text that reads back the same.
std::string fmt_num(double v);
/// "a, b, c".
std::string join_keys(Keys keys);
/// "path.key" (or "key" at the top).
std::string sub(const std::string& path, std::string_view key);
/// "path[i]".
std::string at(const std::string& path, std::size_t i);
std::int64_t line_of(const toml::node& n);
std::int64_t line_of(const toml::key& k);
/// "a table", "an integer", ... for errors.
std::string_view type_name(const toml::node& n);

// Reads one scene document. One instance per load; holds the file name for errors, the folder
// relative paths resolve against, and what cross-table checks need.
class Loader {
 public:
  explicit Loader(const std::filesystem::path& scene_path)
      : m_file(scene_path.string()),
        m_dir(std::filesystem::absolute(scene_path).lexically_normal().parent_path()) {}

  Scene load(const std::string& text);

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

  void read_scene(const toml::table& t, Scene& scene, const toml::node*& effects_node) const;

  // ---- [[organ]] ----

  // Reads the material keys present in t into m (absent keys keep m's values).
  void read_material(const toml::table& t, const std::string& p, Material& m) const;

  // A group named by a key or value: an integer id (taken as is), or a name from `groups`.
  int group_ref(const Organ& organ, const std::string& ref, std::int64_t line,
                const std::string& path) const;

  void read_organs(const toml::table& root, Scene& scene);

  void read_fixed(const toml::table& t, const std::string& p, Organ& organ) const;

  void read_transform(const toml::table& t, const std::string& p, OrganTransform& tr) const;

  // ---- [solver] [render] [record] [cutting] [headless] ----

  void read_solver(const toml::table& t, SolverSettings& s) const;

  // looks = { GROUP = "TISSUE", ... }: the group must be one the organs name (checked once all
  // are read), the tissue one of kTissueLooks.
  void read_looks(const toml::table& t, const std::string& p, RenderSettings& r);

  void read_render(const toml::table& t, RenderSettings& r);

  void read_record(const toml::table& t, RecordSettings& r) const;

  void read_cutting(const toml::table& t, CuttingSettings& c) const;

  void read_headless(const toml::table& t, HeadlessSettings& h) const;

  void read_metrics(const toml::table& t, MetricsSettings& m);

  void read_transfer(const toml::node& n, const std::string& p, MetricsSettings& m);

  void read_procedure(const toml::node& n, const std::string& p, MetricsSettings& m);

  // The rubric's metrics name tools and groups of this scene, and some need an effect or a key.
  void check_rubric(const Scene& scene) const;

  // The families the curriculum's tasks add: the procedure's steps, clips.
  void check_rubric_task(const Scene& scene, const std::string& family, const std::string& suffix,
                         const std::string& what) const;

  static bool has_group(const Scene& scene, const std::string& name);

  // ---- [[support]] ----

  void read_supports(const toml::table& root, Scene& scene);

  // ---- [[tool]] ----

  const ToolPath& tool_path(const std::filesystem::path& file);

  void read_tools(const toml::table& root, Scene& scene);

  // [metrics] names groups of the scene's organs.
  void check_group_refs(const Scene& scene) const;

  // ---- effects ----

  void check_dependencies(const Scene& scene, const toml::node* effects_node) const;

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

}  // namespace serosa::scene_detail
