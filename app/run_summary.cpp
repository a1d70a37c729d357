#include "app/run_summary.h"

#include <cstdio>

namespace serosa::app {
namespace {

using Json = nlohmann::json;

// One "label  text" line, labels in one column.
void line(std::string& out, const char* label, const std::string& text) {
  char head[16];
  std::snprintf(head, sizeof head, "%-11s", label);
  out.append(head).append(text).push_back('\n');
}

// printf into a std::string; the format is checked at each call (a literal there).
#define SEROSA_FMT(buf, ...) (std::snprintf(buf, sizeof buf, __VA_ARGS__), std::string(buf))

std::string procedure_line(const Json& procedure) {
  const Json& steps = procedure.value("steps", Json::array());
  std::size_t done = 0;
  std::string missing;
  for (const Json& s : steps) {
    if (s.value("done", false)) {
      ++done;
    } else {
      missing.append(missing.empty() ? "; not done: " : ", ").append(s.value("name", "?"));
    }
  }
  std::string text = procedure.value("completed", false) ? "completed" : "NOT completed";
  text.append(", ")
      .append(std::to_string(done))
      .append(" of ")
      .append(std::to_string(steps.size()))
      .append(" steps")
      .append(missing);
  return text;
}

std::string score_line(const Json& a) {
  char buf[64];
  std::string text = SEROSA_FMT(buf, "%.1f / 100 (pass %.0f): ", a.value("score", 0.0),
                                a.value("pass_score", 0.0));
  text.append(a.value("passed", false) ? "passed" : "not passed");
  const Json& failed = a.value("failed", Json::array());
  if (!failed.empty() && failed[0].is_string())
    text.append("; ").append(failed[0].get<std::string>());
  return text;
}

void outputs(std::string& out, const Json& r, const SummaryPaths& paths) {
  line(out, "report",
       paths.report ? paths.report->string() : "not written (--report FILE, or --json)");
  if (paths.frames)
    line(out, "pictures",
         paths.frames->string() + " (" + std::to_string(r.value("frames", Json::array()).size()) +
             " PNG)");
  if (r.contains("export_final")) line(out, "mesh", r["export_final"].get<std::string>());
  if (r.contains("recording"))
    line(out, "recording", r["recording"].value("file", std::string("?")));
  if (r.contains("series")) line(out, "series", r["series"].get<std::string>());
  if (r.contains("vtu_series"))
    line(out, "vtu series", r["vtu_series"].value("folder", std::string("?")));
}

}  // namespace

std::string run_summary(const Json& r, const SummaryPaths& paths) {
  std::string out;
  char buf[128];
  const Json& mesh = r.value("mesh_initial", Json::object());
  line(out, "scene",
       r.value("scene", std::string("?")) + " (" + std::to_string(mesh.value("tets", 0)) +
           " tets, " + std::to_string(mesh.value("nodes", 0)) + " nodes)");
  std::string steps = std::to_string(r.value("steps_taken", 0)) + " of " +
                      std::to_string(r.value("steps", 0)) +
                      SEROSA_FMT(buf, " (%.2f s simulated)", r.value("simulated_time_s", 0.0));
  if (r.value("interrupted", false)) steps.append(", interrupted");
  line(out, "steps", steps);
  if (r.contains("procedure")) line(out, "procedure", procedure_line(r["procedure"]));
  if (r.contains("assessment")) line(out, "score", score_line(r["assessment"]));
  const Json& st = r.value("step_time_ms", Json::object());
  line(out, "real time",
       SEROSA_FMT(buf, "%.2fx (step p99 %.1f ms, max %.1f ms, dt %.1f ms)",
                  r.value("real_time_factor", 0.0), st.value("p99", 0.0), st.value("max", 0.0),
                  1e3 * r.value("dt_s", 0.0)));
  const Json& warnings = r.value("warnings", Json::array());
  line(out, "warnings",
       warnings.empty() ? "none"
                        : std::to_string(warnings.size()) +
                              "; the first: " + warnings[0].value("text", std::string("?")));
  outputs(out, r, paths);
  return out;
}

}  // namespace serosa::app
