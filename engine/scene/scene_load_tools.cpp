// The scene's [[tool]] tables: kind, device, hand, trocar and each scripted tool's path
// (docs/scene-format.md).
#include "engine/scene/scene_loader.h"

#include <algorithm>
#include <utility>

#include "engine/hook.h"

namespace serosa::scene_detail {

const ToolPath& Loader::tool_path(const std::filesystem::path& file) {
  auto it = m_paths.find(file);
  if (it == m_paths.end()) it = m_paths.emplace(file, read_tool_path(file)).first;
  return it->second;
}

void Loader::read_tools(const toml::table& root, Scene& scene) {
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
        fail(
            dev_node, dp,
            "script " + tool.device.script.string() + " has no rows for tool \"" + tool.name + "\"",
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
             "script " + tool.device.script.string() + " presses the cautery pedal (buttons bit " +
                 "1) for tool \"" + tool.name + "\", a " + std::string(tool_kind_name(tool.kind)) +
                 ", which has none",
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

}  // namespace serosa::scene_detail
