#include "app/batch_manifest.h"

#include <algorithm>
#include <set>
#include <sstream>

#include <toml++/toml.h>

#include "engine/input_error.h"
#include "engine/scene.h"
#include "engine/toml_reader.h"

namespace serosa::app {
namespace {

namespace fs = std::filesystem;

class ManifestReader {
 public:
  ManifestReader(fs::path file, bool new_goldens)
      : m_in(std::move(file)), m_new_goldens(new_goldens) {}

  BatchManifest read() {
    const toml::table root = m_in.parse("a batch manifest in TOML");
    m_in.check_keys(root, "", {"title", "timeout", "throttle", "run"});
    BatchManifest m;
    m.file = m_in.file();
    if (const auto* n = root.get("title")) m.title = m_in.text(*n, "title");
    if (const auto* n = root.get("timeout")) {
      m.timeout_s = m_in.number(*n, "timeout");
      if (!(m.timeout_s > 0.0)) m_in.fail(*n, "timeout", "not positive", "seconds > 0");
    }
    if (const auto* n = root.get("throttle")) {
      const std::int64_t t = m_in.integer(*n, "throttle");
      if (t < 0 || t > 10000) m_in.fail(*n, "throttle", "out of range", "0 (no limit) to 10000");
      m.throttle = static_cast<int>(t);
    }
    const auto* runs = root.get("run");
    const auto* arr = runs ? runs->as_array() : nullptr;
    if (arr == nullptr || arr->empty())
      throw InputError(m_in.file().string(), 0, "no [[run]] tables", "one [[run]] per run");
    std::set<std::string> names;
    for (std::size_t i = 0; i < arr->size(); ++i) {
      const std::string p = "run[" + std::to_string(i) + "]";
      const auto* t = (*arr)[i].as_table();
      if (t == nullptr) m_in.fail((*arr)[i], p, "not a table", "a [[run]] table");
      read_run(*t, p, names, m.runs);
    }
    return m;
  }

 private:
  fs::path resolve(const std::string& rel) const {
    const fs::path p(rel);
    return p.is_absolute() ? p : fs::absolute(m_in.file().parent_path() / p).lexically_normal();
  }

  fs::path existing(const toml::node& n, const std::string& p, const std::string& what) const {
    const fs::path f = resolve(m_in.text(n, p));
    if (!fs::is_regular_file(f)) m_in.fail(n, p, "no such " + what + " " + f.string(), "a file");
    return f;
  }

  static std::string value_text(const toml::node& n) {
    std::ostringstream s;
    n.visit([&](const auto& v) { s << v; });
    return s.str();
  }

  void read_run(const toml::table& t, const std::string& p, std::set<std::string>& names,
                std::vector<BatchRun>& out) const {
    m_in.check_keys(t, p, {"name", "scene", "steps", "path", "set", "seeds", "perturb", "golden"});
    BatchRun r;
    r.line = t.source().begin.line;
    const toml::node& name = m_in.required(t, p, "name");
    r.group = m_in.text(name, p + ".name");
    const bool ok = !r.group.empty() && std::all_of(r.group.begin(), r.group.end(), [](char c) {
      return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-' || c == '_';
    });
    if (!ok)
      m_in.fail(name, p + ".name", "'" + r.group + "' is not a run name", "a-z, 0-9, - and _");
    if (!names.insert(r.group).second)
      m_in.fail(name, p + ".name", "a second run named '" + r.group + "'", "unique names");
    const toml::node& scene = m_in.required(t, p, "scene");
    r.scene = existing(scene, p + ".scene", "scene");
    if (const auto* n = t.get("steps")) {
      r.steps = m_in.integer(*n, p + ".steps");
      if (*r.steps < 1) m_in.fail(*n, p + ".steps", "out of range", "solver steps >= 1");
    }
    if (const auto* n = t.get("path")) r.path = existing(*n, p + ".path", "tool path");
    if (const auto* n = t.get("set")) read_overrides(*n, p + ".set", r);
    if (const auto* n = t.get("perturb")) {
      r.perturb_m = m_in.number(*n, p + ".perturb");
      if (!(r.perturb_m > 0.0 && r.perturb_m < 0.01))
        m_in.fail(*n, p + ".perturb", "out of range", "an amplitude in (0, 0.01) m");
    }
    if (const auto* n = t.get("golden")) {
      r.golden = resolve(m_in.text(*n, p + ".golden"));
      if (!m_new_goldens && !fs::is_regular_file(*r.golden))
        m_in.fail(*n, p + ".golden", "no such golden " + r.golden->string(),
                  "a golden report (--update-golden writes it)");
    }
    check_scene(r, scene, p);
    const auto* seeds = t.get("seeds");
    if (seeds == nullptr) {
      r.id = r.group;
      out.push_back(std::move(r));
      return;
    }
    const auto* a = seeds->as_array();
    if (a == nullptr || a->empty()) m_in.fail(*seeds, p + ".seeds", "not a list", "[1, 2, ...]");
    if (r.golden)
      m_in.fail(*seeds, p + ".seeds", "seeds with a golden",
                "a golden for an unperturbed run only (seeds perturb the path)");
    for (std::size_t k = 0; k < a->size(); ++k) {
      const std::int64_t s = m_in.integer((*a)[k], p + ".seeds[" + std::to_string(k) + "]");
      if (s < 0) m_in.fail((*a)[k], p + ".seeds", "negative", "seeds >= 0");
      BatchRun seeded = r;
      seeded.seed = static_cast<std::uint64_t>(s);
      seeded.id = r.group + ".seed-" + std::to_string(s);
      if (!names.insert(seeded.id).second)
        m_in.fail((*a)[k], p + ".seeds", "seed " + std::to_string(s) + " twice", "unique seeds");
      out.push_back(std::move(seeded));
    }
  }

  void read_overrides(const toml::node& n, const std::string& p, BatchRun& r) const {
    const auto* t = n.as_table();
    if (t == nullptr) m_in.fail(n, p, "not a table", "{ \"solver.tolerance\" = 1e-4, ... }");
    for (const auto& [key, value] : *t) {
      if (value.is_table())
        m_in.fail(value, p + "." + std::string(key.str()), "a table",
                  "a value (write the key whole: \"solver.tolerance\" = 1e-4)");
      r.overrides.push_back({std::string(key.str()), value_text(value)});
    }
  }

  // The scene, loaded as the run will load it: an override of a key it does not know fails here,
  // before anything runs, naming the manifest's line.
  void check_scene(BatchRun& r, const toml::node& scene, const std::string& p) const {
    try {
      r.paced = has_rig_in_the_loop(load_scene(r.scene, r.overrides));
    } catch (const InputError& e) {
      m_in.fail(scene, p, std::string("its scene does not load: ") + e.what(),
                "a scene that loads with the run's overrides");
    }
  }

  static bool has_rig_in_the_loop(const Scene& s) {
    return s.settings.has(Effect::kHaptics) &&
           std::any_of(s.tools.begin(), s.tools.end(), [](const Tool& t) {
             return t.device.kind == DeviceKind::kRig || t.device.kind == DeviceKind::kRigEmulated;
           });
  }

  TomlReader m_in;
  bool m_new_goldens;
};

}  // namespace

BatchManifest load_manifest(const fs::path& file, bool new_goldens) {
  if (!fs::is_regular_file(file))
    throw InputError(file.string(), 0, "no such manifest", "a batch manifest TOML file");
  return ManifestReader(file, new_goldens).read();
}

}  // namespace serosa::app
