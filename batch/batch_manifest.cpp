#include "batch/batch_manifest.h"

#include <algorithm>
#include <cctype>
#include <map>
#include <set>
#include <sstream>

#include <toml++/toml.h>

#include "engine/input_error.h"
#include "engine/scene/scene.h"
#include "engine/scene/toml_reader.h"

namespace serosa::batch {
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
    Seen seen;
    for (std::size_t i = 0; i < arr->size(); ++i) {
      const std::string p = "run[" + std::to_string(i) + "]";
      const auto* t = (*arr)[i].as_table();
      if (t == nullptr) m_in.fail((*arr)[i], p, "not a table", "a [[run]] table");
      read_run(*t, p, seen, m.runs);
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

  // What earlier runs took: names are unique, and so are goldens (two runs writing one golden
  // under --update-golden would leave the last writer's).
  struct Seen {
    std::set<std::string> names;              ///< [[run]] names
    std::set<std::string> ids;                ///< the runs they expand into (sweeps, seeds)
    std::map<fs::path, std::string> goldens;  ///< golden -> the run that names it
  };

  void read_run(const toml::table& t, const std::string& p, Seen& seen,
                std::vector<BatchRun>& out) const {
    std::set<std::string>& names = seen.names;
    m_in.check_keys(
        t, p,
        {"name", "scene", "steps", "path", "set", "sweep", "seeds", "perturb", "golden", "strict"});
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
      const auto [other, fresh] = seen.goldens.emplace(*r.golden, r.group);
      if (!fresh)
        m_in.fail(*n, p + ".golden",
                  "golden " + r.golden->string() + " is named by run '" + other->second + "' too",
                  "a golden of its own for each run");
    }
    if (const auto* n = t.get("strict")) r.strict = m_in.boolean(*n, p + ".strict");
    r.id = r.group;
    for (BatchRun& v : swept(t, p, r)) {
      check_scene(v, scene, p);
      add_seeded(t, p, std::move(v), seen.ids, out);
    }
  }

  // The run once per combination of its sweep's values (the cross product; keys in the order of
  // their names, values as listed), each named by them: "tol.dt-0.0025.tolerance-0.001".
  std::vector<BatchRun> swept(const toml::table& t, const std::string& p, const BatchRun& r) const {
    const toml::node* n = t.get("sweep");
    if (n == nullptr) return {r};
    const auto* keys = n->as_table();
    if (keys == nullptr || keys->empty())
      m_in.fail(*n, p + ".sweep", "not a table of lists",
                "{ \"solver.tolerance\" = [1e-3, 1e-4] }");
    if (r.golden)
      m_in.fail(*n, p + ".sweep", "a sweep with a golden", "a golden for a single run only");
    std::vector<BatchRun> runs{r};
    for (const auto& [key, values] : *keys) {
      const std::string k(key.str());
      const auto* a = values.as_array();
      if (a == nullptr || a->empty())
        m_in.fail(values, p + ".sweep." + k, "not a list of values", "[value, value, ...]");
      std::vector<BatchRun> next;
      for (const BatchRun& v : runs)
        for (const toml::node& x : *a) {
          BatchRun w = v;
          w.overrides.push_back({k, value_text(x)});
          w.id.append(".").append(k, k.rfind('.') + 1).append("-").append(label(value_text(x)));
          next.push_back(std::move(w));
        }
      runs = std::move(next);
    }
    return runs;
  }

  // A value as a run name carries it: letters, digits, '.', '+' and '-'; anything else '_'.
  static std::string label(std::string v) {
    std::erase_if(v, [](char c) { return c == '"' || c == '\''; });
    for (char& c : v)
      if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '+' && c != '-') c = '_';
    return v;
  }

  // The run, or one per seed (its path perturbed) when it lists seeds.
  void add_seeded(const toml::table& t, const std::string& p, BatchRun r,
                  std::set<std::string>& names, std::vector<BatchRun>& out) const {
    const auto* seeds = t.get("seeds");
    if (seeds == nullptr) {
      if (!names.insert(r.id).second)
        m_in.fail(t, p, "a second run named '" + r.id + "'", "unique names and sweep values");
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
      seeded.id = r.id + ".seed-" + std::to_string(s);
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

}  // namespace serosa::batch
