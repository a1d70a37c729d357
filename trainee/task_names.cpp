#include "trainee/task_names.h"

#include <algorithm>

#include "engine/input_error.h"

namespace serosa::trainee {

namespace {

std::filesystem::path normal(const std::filesystem::path& p) {
  std::error_code ec;
  const std::filesystem::path a = std::filesystem::absolute(p, ec);
  return (ec ? p : a).lexically_normal();
}

// The list at `file` when it loads; none when it is missing or broken (a session is filed all
// the same, under its scene's stem).
TaskNames quietly_loaded(const std::filesystem::path& file) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) return {};
  try {
    return TaskNames(load_tasks(file));
  } catch (const InputError&) {
    return {};
  }
}

}  // namespace

std::string TaskNames::of(const std::filesystem::path& scene, const std::string& stored) const {
  const std::filesystem::path s = normal(scene);
  for (const Task& t : m_tasks)
    if (normal(t.scene) == s) return t.name;
  for (const Task& t : m_tasks)
    if (t.name == stored) return t.name;
  // The same scene in another checkout or install: its file name still says which task it is.
  const std::string stem = scene.stem().string();
  for (const Task& t : m_tasks)
    if (t.scene.stem() == stem || t.scene.stem() == stored) return t.name;
  return stored.empty() ? stem : stored;
}

std::size_t TaskNames::order(const std::string& name) const {
  const auto it =
      std::find_if(m_tasks.begin(), m_tasks.end(), [&](const Task& t) { return t.name == name; });
  return static_cast<std::size_t>(it - m_tasks.begin());
}

TaskNames load_task_names(const std::string& list) {
  if (!list.empty()) return TaskNames(load_tasks(list));
  return quietly_loaded(std::string(kDefaultTaskList));
}

std::string task_name_for_scene(const std::filesystem::path& scene) {
  const std::string stem = scene.stem().string();
  for (const std::filesystem::path& list :
       {normal(scene).parent_path() / "tasks.toml", std::filesystem::path(kDefaultTaskList)}) {
    const std::string name = quietly_loaded(list).of(scene, stem);
    if (name != stem) return name;
  }
  return stem;
}

void name_tasks(std::vector<SessionRecord>& sessions, const TaskNames& names) {
  for (SessionRecord& s : sessions) s.task = names.of(s.scene, s.task);
}

}  // namespace serosa::trainee
