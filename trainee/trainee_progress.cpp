#include "trainee/trainee_progress.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <stdexcept>

#include "engine/shell_command.h"

namespace serosa::trainee {

namespace {

std::string score_text(std::optional<double> s) {
  return s ? std::to_string(std::lround(*s)) : "-";
}

std::string padded(std::string s, std::size_t width) {
  if (s.size() < width) s.append(width - s.size(), ' ');
  return s;
}

bool starts_with(const std::string& s, const std::string& head) { return s.rfind(head, 0) == 0; }

// A folder of its own under the system's temporary folder, removed with everything in it.
class TemporaryFolder {
 public:
  TemporaryFolder() {
    std::string name = (std::filesystem::temp_directory_path() / "serosa-plot-XXXXXX").string();
    if (mkdtemp(name.data()) == nullptr)
      throw std::runtime_error(std::string("cannot make a temporary folder like ") + name);
    m_path = name;
  }
  ~TemporaryFolder() {
    std::error_code ec;
    std::filesystem::remove_all(m_path, ec);
  }
  TemporaryFolder(const TemporaryFolder&) = delete;
  TemporaryFolder& operator=(const TemporaryFolder&) = delete;
  [[nodiscard]] const std::filesystem::path& path() const { return m_path; }

 private:
  std::filesystem::path m_path;
};

// The gnuplot data: one block per task (gnuplot's index): session number, score, passed (1/0).
std::string curve_data(const std::vector<TaskProgress>& tasks,
                       const std::vector<SessionRecord>& sessions) {
  std::string d;
  for (const TaskProgress& p : tasks) {
    for (std::size_t i = 0; i < sessions.size(); ++i)
      if (sessions[i].task == p.task && sessions[i].score)
        d.append(std::to_string(i + 1))
            .append(" ")
            .append(std::to_string(*sessions[i].score))
            .append(sessions[i].passed.value_or(false) ? " 1\n" : " 0\n");
    d.append("\n\n");
  }
  return d;
}

std::string curve_script(const std::string& trainee, const std::vector<TaskProgress>& tasks,
                         std::size_t sessions, const std::filesystem::path& dat,
                         const std::filesystem::path& png) {
  std::string s = "set terminal pngcairo noenhanced size 900,560 font ',10'\n";
  s += std::string("set output ") + gp_quote(png.string()) + "\n";
  s += std::string("set title ") + gp_quote(std::string("Learning curve: ") + trainee) + "\n";
  s += "set xlabel 'session'\nset ylabel 'score (0-100)'\nset yrange [0:100]\n";
  s += std::string("set xrange [0.5:") + std::to_string(sessions) + ".5]\nset xtics 1\n";
  s += "set key bottom right\nset grid\n";
  s += "plot ";
  const std::string data = gp_quote(dat.string());
  for (std::size_t k = 0; k < tasks.size(); ++k) {
    const std::string colour = std::string(" lc rgb '") + task_colour(k) + "'";
    const std::string block = data + " index " + std::to_string(k);
    if (k > 0) s += ", ";
    s += block + " using 1:2 with linespoints lw 2" + colour + " title " + gp_quote(tasks[k].task);
    s += std::string(", ") + block +
         " using 1:($3 > 0 ? $2 : 1/0) with points pt 7 ps 1.6 lc rgb '#28963c' ";
    s += k == 0 ? "title 'passed'" : "notitle";
  }
  for (const PassLine& l : pass_lines(tasks))
    s.append(", ")
        .append(std::to_string(l.score))
        .append(" with lines dt 2 lw 1.5 lc rgb '")
        .append(l.tasks.size() == 1 ? task_colour(l.tasks[0]) : "#666666")
        .append("' title ")
        .append(gp_quote(l.label(tasks)));
  return s + "\n";
}

}  // namespace

std::vector<TaskProgress> task_progress(const std::vector<SessionRecord>& sessions) {
  std::vector<TaskProgress> out;
  for (const SessionRecord& s : sessions) {
    auto it = std::find_if(out.begin(), out.end(),
                           [&](const TaskProgress& p) { return p.task == s.task; });
    if (it == out.end()) {
      out.push_back(TaskProgress{});
      out.back().task = s.task;
      it = out.end() - 1;
    }
    ++it->sessions;
    it->last = s.score;
    if (s.score) it->best = std::max(it->best.value_or(*s.score), *s.score);
    if (s.pass_score) it->pass_score = s.pass_score;
    it->last_passed = s.passed.value_or(false);
    if (it->last_passed) {
      ++it->passed;
      if (!it->first_passed) it->first_passed = it->sessions;
    }
  }
  return out;
}

std::vector<PassLine> pass_lines(const std::vector<TaskProgress>& tasks) {
  std::vector<PassLine> out;
  for (std::size_t k = 0; k < tasks.size(); ++k) {
    if (!tasks[k].pass_score) continue;
    auto it = std::find_if(out.begin(), out.end(),
                           [&](const PassLine& l) { return l.score == *tasks[k].pass_score; });
    if (it == out.end()) it = out.insert(out.end(), PassLine{*tasks[k].pass_score, {}});
    it->tasks.push_back(k);
  }
  std::sort(out.begin(), out.end(),
            [](const PassLine& a, const PassLine& b) { return a.score < b.score; });
  return out;
}

std::string PassLine::label(const std::vector<TaskProgress>& all) const {
  std::string l = std::string("pass ") + score_text(score) + ", ";
  if (tasks.size() == 1) return l + all[tasks[0]].task;
  if (tasks.size() == all.size()) return l + "every task";
  return l + std::to_string(tasks.size()) + " tasks";
}

std::string short_reason(const std::string& reason) {
  const std::string under = " under the pass score of ";
  if (const auto at = reason.find(under); starts_with(reason, "score ") && at != std::string::npos)
    return reason.substr(0, at) + " < " + reason.substr(at + under.size());
  for (const auto& [words, sign] :
       {std::pair<std::string, std::string>{", above the limit of ", " > "},
        {", below the limit of ", " < "}}) {
    const auto at = reason.find(words);
    if (at == std::string::npos) continue;
    std::string limit = reason.substr(at + words.size());
    if (const auto c = limit.find(" ("); c != std::string::npos) limit.resize(c);
    return reason.substr(0, at) + sign + limit;
  }
  return reason;
}

std::string criterion_of(const std::string& reason) {
  if (starts_with(reason, "score ") && reason.find(" under the pass score") != std::string::npos)
    return "score under the pass score";
  const auto at = reason.find(" = ");
  return at == std::string::npos ? reason : reason.substr(0, at);
}

std::string why_failed(const SessionRecord& s) {
  if (!s.passed || *s.passed) return "";
  if (!s.reasons_known) return "not known (its report had gone when the database was upgraded)";
  std::string why;
  for (const std::string& r : s.failed) why.append(why.empty() ? "" : "; ").append(short_reason(r));
  return why.empty() ? "not passed" : why;
}

std::string progress_text(const std::string& trainee, const std::vector<SessionRecord>& sessions) {
  std::string t = std::string("trainee ") + trainee + ": " + std::to_string(sessions.size()) +
                  " session" + (sessions.size() == 1 ? "" : "s") + "\n\n";
  t += "task                  sessions  passed  best  last  pass at  first passed\n";
  for (const TaskProgress& p : task_progress(sessions)) {
    char line[256];
    std::snprintf(line, sizeof line, "%s  %8d  %6d  %4s  %4s  %7s  %s\n",
                  padded(p.task, 20).c_str(), p.sessions, p.passed, score_text(p.best).c_str(),
                  score_text(p.last).c_str(), score_text(p.pass_score).c_str(),
                  p.first_passed
                      ? (std::string("session ") + std::to_string(*p.first_passed)).c_str()
                      : "not yet");
    t += line;
  }
  t += "\n  #  started (UTC)         task                  score  passed  recording\n";
  for (std::size_t i = 0; i < sessions.size(); ++i) {
    const SessionRecord& s = sessions[i];
    char line[1024];
    std::snprintf(line, sizeof line, "%3zu  %s  %s  %5s  %-6s  %s\n", i + 1,
                  padded(s.started_utc, 20).c_str(), padded(s.task, 20).c_str(),
                  score_text(s.score).c_str(), s.passed ? (*s.passed ? "yes" : "no") : "-",
                  s.recording.empty() ? "(not recorded)" : s.recording.c_str());
    t += line;
    if (const std::string why = why_failed(s); !why.empty())
      t += std::string("     failed: ") + why + "\n";
  }
  return t;
}

std::string trainees_text(const std::vector<SessionRecord>& all, const std::filesystem::path& db) {
  std::map<std::string, std::vector<SessionRecord>> by_trainee;
  for (const SessionRecord& s : all) by_trainee[s.trainee].push_back(s);
  std::string t = std::to_string(by_trainee.size()) + " trainee" +
                  (by_trainee.size() == 1 ? "" : "s") + " in " + db.string() + "\n\n";
  t += "trainee               sessions  tasks  tasks passed\n";
  for (const auto& [name, sessions] : by_trainee) {
    const std::vector<TaskProgress> tasks = task_progress(sessions);
    const auto passed = std::count_if(tasks.begin(), tasks.end(),
                                      [](const TaskProgress& p) { return p.passed > 0; });
    char line[256];
    std::snprintf(line, sizeof line, "%s  %8zu  %5zu  %12td\n", padded(name, 20).c_str(),
                  sessions.size(), tasks.size(), passed);
    t += line;
  }
  t +=
      "\n`serosa trainee NAME` shows one trainee's sessions; `serosa cohort --html DIR` writes the "
      "whole group's page.\n";
  return t;
}

const char* task_colour(std::size_t index) {
  static constexpr std::array<const char*, 8> kColours{"#1f77b4", "#d62728", "#9467bd", "#ff7f0e",
                                                       "#17becf", "#8c564b", "#e377c2", "#7f7f7f"};
  return kColours[index % kColours.size()];
}

void plot_learning_curve(const std::string& trainee, const std::vector<SessionRecord>& sessions,
                         const std::filesystem::path& png, const std::string& gnuplot) {
  const std::vector<TaskProgress> tasks = task_progress(sessions);
  const TemporaryFolder work;  // nothing but the picture is left beside it
  const std::filesystem::path dat = work.path() / "curve.dat", gp = work.path() / "curve.gp";
  const std::filesystem::path out = std::filesystem::absolute(png);
  for (const auto& [file, text] :
       {std::pair{dat, curve_data(tasks, sessions)},
        std::pair{gp, curve_script(trainee, tasks, sessions.size(), dat, out)}}) {
    std::ofstream f(file);
    f << text;
    if (!f) throw std::runtime_error(std::string("cannot write ") + file.string());
  }
  std::filesystem::remove(out);
  const Command r = run_command(shell_quote(gnuplot) + " " + shell_quote(gp.string()));
  if (r.code != 0) throw std::runtime_error(std::string("gnuplot failed: ") + first_line(r.output));
  if (!std::filesystem::exists(out) || std::filesystem::file_size(out) == 0)
    throw std::runtime_error(std::string("gnuplot wrote no ") + png.string());
}

}  // namespace serosa::trainee
