#include "trainee/task_list.h"

#include <algorithm>
#include <cstdio>

#include "engine/input_error.h"
#include "engine/scene/toml_reader.h"

namespace serosa::trainee {
namespace {

bool good_name(const std::string& n) {
  return !n.empty() && std::all_of(n.begin(), n.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-';
  });
}

Task read_task(const TomlReader& in, const toml::table& t, const std::string& p) {
  in.check_keys(t, p,
                {"name", "title", "skill", "level", "scene", "expert", "novice", "expert_steps",
                 "novice_steps"});
  const std::filesystem::path folder = in.file().parent_path();
  const auto file = [&](std::string_view key) {
    const std::filesystem::path f =
        (folder / in.text(in.required(t, p, key), p + "." + std::string(key))).lexically_normal();
    if (!std::filesystem::is_regular_file(f))
      in.fail(*t.get(key), p + "." + std::string(key), "no such file: " + f.string(),
              "a path relative to the task list's folder");
    return f;
  };
  const auto steps = [&](std::string_view key) {
    const std::int64_t n = in.integer(in.required(t, p, key), p + "." + std::string(key));
    if (n <= 0) in.fail(*t.get(key), p + "." + std::string(key), "not positive", "steps > 0");
    return n;
  };
  Task k;
  k.name = in.text(in.required(t, p, "name"), p + ".name");
  if (!good_name(k.name))
    in.fail(*t.get("name"), p + ".name", "'" + k.name + "' is not a task name",
            "lower case letters, digits and '-'");
  k.title = in.text(in.required(t, p, "title"), p + ".title");
  if (const auto* n = t.get("skill")) k.skill = in.text(*n, p + ".skill");
  const std::int64_t level = in.integer(in.required(t, p, "level"), p + ".level");
  if (level < 1 || level > 5) in.fail(*t.get("level"), p + ".level", "out of range", "1 to 5");
  k.level = static_cast<int>(level);
  k.scene = file("scene");
  k.expert = file("expert");
  k.novice = file("novice");
  k.expert_steps = steps("expert_steps");
  k.novice_steps = steps("novice_steps");
  return k;
}

}  // namespace

std::vector<Task> load_tasks(const std::filesystem::path& file) {
  const TomlReader in(file);
  const toml::table root = in.parse("the task list (config/tasks.toml)");
  in.check_keys(root, "", {"task"});
  const auto* list = root.get("task");
  const auto* arr = list != nullptr ? list->as_array() : nullptr;
  if (arr == nullptr || arr->empty() || !arr->is_array_of_tables())
    throw InputError(file.string(), 0, "no [[task]] tables", "one [[task]] per task");
  std::vector<Task> tasks;
  for (std::size_t i = 0; i < arr->size(); ++i) {
    const auto& t = *(*arr)[i].as_table();
    const std::string p = "task[" + std::to_string(i) + "]";
    Task k = read_task(in, t, p);
    if (std::any_of(tasks.begin(), tasks.end(), [&](const Task& o) { return o.name == k.name; }))
      in.fail(*t.get("name"), p + ".name", "a second task named '" + k.name + "'",
              "one task per name");
    tasks.push_back(std::move(k));
  }
  std::stable_sort(tasks.begin(), tasks.end(),
                   [](const Task& a, const Task& b) { return a.level < b.level; });
  return tasks;
}

const Task& find_task(const std::vector<Task>& tasks, std::string_view name,
                      const std::filesystem::path& file) {
  for (const Task& t : tasks)
    if (t.name == name) return t;
  std::string names;
  for (const Task& t : tasks) names.append(names.empty() ? "" : ", ").append(t.name);
  throw InputError(file.string(), 0, "no task named '" + std::string(name) + "'", names);
}

std::string tasks_text(const std::vector<Task>& tasks) {
  std::size_t wide = 4;
  for (const Task& t : tasks) wide = std::max(wide, t.name.size());
  std::string out;
  for (const Task& t : tasks) {
    char head[64];
    std::snprintf(head, sizeof head, "%d  %-*s  ", t.level, static_cast<int>(wide), t.name.c_str());
    out.append(head).append(t.title);
    if (!t.skill.empty()) out.append(": ").append(t.skill);
    out.append("  (").append(t.scene.string()).append(")\n");
  }
  return out;
}

}  // namespace serosa::trainee
