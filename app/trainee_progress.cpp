#include "app/trainee_progress.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>

#include "app/shell_command.h"

namespace serosa::app {

namespace {

std::string score_text(std::optional<double> s) {
  return s ? std::to_string(std::lround(*s)) : "-";
}

std::string padded(std::string s, std::size_t width) {
  if (s.size() < width) s.append(width - s.size(), ' ');
  return s;
}

}  // namespace

std::vector<TaskProgress> task_progress(const std::vector<SessionRecord>& sessions) {
  std::vector<TaskProgress> out;
  for (const SessionRecord& s : sessions) {
    auto it = std::find_if(out.begin(), out.end(),
                           [&](const TaskProgress& p) { return p.task == s.task; });
    if (it == out.end()) {
      out.push_back(TaskProgress{s.task, 0, 0, std::nullopt, std::nullopt, std::nullopt});
      it = out.end() - 1;
    }
    ++it->sessions;
    it->last = s.score;
    if (s.score) it->best = std::max(it->best.value_or(*s.score), *s.score);
    if (s.passed.value_or(false)) {
      ++it->passed;
      if (!it->first_passed) it->first_passed = it->sessions;
    }
  }
  return out;
}

std::string progress_text(const std::string& trainee, const std::vector<SessionRecord>& sessions) {
  std::string t = "trainee " + trainee + ": " + std::to_string(sessions.size()) + " session" +
                  (sessions.size() == 1 ? "" : "s") + "\n\n";
  t += "task                  sessions  passed  best  last  first passed\n";
  for (const TaskProgress& p : task_progress(sessions)) {
    char line[256];
    std::snprintf(
        line, sizeof line, "%s  %8d  %6d  %4s  %4s  %s\n", padded(p.task, 20).c_str(), p.sessions,
        p.passed, score_text(p.best).c_str(), score_text(p.last).c_str(),
        p.first_passed ? ("session " + std::to_string(*p.first_passed)).c_str() : "not yet");
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
  }
  return t;
}

void plot_learning_curve(const std::string& trainee, const std::vector<SessionRecord>& sessions,
                         const std::filesystem::path& png, const std::string& gnuplot) {
  const std::vector<TaskProgress> tasks = task_progress(sessions);
  std::filesystem::path dat = png, gp = png;
  dat.replace_extension(".dat");
  gp.replace_extension(".gp");
  {
    // One block per task (gnuplot's index): session number, score, passed (1/0).
    std::ofstream d(dat);
    for (const TaskProgress& p : tasks) {
      for (std::size_t i = 0; i < sessions.size(); ++i)
        if (sessions[i].task == p.task && sessions[i].score)
          d << i + 1 << ' ' << *sessions[i].score << ' '
            << (sessions[i].passed.value_or(false) ? 1 : 0) << '\n';
      d << "\n\n";
    }
    if (!d) throw std::runtime_error("cannot write " + dat.string());
  }
  std::string s = "set terminal pngcairo noenhanced size 900,560 font ',10'\n";
  s += "set output " + gp_quote(png.string()) + "\n";
  s += "set title " + gp_quote("Learning curve: " + trainee) + "\n";
  s += "set xlabel 'session'\nset ylabel 'score (0-100)'\nset yrange [0:100]\n";
  s += "set xrange [0.5:" + std::to_string(sessions.size()) + ".5]\nset xtics 1\n";
  s += "set key bottom right\nset grid\n";
  s += "plot ";
  for (std::size_t k = 0; k < tasks.size(); ++k) {
    const std::string data = gp_quote(dat.string());
    s += (k > 0 ? ", " : "") + data + " index " + std::to_string(k) +
         " using 1:2 with linespoints lw 2 title " + gp_quote(tasks[k].task) + ", " + data +
         " index " + std::to_string(k) +
         " using 1:($3 > 0 ? $2 : 1/0) with points pt 7 ps 1.6 lc rgb '#28963c' " +
         (k == 0 ? "title 'passed'" : "notitle");
  }
  s += "\n";
  {
    std::ofstream g(gp);
    g << s;
    if (!g) throw std::runtime_error("cannot write " + gp.string());
  }
  std::filesystem::remove(png);
  const Command r = run_command(shell_quote(gnuplot) + " " + shell_quote(gp.string()));
  if (r.code != 0)
    throw std::runtime_error("gnuplot failed on " + gp.string() + ": " + first_line(r.output));
  if (!std::filesystem::exists(png) || std::filesystem::file_size(png) == 0)
    throw std::runtime_error("gnuplot wrote no " + png.string());
}

}  // namespace serosa::app
