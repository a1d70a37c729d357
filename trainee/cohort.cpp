#include "trainee/cohort.h"

#include <algorithm>
#include <map>
#include <set>

namespace serosa::trainee {

namespace {

std::vector<std::string> ordered_tasks(const std::vector<SessionRecord>& sessions,
                                       const TaskNames& names) {
  std::vector<std::string> tasks;
  for (const SessionRecord& s : sessions)
    if (std::find(tasks.begin(), tasks.end(), s.task) == tasks.end()) tasks.push_back(s.task);
  std::sort(tasks.begin(), tasks.end(), [&](const std::string& a, const std::string& b) {
    const std::size_t oa = names.order(a), ob = names.order(b);
    return oa != ob ? oa < ob : a < b;
  });
  return tasks;
}

std::size_t index_of(const std::vector<std::string>& tasks, const std::string& task) {
  return static_cast<std::size_t>(std::find(tasks.begin(), tasks.end(), task) - tasks.begin());
}

TaskPassRate pass_rate(const std::string& task, const std::vector<TraineeCohort>& trainees) {
  TaskPassRate r;
  r.task = task;
  for (const TraineeCohort& t : trainees) {
    const TaskProgress* p = t.on(task);
    if (p == nullptr) continue;
    ++r.trainees;
    r.trainees_passed += p->passed > 0 ? 1 : 0;
    r.sessions += p->sessions;
    r.sessions_passed += p->passed;
    if (p->pass_score) r.pass_score = p->pass_score;
  }
  return r;
}

// Each criterion once per session that missed it, however many of its lists name it.
std::vector<CriterionCount> count_criteria(const std::vector<SessionRecord>& sessions,
                                           const std::vector<std::string>& tasks) {
  std::map<std::string, CriterionCount> by_name;
  for (const SessionRecord& s : sessions) {
    std::set<std::string> missed, failing;
    for (const std::string& r : s.failed) failing.insert(criterion_of(r));
    for (const std::string& r : s.below_threshold) missed.insert(criterion_of(r));
    missed.insert(failing.begin(), failing.end());
    for (const std::string& c : missed) {
      CriterionCount& n = by_name[c];
      n.criterion = c;
      ++n.sessions;
      n.failing += failing.count(c) > 0 ? 1 : 0;
      if (std::find(n.tasks.begin(), n.tasks.end(), s.task) == n.tasks.end())
        n.tasks.push_back(s.task);
    }
  }
  std::vector<CriterionCount> out;
  for (auto& [name, n] : by_name) {
    std::sort(n.tasks.begin(), n.tasks.end(), [&](const std::string& a, const std::string& b) {
      return index_of(tasks, a) < index_of(tasks, b);
    });
    out.push_back(std::move(n));
  }
  std::stable_sort(out.begin(), out.end(), [](const CriterionCount& a, const CriterionCount& b) {
    return a.sessions != b.sessions ? a.sessions > b.sessions : a.failing > b.failing;
  });
  return out;
}

}  // namespace

const TaskProgress* TraineeCohort::on(const std::string& task) const {
  const auto it = std::find_if(tasks.begin(), tasks.end(),
                               [&](const TaskProgress& p) { return p.task == task; });
  return it == tasks.end() ? nullptr : &*it;
}

Cohort gather_cohort(std::vector<SessionRecord> sessions, const TaskNames& names) {
  name_tasks(sessions, names);
  Cohort c;
  c.sessions = static_cast<int>(sessions.size());
  c.tasks = ordered_tasks(sessions, names);
  std::map<std::string, std::vector<SessionRecord>> by_trainee;  // sorted by name
  for (SessionRecord& s : sessions) {
    if (s.passed && !*s.passed && !s.reasons_known) ++c.reasons_unknown;
    by_trainee[s.trainee].push_back(s);
  }
  for (auto& [name, mine] : by_trainee) {
    TraineeCohort t;
    t.name = name;
    t.tasks = task_progress(mine);
    std::sort(t.tasks.begin(), t.tasks.end(), [&](const TaskProgress& a, const TaskProgress& b) {
      return index_of(c.tasks, a.task) < index_of(c.tasks, b.task);
    });
    t.sessions = std::move(mine);
    c.trainees.push_back(std::move(t));
  }
  for (const std::string& task : c.tasks) c.pass_rates.push_back(pass_rate(task, c.trainees));
  c.criteria = count_criteria(sessions, c.tasks);
  return c;
}

}  // namespace serosa::trainee
