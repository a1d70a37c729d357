// load_scene / parse_scene_text: TOML -> validated Scene (docs/scene-format.md).
//
// Every table is checked against its list of allowed keys before its values are read, so a typo
// is an error that lists what was meant. Every error names the file, the line of the offending key
// or value (toml++ source regions) and the key path ("organ[0].young"); a missing key names the
// line of the table that should hold it.
#include "engine/scene/scene_loader.h"

#include <algorithm>
#include <charconv>
#include <fstream>
#include <sstream>
#include <system_error>

#include "engine/hook.h"
#include "engine/scene/presets.h"

namespace serosa::scene_detail {

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

Scene Loader::load(const std::string& text) {
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

void Loader::read_scene(const toml::table& t, Scene& scene, const toml::node*& effects_node) const {
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

// [metrics] names groups of the scene's organs.
void Loader::check_group_refs(const Scene& scene) const {
  std::string names;
  for (const Organ& o : scene.organs)
    for (const auto& [id, name] : o.groups) names += (names.empty() ? "" : ", ") + name;
  for (const GroupRef& r : m_group_refs) {
    const bool known = std::any_of(scene.organs.begin(), scene.organs.end(),
                                   [&](const Organ& o) { return o.group_id(r.name).has_value(); });
    if (!known)
      fail(r.line, r.path, "unknown group \"" + r.name + "\"",
           names.empty() ? std::string("a group the organs name (they name none)")
                         : "one of: " + names);
  }
}

void Loader::check_dependencies(const Scene& scene, const toml::node* effects_node) const {
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

}  // namespace serosa::scene_detail

namespace serosa {

Scene parse_scene_text(const std::string& toml, const std::filesystem::path& scene_path) {
  return scene_detail::Loader(scene_path).load(toml);
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
