#include "trainee/cohort_svg.h"

#include <algorithm>
#include <cstdio>

#include "trainee/cohort_markup.h"

namespace serosa::trainee {

namespace {

// The learning curve's frame, in SVG user units (pixels at 100 %).
constexpr double kWidth = 640.0, kHeight = 300.0;
constexpr double kLeft = 44.0, kRight = 170.0, kTop = 14.0, kBottom = 38.0;
constexpr double kPlotW = kWidth - kLeft - kRight, kPlotH = kHeight - kTop - kBottom;
constexpr const char* kPassGreen = "#28963c";

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f", v);
  return buf;
}

std::size_t colour_index(const std::vector<std::string>& tasks, const std::string& task) {
  return static_cast<std::size_t>(std::find(tasks.begin(), tasks.end(), task) - tasks.begin());
}

struct Frame {
  std::size_t sessions;
  [[nodiscard]] double x(std::size_t number) const {
    return kLeft + (static_cast<double>(number) - 0.5) / static_cast<double>(sessions) * kPlotW;
  }
  [[nodiscard]] static double y(double score) {
    return kTop + (1.0 - std::clamp(score, 0.0, 100.0) / 100.0) * kPlotH;
  }
};

std::string text(double x, double y, const std::string& anchor, const std::string& t) {
  return std::string("<text x=\"") + num(x) + "\" y=\"" + num(y) + "\" text-anchor=\"" + anchor +
         "\">" + html_escape(t) + "</text>";
}

std::string line(double x1, double y1, double x2, double y2, const std::string& style) {
  return std::string("<line x1=\"") + num(x1) + "\" y1=\"" + num(y1) + "\" x2=\"" + num(x2) +
         "\" y2=\"" + num(y2) + "\" " + style + "/>";
}

std::string axes(const Frame& f) {
  std::string s;
  for (int score = 0; score <= 100; score += 20) {
    const double y = Frame::y(score);
    s += line(kLeft, y, kLeft + kPlotW, y, "class=\"grid\"");
    s += text(kLeft - 6.0, y + 4.0, "end", std::to_string(score));
  }
  const std::size_t step = std::max<std::size_t>(1, (f.sessions + 9) / 10);
  for (std::size_t n = 1; n <= f.sessions; n += step)
    s += text(f.x(n), kTop + kPlotH + 16.0, "middle", std::to_string(n));
  s += text(kLeft + kPlotW / 2.0, kHeight - 4.0, "middle", "session");
  s += std::string("<text x=\"12\" y=\"") + num(kTop + kPlotH / 2.0) +
       "\" text-anchor=\"middle\" transform=\"" + "rotate(-90 12 " + num(kTop + kPlotH / 2.0) +
       ")\">score</text>";
  return s;
}

// One task's curve: its sessions' points joined, passes ringed, its pass score dashed.
std::string task_curve(const TraineeCohort& t, const TaskProgress& p, const Frame& f,
                       const std::string& colour) {
  std::string points, marks;
  for (std::size_t i = 0; i < t.sessions.size(); ++i) {
    const SessionRecord& s = t.sessions[i];
    if (s.task != p.task || !s.score) continue;
    const std::string x = num(f.x(i + 1)), y = num(Frame::y(*s.score));
    points.append(points.empty() ? "" : " ").append(x).append(",").append(y);
    const bool passed = s.passed.value_or(false);
    marks += std::string("<circle cx=\"") + x + "\" cy=\"" + y + "\" r=\"" +
             (passed ? "5.5" : "4") + "\" fill=\"" + colour + "\"" +
             (passed ? std::string(" stroke=\"") + kPassGreen + "\" stroke-width=\"2.5\"" : "") +
             "><title>" +
             html_escape(std::string("session ") + std::to_string(i + 1) + ", " + p.task + ": " +
                         score_text(s.score) + (passed ? ", passed" : ", not passed")) +
             "</title></circle>";
  }
  std::string s;
  s += std::string("<polyline class=\"curve\" fill=\"none\" stroke=\"") + colour +
       "\" stroke-width=\"2\" points=\"" + points + "\"/>";
  return s + marks;
}

std::string pass_colour(const PassLine& l, const TraineeCohort& t,
                        const std::vector<std::string>& tasks) {
  return l.tasks.size() == 1 ? task_colour(colour_index(tasks, t.tasks[l.tasks[0]].task))
                             : "#666666";
}

std::string dashed(double x1, double y1, double x2, double y2, const std::string& colour) {
  return line(
      x1, y1, x2, y2,
      std::string("stroke=\"") + colour + "\" stroke-width=\"1.2\" stroke-dasharray=\"6 4\"");
}

std::string pass_score_lines(const TraineeCohort& t, const std::vector<std::string>& tasks) {
  std::string s;
  for (const PassLine& l : pass_lines(t.tasks))
    s += dashed(kLeft, Frame::y(l.score), kLeft + kPlotW, Frame::y(l.score),
                pass_colour(l, t, tasks));
  return s;
}

std::string legend(const TraineeCohort& t, const std::vector<std::string>& tasks) {
  std::string s;
  double y = kTop + 10.0;
  const double x = kLeft + kPlotW + 14.0;
  for (const TaskProgress& p : t.tasks) {
    s += line(x, y - 4.0, x + 22.0, y - 4.0,
              std::string("stroke=\"") + task_colour(colour_index(tasks, p.task)) +
                  "\" stroke-width=\"2\"");
    s += text(x + 28.0, y, "start", p.task);
    y += 18.0;
  }
  for (const PassLine& l : pass_lines(t.tasks)) {
    s += dashed(x, y - 4.0, x + 22.0, y - 4.0, pass_colour(l, t, tasks));
    s += text(x + 28.0, y, "start", l.label(t.tasks));
    y += 18.0;
  }
  s += std::string("<circle cx=\"") + num(x + 11.0) + "\" cy=\"" + num(y - 4.0) +
       "\" r=\"5.5\" fill=\"#fff\" stroke=\"" + kPassGreen + "\" stroke-width=\"2.5\"/>";
  return s + text(x + 28.0, y, "start", "passed");
}

}  // namespace

