#include "engine/scene/scene_override.h"

#include <charconv>
#include <fstream>
#include <sstream>

#include <toml++/toml.h>

#include "engine/input_error.h"

namespace serosa {
namespace {

std::vector<std::string> split_dots(const std::string& key) {
  std::vector<std::string> parts;
  std::size_t start = 0;
  while (true) {
    const std::size_t dot = key.find('.', start);
    parts.push_back(key.substr(start, dot == std::string::npos ? std::string::npos : dot - start));
    if (dot == std::string::npos) return parts;
    start = dot + 1;
  }
}

bool index_of(const std::string& part, std::size_t& index) {
  const auto [end, ec] = std::from_chars(part.data(), part.data() + part.size(), index);
  return ec == std::errc() && end == part.data() + part.size();
}

// A word the shell leaves bare (cholmod, ../assets/x.msh): no quotes, brackets, braces, spaces.
bool bare_word(const std::string& v) {
  return !v.empty() && v.find_first_of("\"'[]{}=# \t") == std::string::npos;
}

// The value as TOML; a bare word where the key holds text (or holds nothing yet) is that text,
// as `--set solver.kind=cholmod` means.
toml::node_view<toml::node> value_node(toml::table& holder, const SceneOverride& o,
                                       const std::string& file, const toml::node* old) {
  try {
    holder = toml::parse("v = " + o.value);
    return holder["v"];
  } catch (const toml::parse_error&) {
  }
  if (bare_word(o.value) && (old == nullptr || old->is_string())) {
    holder = toml::table{{"v", o.value}};
    return holder["v"];
  }
  throw InputError(file, 0, o.key + ": the value " + o.value + " is not TOML",
                   "a TOML value (a number, \"text\", true, [x, y, z])");
}

// The table the override's last part goes into (walking `parts` but the last).
toml::table& parent_of(toml::table& root, const SceneOverride& o,
                       const std::vector<std::string>& parts, const std::string& file) {
  toml::table* t = &root;
  std::string walked;
  for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
    walked += (walked.empty() ? "" : ".") + parts[i];
    toml::node* n = t->get(parts[i]);
    if (n == nullptr)
      throw InputError(file, 0, o.key + ": the scene has no [" + walked + "]",
                       "a key under a table the scene has");
    std::size_t k = 0;
    if (auto* a = n->as_array();
        a != nullptr && i + 2 < parts.size() && index_of(parts[i + 1], k)) {
      if (k >= a->size() || !(*a)[k].is_table())
        throw InputError(file, 0, o.key + ": " + walked + " has no table " + parts[i + 1],
                         "an index below " + std::to_string(a->size()));
      t = (*a)[k].as_table();
      walked += "." + parts[++i];
      continue;
    }
    if (n->is_array_of_tables()) {
      std::string rest;
      for (std::size_t j = i + 1; j < parts.size(); ++j) rest += "." + parts[j];
      throw InputError(file, 0, o.key + ": " + walked + " is a list of [[" + walked + "]] tables",
                       "one picked by its index, as " + walked + ".0" + rest);
    }
    if (!n->is_table())
      throw InputError(file, 0, o.key + ": " + walked + " is a value, not a table",
                       "a key under a table");
    t = n->as_table();
  }
  return *t;
}

}  // namespace

SceneOverride parse_override(const std::string& text, const std::string& where) {
  const std::size_t eq = text.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 >= text.size())
    throw InputError(where, 0, "'" + text + "' is not KEY=VALUE",
                     "a scene key and a TOML value, as solver.tolerance=1e-4");
  return {text.substr(0, eq), text.substr(eq + 1)};
}

std::string apply_overrides(const std::string& toml, const std::filesystem::path& scene_path,
                            const std::vector<SceneOverride>& overrides) {
  if (overrides.empty()) return toml;
  const std::string file = scene_path.string();
  toml::table root;
  try {
    root = toml::parse(toml, file);
  } catch (const toml::parse_error& e) {
    throw InputError(file, static_cast<std::int64_t>(e.source().begin.line),
                     std::string("TOML syntax error: ") + std::string(e.description()),
                     "a scene in TOML");
  }
  for (const SceneOverride& o : overrides) {
    const std::vector<std::string> parts = split_dots(o.key);
    for (const std::string& p : parts)
      if (p.empty())
        throw InputError(file, 0, "'" + o.key + "' is not a key path", "names joined by dots");
    toml::table& parent = parent_of(root, o, parts, file);
    toml::table holder;
    const toml::node* old = parent.get(parts.back());
    const auto value = value_node(holder, o, file, old);
    if (old != nullptr && old->is_table())
      throw InputError(file, 0, o.key + " is a table, not a value", "a key that holds a value");
    parent.insert_or_assign(parts.back(), *value.node());
  }
  std::ostringstream out;
  out << root;
  return out.str();
}

Scene load_scene(const std::filesystem::path& path, const std::vector<SceneOverride>& overrides) {
  if (overrides.empty()) return load_scene(path);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string(), 0, "cannot open scene file", "a readable TOML file");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  const std::string text = apply_overrides(buffer.str(), path, overrides);
  try {
    return parse_scene_text(text, path);
  } catch (const InputError& e) {
    // The loader read the rewritten text: its line numbers are not the file's.
    throw InputError(e.file(), 0, e.message() + " (the scene with its overrides)", e.expected());
  }
}

}  // namespace serosa
