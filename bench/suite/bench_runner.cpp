// The runner of `serosa bench` (bench_registry.h): parts in order, then for each its CSV files,
// gnuplot scripts and PNGs, and its monotonicity checks.
#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <nlohmann/json.hpp>
#include <ostream>
#include <set>
#include <stdexcept>

#include "bench/suite/bench_registry.h"
#include "engine/shell_command.h"

namespace serosa::bench {

namespace fs = std::filesystem;

namespace {

const Table* find_table(const std::vector<Table>& tables, const std::string& name) {
  const auto it =
      std::find_if(tables.begin(), tables.end(), [&](const Table& t) { return t.name == name; });
  return it == tables.end() ? nullptr : &*it;
}

// "$3" or, on a log axis, "($3 > 0 ? $3 : 1/0)" (gnuplot skips the point).
std::string gp_column(std::size_t csv_column, bool log_axis) {
  const std::string c = "$" + std::to_string(csv_column);
  if (!log_axis) return "(" + c + ")";
  std::string s = "(";
  s.append(c).append(" > 0 ? ").append(c).append(" : 1/0)");
  return s;
}

// Writes, draws and checks what one part returned.
void process(const PartResult& result, const RunnerOptions& options, std::set<std::string>& names,
             PartReport& report) {
  const fs::path& out = options.bench.out;
  report.notes = result.notes;
  for (const Table& t : result.tables) {
    if (t.name.empty() || !names.insert(t.name).second) {
      report.problems.push_back("table name '" + t.name + "' is empty or used twice in this run");
      continue;
    }
    if (t.rows.empty()) report.problems.push_back("table '" + t.name + "' has no rows");
    try {
      const fs::path file = out / (t.name + ".csv");
      t.write_csv(file);
      report.tables.push_back(file.string());
    } catch (const std::exception& e) {
      report.problems.push_back(e.what());
    }
  }
  for (const Plot& p : result.plots) {
    std::string script;
    try {
      script = gnuplot_script(p, result.tables);
    } catch (const std::exception& e) {
      report.problems.push_back(e.what());
      continue;
    }
    bool empty = false;
    for (const Series& s : p.series) {
      const Table* t = find_table(result.tables, s.table);
      if (t != nullptr && t->rows.empty()) empty = true;
    }
    if (empty) {
      report.problems.push_back("plot '" + p.name + "' draws an empty table");
      continue;
    }
    const fs::path gp = out / (p.name + ".gp");
    {
      std::ofstream os(gp);
      os << script;
      if (!os) {
        report.problems.push_back("cannot write " + gp.string());
        continue;
      }
    }
    if (!options.plots) continue;
    const fs::path png = out / (p.name + ".png");
    fs::remove(png);
    std::string cmd = "cd ";
    cmd.append(shell_quote(out.string())).append(" && ").append(shell_quote(options.gnuplot));
    cmd.append(" ").append(shell_quote(p.name + ".gp"));
    const Command r = run_command(cmd);
    if (r.code != 0) {
      report.problems.push_back("gnuplot failed on " + gp.string() + ": " + first_line(r.output));
    } else if (r.output.find("no valid points") != std::string::npos) {
      report.problems.push_back("plot '" + p.name + "': a series has no valid points (" +
                                first_line(r.output) + ")");
    } else if (!fs::exists(png) || fs::file_size(png) == 0) {
      report.problems.push_back("gnuplot wrote no " + png.string());
    } else {
      report.plots.push_back(png.string());
    }
  }
  for (const MonotoneCheck& c : result.checks) {
    const Table* t = find_table(result.tables, c.table);
    if (t == nullptr) {
      report.problems.push_back("check '" + c.why + "' names a missing table '" + c.table + "'");
      continue;
    }
    try {
      report.checks.push_back({c, check_monotone(*t, c)});
    } catch (const std::exception& e) {
      report.problems.push_back("check '" + c.why + "': " + e.what());
    }
  }
}

}  // namespace

bool PartReport::ok() const {
  return error.empty() && problems.empty() &&
         std::all_of(checks.begin(), checks.end(),
                     [](const CheckOutcome& c) { return c.violation.empty(); });
}

bool BenchReport::ok() const {
  return std::all_of(parts.begin(), parts.end(), [](const PartReport& p) { return p.ok(); });
}

bool program_runs(const std::string& program) {
  const std::string cmd = shell_quote(program) + " --version > /dev/null 2>&1";
  const int status = std::system(cmd.c_str());
  return status != -1 && WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

std::string gnuplot_script(const Plot& plot, const std::vector<Table>& tables) {
  if (plot.series.empty()) throw std::invalid_argument("plot '" + plot.name + "' has no series");
  std::string s = "# ";
  s.append(plot.title).append("\n# Drawn by `serosa bench` from the CSV files beside it: gnuplot ");
  s.append(plot.name).append(".gp\n");
  s.append("set terminal pngcairo noenhanced size 1000,650 font ',10'\n");
  s.append("set output ").append(gp_quote(plot.name + ".png")).append("\n");
  s.append("set datafile separator ','\n");
  s.append("set title ").append(gp_quote(plot.title)).append("\n");
  s.append("set xlabel ").append(gp_quote(plot.x_label)).append("\n");
  s.append("set ylabel ").append(gp_quote(plot.y_label)).append("\n");
  s.append("set grid\nset key below\n");
  if (plot.log_x) s.append("set logscale x\n");
  if (plot.log_y) s.append("set logscale y\nset format y '%.0e'\n");
  std::string cmd = "plot ";
  bool first = true;
  for (const Series& series : plot.series) {
    const Table* t = find_table(tables, series.table);
    if (t == nullptr)
      throw std::invalid_argument("plot '" + plot.name + "' names a missing table '" +
                                  series.table + "'");
    // CSV column k+2 holds Table column k (column 1 is the setting).
    const std::size_t cx = t->column(series.x) + 2;
    const std::size_t cy = t->column(series.y) + 2;
    const std::string file = gp_quote(t->name + ".csv");
    const std::string use = gp_column(cx, plot.log_x) + ":" + gp_column(cy, plot.log_y);
    if (!first) cmd.append(", \\\n     ");
    first = false;
    cmd.append(file).append(" skip 1 using ").append(use);
    cmd.append(series.points ? " with points pointsize 1.5" : " with linespoints");
    cmd.append(" title ").append(gp_quote(series.legend));
    if (series.label_points) {
      cmd.append(", \\\n     ").append(file).append(" skip 1 using ").append(use);
      cmd.append(":1 with labels offset char 1,0.6 left font ',8' notitle");
    }
  }
  s.append(cmd).append("\n");
  return s;
}

BenchReport run_parts(const std::vector<PartEntry>& parts, const RunnerOptions& options,
                      std::ostream& log) {
  BenchReport report;
  report.quick = options.bench.quick;
  report.out = options.bench.out;
  std::set<std::string> names;
  const auto t_all = std::chrono::steady_clock::now();
  for (const PartEntry& part : parts) {
    PartReport r;
    r.name = part.name;
    log << "bench: running " << part.name << (options.bench.quick ? " (quick)" : "") << " ..."
        << std::endl;
    const auto t0 = std::chrono::steady_clock::now();
    PartResult result;
    try {
      result = part.run(options.bench);
    } catch (const std::exception& e) {
      r.error = e.what();
    } catch (...) {
      r.error = "unknown exception";
    }
    r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (r.error.empty()) process(result, options, names, r);
    report.parts.push_back(std::move(r));
  }
  report.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_all).count();
  return report;
}

void write_summary_json(const BenchReport& report, const fs::path& file) {
  nlohmann::json j;
  j["ok"] = report.ok();
  j["quick"] = report.quick;
  j["wall_s"] = report.wall_s;
  j["parts"] = nlohmann::json::array();
  for (const PartReport& p : report.parts) {
    nlohmann::json jp;
    jp["name"] = p.name;
    jp["ok"] = p.ok();
    jp["wall_s"] = p.wall_s;
    jp["error"] = p.error;
    jp["tables"] = p.tables;
    jp["plots"] = p.plots;
    jp["checks"] = nlohmann::json::array();
    for (const CheckOutcome& c : p.checks)
      jp["checks"].push_back({{"table", c.check.table},
                              {"knob", c.check.knob},
                              {"value", c.check.value},
                              {"why", c.check.why},
                              {"ok", c.violation.empty()},
                              {"violation", c.violation}});
    jp["problems"] = p.problems;
    jp["notes"] = p.notes;
    j["parts"].push_back(std::move(jp));
  }
  std::ofstream os(file);
  os << j.dump(2) << '\n';
  if (!os) throw std::runtime_error("cannot write " + file.string());
}

void print_summary(const BenchReport& report, std::ostream& os) {
  char buf[64];
  for (const PartReport& p : report.parts) {
    std::snprintf(buf, sizeof buf, "%.1f s", p.wall_s);
    os << "== " << p.name << "  " << buf << "  " << (p.ok() ? "ok" : "FAILED") << '\n';
    if (!p.error.empty()) os << "   ERROR: the part threw: " << p.error << '\n';
    for (const auto& t : p.tables) os << "   table  " << t << '\n';
    for (const auto& g : p.plots) os << "   plot   " << g << '\n';
    for (const CheckOutcome& c : p.checks) {
      os << (c.violation.empty() ? "   check ok      " : "   check FAILED  ") << c.check.why;
      if (!c.violation.empty()) os << "\n                 " << c.violation;
      os << '\n';
    }
    for (const auto& q : p.problems) os << "   PROBLEM " << q << '\n';
    for (const auto& n : p.notes) os << "   note   " << n << '\n';
  }
  std::snprintf(buf, sizeof buf, "%.1f s", report.wall_s);
  os << "bench: " << report.parts.size() << " part(s) in " << buf << ": "
     << (report.ok() ? "every curve produced, every check held"
                     : "FAILED (see ERROR / check FAILED / PROBLEM above)")
     << '\n';
}

}  // namespace serosa::bench
