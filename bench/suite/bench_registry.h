// The parts `serosa bench` knows (bench/suite/bench_registry.cpp lists them, in run order) and the
// runner that executes a selection of them: runs each part, writes its tables as CSV, draws its
// plots with gnuplot, runs its monotonicity checks, and reports everything (summary.json).
#pragma once

#include <filesystem>
#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

#include "bench/suite/bench_table.h"

namespace serosa::bench {

/// One part: its command-line name and the function that measures it.
struct PartEntry {
  std::string name;
  std::function<PartResult(const BenchOptions&)> run;
};

/// Every part compiled into this build, in run order (bench_registry.cpp).
[[nodiscard]] const std::vector<PartEntry>& registered_parts();

/// How the runner runs.
struct RunnerOptions {
  BenchOptions bench;               ///< handed to each part (out = the output folder, created)
  bool plots = true;                ///< draw the plots with gnuplot (else only the .gp scripts)
  std::string gnuplot = "gnuplot";  ///< the gnuplot program (looked up on PATH)
};

/// The outcome of one MonotoneCheck.
struct CheckOutcome {
  MonotoneCheck check;
  std::string violation;  ///< empty when it holds
};

/// What running one part produced.
struct PartReport {
  std::string name;
  double wall_s = 0.0;              ///< wall time of the part's measurement, s
  std::string error;                ///< what the part threw (empty when it returned)
  std::vector<std::string> tables;  ///< CSV files written (paths)
  std::vector<std::string> plots;   ///< PNG files drawn (paths)
  std::vector<CheckOutcome> checks;
  std::vector<std::string> problems;  ///< empty tables, plots naming missing tables or
                                      ///< columns, gnuplot failures, checks that could not run
  std::vector<std::string> notes;     ///< the part's own readings
  /// Returned, every curve produced, every check held.
  [[nodiscard]] bool ok() const;
};

/// The whole run.
struct BenchReport {
  bool quick = false;
  std::filesystem::path out;
  double wall_s = 0.0;  ///< all parts together, s
  std::vector<PartReport> parts;
  [[nodiscard]] bool ok() const;
};

/// Whether `program` runs (`program --version` exits 0).
[[nodiscard]] bool program_runs(const std::string& program);

/// The gnuplot script that draws `plot` from the CSV files in its own folder into <plot.name>.png
/// (run from that folder). Throws std::invalid_argument when the plot names a table that is not
/// in `tables`, a column that table lacks, or has no series.
[[nodiscard]] std::string gnuplot_script(const Plot& plot, const std::vector<Table>& tables);

/// Runs `parts` in order (a part that throws is reported and the others still run), writing into
/// options.bench.out, which must exist. Progress and the summary go to `log`.
[[nodiscard]] BenchReport run_parts(const std::vector<PartEntry>& parts,
                                    const RunnerOptions& options, std::ostream& log);

/// Writes the report as JSON: {"ok", "quick", "wall_s", "parts": [{"name", "ok", "wall_s",
/// "error", "tables", "plots", "checks": [{"table", "knob", "value", "why", "ok", "violation"}],
/// "problems", "notes"}]}.
void write_summary_json(const BenchReport& report, const std::filesystem::path& file);

/// Prints the human summary: per part its wall time, files, checks (ok / FAILED and why), notes.
void print_summary(const BenchReport& report, std::ostream& os);

}  // namespace serosa::bench
