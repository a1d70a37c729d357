#include "trainee/cohort_html.h"

#include "engine/shell_command.h"
#include "trainee/cohort_markup.h"
#include "trainee/cohort_svg.h"

namespace serosa::trainee {

namespace {

const char* const kStyle = R"(<style>
body { font-family: "DejaVu Sans", Verdana, sans-serif; font-size: 14px; color: #222;
       margin: 24px 32px; background: #fff; }
h1 { font-size: 24px; margin-bottom: 4px; }
h2 { font-size: 18px; margin-top: 32px; border-bottom: 2px solid #3a6ea5; padding-bottom: 3px; }
h3 { font-size: 15px; margin: 18px 0 6px; }
p.meta, p.note { color: #555; }
table { border-collapse: collapse; margin: 8px 0; }
th, td { border: 1px solid #ccc; padding: 4px 8px; text-align: left; vertical-align: top; }
th { background: #eef3f8; }
td.num { text-align: right; }
td.passed { background: #e4f4e6; }
td.failed { background: #fbe6e4; }
td.none { color: #999; background: #f6f6f6; }
span.yes { color: #1d7a30; font-weight: bold; }
span.no { color: #b3261e; font-weight: bold; }
span.missing { color: #b3261e; }
code { font-family: "DejaVu Sans Mono", monospace; font-size: 12px; background: #f3f3f3;
       padding: 1px 3px; }
svg text { font-family: "DejaVu Sans", Verdana, sans-serif; font-size: 11px; fill: #333; }
svg rect.plot { fill: #fafafa; stroke: #999; }
svg line.grid { stroke: #ddd; }
figure { display: inline-block; margin: 0 24px 16px 0; }
figcaption { font-weight: bold; margin-bottom: 4px; }
</style>
)";

std::string yes_no(bool yes) {
  return yes ? "<span class=\"yes\">yes</span>" : "<span class=\"no\">no</span>";
}

std::string plural(int n, const std::string& what) {
  return std::to_string(n) + " " + what + (n == 1 ? "" : "s");
}

bool there(const std::string& file) {
  std::error_code ec;
  return !file.empty() && std::filesystem::exists(file, ec);
}

std::string header(const Cohort& c, const PageContext& ctx) {
  std::string h = "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
  h += "<title>Serosa cohort progress</title>\n";
  h += kStyle;
  h += "</head>\n<body>\n<h1>Cohort progress</h1>\n<p class=\"meta\">";
  h += html_escape(plural(static_cast<int>(c.trainees.size()), "trainee") + ", " +
                   plural(c.sessions, "session") + ", " +
                   plural(static_cast<int>(c.tasks.size()), "task"));
  h += std::string(" &middot; database <code>") + html_escape(ctx.db.string()) +
       "</code> &middot; written " + html_escape(date_text(ctx.written_utc)) + "</p>\n";
  h += "<p class=\"meta\"><a href=\"#table\">trainees and tasks</a> &middot; <a "
       "href=\"#curves\">learning curves</a> &middot; <a href=\"#pass-rate\">pass rate</a> "
       "&middot; <a href=\"#criteria\">criteria missed</a> &middot; <a "
       "href=\"#sessions\">sessions</a></p>\n";
  return h;
}

std::string cell(const TaskProgress* p) {
  if (p == nullptr) return "<td class=\"none\">&ndash;</td>";
  std::string c = std::string("<td class=\"") + (p->passed > 0 ? "passed" : "failed") + "\">";
  c += html_escape(plural(p->sessions, "session")) + "<br>best " +
       html_escape(score_text(p->best)) + ", last " + html_escape(score_text(p->last)) +
       "<br>passed " + yes_no(p->passed > 0) + " / last " + yes_no(p->last_passed);
  return c + "</td>";
}

// (a) every trainee x every task.
std::string table_section(const Cohort& c) {
  std::string s =
      "<h2 id=\"table\">Trainees and tasks</h2>\n<table class=\"grid\">\n<tr><th>trainee</th>";
  for (const TaskPassRate& r : c.pass_rates)
    s += std::string("<th>") + html_escape(r.task) +
         (r.pass_score
              ? std::string("<br><small>pass ") + html_escape(score_text(r.pass_score)) + "</small>"
              : std::string()) +
         "</th>";
  s += "</tr>\n";
  for (const TraineeCohort& t : c.trainees) {
    s += std::string("<tr><th>") + html_escape(t.name) + "</th>";
    for (const std::string& task : c.tasks) s += cell(t.on(task));
    s += "</tr>\n";
  }
  return s +
         "</table>\n<p class=\"note\">passed: any session passed; last: the latest one "
         "did.</p>\n";
}

// (b) each trainee's learning curve.
std::string curves_section(const Cohort& c) {
  std::string s =
      "<h2 id=\"curves\">Learning curves</h2>\n<p class=\"note\">Score against the "
      "trainee's session number, one line per task; the dashed line is the task's "
      "pass score, a green ring a pass.</p>\n";
  for (const TraineeCohort& t : c.trainees)
    s += std::string("<figure><figcaption>") + html_escape(t.name) + "</figcaption>" +
         learning_curve_svg(t, c.tasks) + "</figure>\n";
  return s;
}

// (c) the group's pass rate per task.
std::string pass_rate_section(const Cohort& c) {
  return std::string(
             "<h2 id=\"pass-rate\">Pass rate per task</h2>\n<p class=\"note\">Of the "
             "trainees who practised a task, the share who passed it at least "
             "once.</p>\n") +
         pass_rate_svg(c.pass_rates) + "\n";
}

// (d) the criteria most often missed.
std::string criteria_section(const Cohort& c) {
  std::string s = "<h2 id=\"criteria\">Criteria most often missed</h2>\n";
  if (c.criteria.empty()) return s + "<p>No session missed a criterion.</p>\n";
  s += "<table>\n<tr><th>criterion</th><th>sessions that missed it</th><th>of which it failed "
       "the session</th><th>tasks</th></tr>\n";
  for (const CriterionCount& n : c.criteria) {
    std::string tasks;
    for (const std::string& t : n.tasks) tasks.append(tasks.empty() ? "" : ", ").append(t);
    s += std::string("<tr><td><code>") + html_escape(n.criterion) +
         "</code></td><td class=\"num\">" + std::to_string(n.sessions) + "</td><td class=\"num\">" +
         std::to_string(n.failing) + "</td><td>" + html_escape(tasks) + "</td></tr>\n";
  }
  s += "</table>\n<p class=\"note\">Counted once per session that had it on its assessment's "
       "failed or below-threshold list.";
  if (c.reasons_unknown > 0)
    s += std::string(" ") + html_escape(plural(c.reasons_unknown, "failed session")) +
         " could not be counted: the report had gone when the database was upgraded.";
  return s + "</p>\n";
}

std::string file_cell(const std::string& file, const PageContext& ctx, const std::string& what) {
  if (file.empty()) return std::string("<td class=\"none\">not ") + what + "</td>";
  if (!there(file))
    return std::string("<td><span class=\"missing\">missing</span> (was <code>") +
           html_escape(file) + "</code>)</td>";
  return std::string("<td><a href=\"") + html_escape(file_href(file, ctx.page_dir)) + "\">" +
         html_escape(std::filesystem::path(file).filename().string()) + "</a></td>";
}

std::string session_row(std::size_t number, const SessionRecord& s, const PageContext& ctx) {
  std::string r = std::string("<tr><td class=\"num\">") + std::to_string(number) + "</td><td>" +
                  html_escape(date_text(s.started_utc)) + "</td><td>" + html_escape(s.task) +
                  "</td><td class=\"num\">" + html_escape(score_text(s.score)) + "</td><td>" +
                  (s.passed ? yes_no(*s.passed) : std::string("&ndash;")) + "</td><td>" +
                  html_escape(why_failed(s)) + "</td>";
  r += file_cell(s.recording, ctx, "recorded") + file_cell(s.report, ctx, "written");
  r += std::string("<td>") +
       (there(s.recording)
            ? std::string("<code>") +
                  html_escape(std::string("serosa replay ") + shell_quote(s.recording)) + "</code>"
            : std::string("&ndash;")) +
       "</td></tr>\n";
  return r;
}

// (e) every session.
std::string sessions_section(const Cohort& c, const PageContext& ctx) {
  std::string s = "<h2 id=\"sessions\">Every session</h2>\n";
  for (const TraineeCohort& t : c.trainees) {
    s += std::string("<h3>") + html_escape(t.name) +
         "</h3>\n<table>\n<tr><th>#</th><th>started</th>"
         "<th>task</th><th>score</th><th>passed</th><th>why it failed</th><th>recording</th>"
         "<th>report</th><th>replay</th></tr>\n";
    for (std::size_t i = 0; i < t.sessions.size(); ++i) s += session_row(i + 1, t.sessions[i], ctx);
    s += "</table>\n";
  }
  return s;
}

}  // namespace

std::string cohort_html(const Cohort& cohort, const PageContext& context) {
  std::string page = header(cohort, context);
  if (cohort.trainees.empty())
    return page +
           "<p>No sessions yet: `serosa headless` or `serosa run` with --trainee NAME "
           "files them.</p>\n</body>\n</html>\n";
  page += table_section(cohort);
  page += curves_section(cohort);
  page += pass_rate_section(cohort);
  page += criteria_section(cohort);
  page += sessions_section(cohort, context);
  return page + "</body>\n</html>\n";
}

std::vector<std::string> missing_files(const Cohort& cohort) {
  std::vector<std::string> out;
  for (const TraineeCohort& t : cohort.trainees)
    for (const SessionRecord& s : t.sessions)
      for (const std::string& f : {s.recording, s.report})
        if (!f.empty() && !there(f)) out.push_back(f);
  return out;
}

}  // namespace serosa::trainee
