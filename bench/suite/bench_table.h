// `serosa bench`: the data every part of the accuracy-versus-time suite returns.
// A part measures one or more knobs; for each knob setting it adds a row to a Table (accuracy
// and time side by side), names the Plots to draw from the tables (accuracy on one axis, time on
// the other), and the MonotoneChecks that must hold on accuracy (never on timings: they drift).
// The command (bench/suite/cmd_bench.cpp) writes every table as CSV, draws every plot with
// gnuplot, runs the checks and fails on a violated one.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace serosa::bench {

/// How a part runs.
struct BenchOptions {
  bool quick = false;         ///< small sizes and few repetitions: the CI smoke run (< 2 min)
  std::filesystem::path out;  ///< folder the CSV files and plots go to
  std::filesystem::path assets_dir;  ///< the project's assets/ folder (organ meshes)
};

/// One CSV file: a row per knob setting. Column names carry their unit ("ms_per_step",
/// "rel_error", "volume_lost_m3"); `setting` is the first CSV column, a human label of the knob
/// value ("cg tol=1e-4", "pattern").
struct Table {
  std::string name;                       ///< file stem: <out>/<name>.csv (unique in the run)
  std::vector<std::string> columns;       ///< numeric column names, with units
  std::vector<std::string> settings;      ///< one label per row
  std::vector<std::vector<double>> rows;  ///< rows × columns values

  /// Appends a row; throws std::invalid_argument when values.size() != columns.size().
  void add(std::string setting, std::vector<double> values);
  /// Index of a column; throws std::invalid_argument naming the table and column when missing.
  [[nodiscard]] std::size_t column(std::string_view name) const;
  /// The values of one column, in row order.
  [[nodiscard]] std::vector<double> values(std::string_view name) const;
  /// Writes `setting,<columns...>` then one line per row (values with 9 significant digits).
  void write_csv(const std::filesystem::path& file) const;
};

/// One line (or point cloud) in a plot: column `y` against column `x` of a table.
struct Series {
  std::string table;          ///< Table::name
  std::string x, y;           ///< column names
  std::string legend;         ///< key text
  bool points = false;        ///< points only (distinct methods), else lines with points (a sweep)
  bool label_points = false;  ///< write each row's setting next to its point
};

/// One PNG: <out>/<name>.png.
struct Plot {
  std::string name;
  std::string title;
  std::string x_label, y_label;  ///< with units
  bool log_x = false, log_y = false;
  std::vector<Series> series;
};

enum class Direction { increasing, decreasing };

/// Along the rows of `table` sorted by column `knob`, column `value` must be monotone in
/// `direction`, allowing each step to go the wrong way by at most rel_tol × |previous value|
/// (plus abs_tol). For accuracy only: "error falls as the iteration cap rises".
struct MonotoneCheck {
  std::string table, knob, value;
  Direction direction = Direction::decreasing;
  double rel_tol = 0.0;
  double abs_tol = 0.0;
  std::string why;  ///< one line saying what the check means, printed with its result
};

/// Everything one part measured.
struct PartResult {
  std::vector<Table> tables;
  std::vector<Plot> plots;
  std::vector<MonotoneCheck> checks;
  std::vector<std::string> notes;  ///< one-line readings printed in the summary
};

/// printf-formatted text of at most 63 characters (figures in notes and labels).
[[gnu::format(printf, 1, 2)]] std::string fmt_double(const char* format, ...);

/// The first violation of `check` on `table` as a message, or empty when it holds (or the table
/// has fewer than two rows).
[[nodiscard]] std::string check_monotone(const Table& table, const MonotoneCheck& check);

}  // namespace serosa::bench
