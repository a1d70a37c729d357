#include "batch/batch_summary.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>

#include "engine/shell_command.h"

namespace serosa::batch {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

std::string xml(const std::string& s) {
  std::string o;
  for (char c : s) {
    switch (c) {
      case '&':
        o += "&amp;";
        break;
      case '<':
        o += "&lt;";
        break;
      case '>':
        o += "&gt;";
        break;
      case '"':
        o += "&quot;";
        break;
      default:
        o += c;
    }
  }
  return o;
}

void write_junit(const Json& summary, const fs::path& file) {
  std::ofstream out(file);
  const Json& runs = summary["runs"];
  out << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  out << "<testsuites name=\"serosa batch\" tests=\"" << runs.size() << "\" failures=\""
      << summary["failed"].get<int>() << "\">\n";
  out << "  <testsuite name=\"" << xml(summary["title"].get<std::string>()) << "\" tests=\""
      << runs.size() << "\" failures=\"" << summary["failed"].get<int>() << "\">\n";
  for (const Json& r : runs) {
    out << "    <testcase classname=\"" << xml(r.value("group", "")) << "\" name=\""
        << xml(r.value("id", "")) << "\" time=\"" << r.value("wall_s", 0.0) << "\">";
    if (r.value("status", "") != "passed")
      out << "\n      <failure message=\""
          << xml(r.value("status", "") + ": " + r.value("reason", ""))
          << "\">log: " << xml(r.value("log", "")) << "</failure>\n    ";
    out << "</testcase>\n";
  }
  out << "  </testsuite>\n</testsuites>\n";
}

// Every number among a report's metrics, by its path ("path_length_m/grasper").
void numbers(const Json& j, const std::string& prefix, std::map<std::string, double>& out) {
  if (j.is_number()) out[prefix] = j.get<double>();
  if (!j.is_object()) return;
  for (const auto& [k, v] : j.items()) numbers(v, prefix.empty() ? k : prefix + "/" + k, out);
}

struct Spread {
  double min = 0.0, max = 0.0, mean = 0.0;
  int n = 0;
};

// Per group with seeds: per metric, its spread over the seeds' runs.
std::map<std::string, std::map<std::string, Spread>> spreads(const Json& runs) {
  std::map<std::string, std::vector<std::map<std::string, double>>> by_group;
  for (const Json& r : runs)
    if (!r.value("seed", Json(nullptr)).is_null() && r.contains("metrics")) {
      std::map<std::string, double> m;
      numbers(r["metrics"], "", m);
      by_group[r.value("group", "")].push_back(std::move(m));
    }
  std::map<std::string, std::map<std::string, Spread>> out;
  for (const auto& [group, list] : by_group)
    for (const auto& m : list)
      for (const auto& [k, v] : m) {
        Spread& s = out[group][k];
        s.min = s.n == 0 ? v : std::min(s.min, v);
        s.max = s.n == 0 ? v : std::max(s.max, v);
        s.mean = (s.mean * s.n + v) / (s.n + 1);
        ++s.n;
      }
  return out;
}

// Draws the bar charts; returns what to say in the page when it could not.
std::string plot(const Json& runs, const std::map<std::string, std::map<std::string, Spread>>& sp,
                 const fs::path& out, const std::string& gnuplot) {
  std::ofstream(out / "runs.dat") << [&] {
    std::ostringstream d;
    for (const Json& r : runs) {
      const Json rtf = r.value("real_time_factor", Json(nullptr));
      d << '"' << r.value("id", "") << "\" " << r.value("wall_s", 0.0) << ' '
        << (rtf.is_number() ? rtf.get<double>() : 0.0) << '\n';
    }
    return d.str();
  }();
  std::ofstream(out / "spread.dat") << [&] {
    std::ostringstream d;  // the relative spread (max - min) / |mean| of each metric, per group
    for (const auto& [group, metrics] : sp)
      for (const auto& [k, s] : metrics)
        if (std::abs(s.mean) > 0.0)
          d << '"' << group << ':' << k << "\" " << (s.max - s.min) / std::abs(s.mean) << '\n';
    return d.str();
  }();
  const fs::path gp = out / "plots.gp";
  std::ofstream(gp) << "set terminal pngcairo size 1000,500\nset style fill solid 0.6\n"
                       "set boxwidth 0.7\nset xtics rotate by -40 noenhanced\nset grid ytics\n"
                       "set output "
                    << gp_quote((out / "time.png").string())
                    << "\nset ylabel 'wall time per run (s)'\n"
                       "plot "
                    << gp_quote((out / "runs.dat").string())
                    << " using 2:xtic(1) with boxes notitle\n"
                       "set output "
                    << gp_quote((out / "real_time_factor.png").string())
                    << "\nset ylabel 'real-time factor'\n"
                       "plot "
                    << gp_quote((out / "runs.dat").string())
                    << " using 3:xtic(1) with boxes notitle\n"
                    << (sp.empty() ? ""
                                   : "set output " + gp_quote((out / "spread.png").string()) +
                                         "\nset ylabel '(max - min) / mean over the seeds'\n"
                                         "plot " +
                                         gp_quote((out / "spread.dat").string()) +
                                         " using 2:xtic(1) with boxes notitle\n");
  const Command c = run_command(shell_quote(gnuplot) + " " + shell_quote(gp.string()));
  if (c.code != 0) return "The plots could not be drawn: " + first_line(c.output);
  return "";
}

void write_markdown(const Json& summary,
                    const std::map<std::string, std::map<std::string, Spread>>& sp,
                    const std::string& plot_note, const fs::path& file) {
  std::ofstream md(file);
  md << "# " << summary["title"].get<std::string>() << "\n\n"
     << summary["passed"].get<int>() << " of " << summary["runs"].size() << " runs passed ("
     << summary["manifest"].get<std::string>() << ").\n\n"
     << "| run | status | wall time (s) | real-time factor | golden | reason |\n"
     << "|---|---|---|---|---|---|\n";
  char buf[64];
  for (const Json& r : summary["runs"]) {
    const Json rtf = r.value("real_time_factor", Json(nullptr));
    std::snprintf(buf, sizeof buf, "%.1f", r.value("wall_s", 0.0));
    md << "| " << r.value("id", "") << " | " << r.value("status", "") << " | " << buf << " | ";
    if (rtf.is_number()) {
      std::snprintf(buf, sizeof buf, "%.2f", rtf.get<double>());
      md << buf;
    }
    md << " | " << r.value("golden", "") << " | " << r.value("reason", "") << " |\n";
  }
  md << "\n"
     << (plot_note.empty()
             ? "![time per run](time.png)\n\n![real-time factor](real_time_factor.png)\n"
             : plot_note + "\n");
  if (sp.empty()) return;
  md << "\n## Spread across seeds\n\n";
  if (plot_note.empty()) md << "![spread](spread.png)\n\n";
  for (const auto& [group, metrics] : sp) {
    md << "### " << group << "\n\n| metric | min | mean | max | seeds |\n|---|---|---|---|---|\n";
    for (const auto& [k, s] : metrics) {
      if (s.min == 0.0 && s.max == 0.0) continue;  // nothing measured there
      std::snprintf(buf, sizeof buf, "%.6g | %.6g | %.6g", s.min, s.mean, s.max);
      md << "| " << k << " | " << buf << " | " << s.n << " |\n";
    }
    md << '\n';
  }
}

}  // namespace

Json write_batch_summary(const BatchManifest& m, std::vector<Json> results, const fs::path& out,
                         const std::string& gnuplot) {
  int passed = 0;
  for (std::size_t i = 0; i < results.size(); ++i) {
    if (results[i].is_null() || !results[i].is_object())
      results[i] = {
          {"id", m.runs[i].id},
          {"group", m.runs[i].group},
          {"status", "failed"},
          {"reason", "no result: the run never finished (its task died or was cancelled)"}};
    passed += results[i].value("status", "") == "passed" ? 1 : 0;
  }
  Json summary{{"manifest", m.file.string()},
               {"title", m.title.empty() ? std::string("serosa batch") : m.title},
               {"passed", passed},
               {"failed", static_cast<int>(results.size()) - passed},
               {"runs", results}};
  fs::create_directories(out);
  std::ofstream(out / "summary.json") << summary.dump(2) << '\n';
  write_junit(summary, out / "junit.xml");
  const auto sp = spreads(summary["runs"]);
  write_markdown(summary, sp, plot(summary["runs"], sp, out, gnuplot), out / "summary.md");
  return summary;
}

}  // namespace serosa::batch