std::string learning_curve_svg(const TraineeCohort& trainee,
                               const std::vector<std::string>& tasks) {
  const Frame f{std::max<std::size_t>(1, trainee.sessions.size())};
  std::string s =
      std::string("<svg class=\"curve\" xmlns=\"http://www.w3.org/2000/svg\" width=\"") +
      num(kWidth) + "\" height=\"" + num(kHeight) + "\" viewBox=\"0 0 " + num(kWidth) + " " +
      num(kHeight) + "\" role=\"img\" aria-label=\"" +
      html_escape(std::string("Learning curve of ") + trainee.name) + "\">";
  s += std::string("<rect class=\"plot\" x=\"") + num(kLeft) + "\" y=\"" + num(kTop) +
       "\" width=\"" + num(kPlotW) + "\" height=\"" + num(kPlotH) + "\"/>";
  s += axes(f) + pass_score_lines(trainee, tasks);
  for (const TaskProgress& p : trainee.tasks)
    s += task_curve(trainee, p, f, task_colour(colour_index(tasks, p.task)));
  return s + legend(trainee, tasks) + "</svg>";
}

std::string pass_rate_svg(const std::vector<TaskPassRate>& rates) {
  constexpr double kRow = 30.0, kLabel = 150.0, kBar = 320.0, kWide = 760.0;
  const double height = 16.0 + kRow * static_cast<double>(rates.size());
  std::string s = std::string("<svg class=\"bars\" xmlns=\"http://www.w3.org/2000/svg\" width=\"") +
                  num(kWide) + "\" height=\"" + num(height) + "\" viewBox=\"0 0 " + num(kWide) +
                  " " + num(height) + "\" role=\"img\" aria-label=\"Pass rate per task\">";
  for (std::size_t i = 0; i < rates.size(); ++i) {
    const TaskPassRate& r = rates[i];
    const double y = 8.0 + kRow * static_cast<double>(i);
    const double share = r.trainees > 0 ? static_cast<double>(r.trainees_passed) / r.trainees : 0.0;
    s += text(kLabel - 8.0, y + 17.0, "end", r.task);
    s += std::string("<rect x=\"") + num(kLabel) + "\" y=\"" + num(y) + "\" width=\"" + num(kBar) +
         "\" height=\"22\" fill=\"#e8e8e8\"/>";
    s += std::string("<rect x=\"") + num(kLabel) + "\" y=\"" + num(y) + "\" width=\"" +
         num(kBar * share) + "\" height=\"22\" fill=\"" + task_colour(i) + "\"><title>" +
         html_escape(r.task + ": " + num(100.0 * share) + " %") + "</title></rect>";
    s += text(kLabel + kBar + 8.0, y + 17.0, "start",
              std::to_string(r.trainees_passed) + " of " + std::to_string(r.trainees) +
                  " trainees passed (" + std::to_string(r.sessions_passed) + " of " +
                  std::to_string(r.sessions) + " sessions)");
  }
  return s + "</svg>";
}

}  // namespace serosa::trainee
