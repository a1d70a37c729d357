#include "bench/suite/bench_table.h"

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <fstream>
#include <numeric>
#include <stdexcept>

namespace serosa::bench {

std::string fmt_double(const char* format, ...) {
  char buf[64];
  va_list args;
  va_start(args, format);
  std::vsnprintf(buf, sizeof buf, format, args);
  va_end(args);
  return buf;
}

void Table::add(std::string setting, std::vector<double> values) {
  if (values.size() != columns.size()) {
    std::string msg = "bench table '";
    msg.append(name).append("': row '").append(setting).append("' has ");
    msg.append(std::to_string(values.size())).append(" values for ");
    msg.append(std::to_string(columns.size())).append(" columns");
    throw std::invalid_argument(msg);
  }
  settings.push_back(std::move(setting));
  rows.push_back(std::move(values));
}

std::size_t Table::column(std::string_view wanted) const {
  const auto it = std::find(columns.begin(), columns.end(), wanted);
  if (it == columns.end()) {
    std::string msg = "bench table '";
    msg.append(name).append("' has no column '").append(wanted).append("'");
    throw std::invalid_argument(msg);
  }
  return static_cast<std::size_t>(it - columns.begin());
}

std::vector<double> Table::values(std::string_view wanted) const {
  const std::size_t c = column(wanted);
  std::vector<double> out;
  out.reserve(rows.size());
  for (const auto& row : rows) out.push_back(row[c]);
  return out;
}

void Table::write_csv(const std::filesystem::path& file) const {
  std::ofstream os(file);
  if (!os) throw std::runtime_error("cannot write " + file.string());
  os << "setting";
  for (const auto& c : columns) os << ',' << c;
  os << '\n';
  char buf[64];
  for (std::size_t r = 0; r < rows.size(); ++r) {
    // Settings are labels; a comma or quote in one would break the CSV, so quote them all.
    os << '"';
    for (char ch : settings[r]) {
      if (ch == '"') os << '"';
      os << ch;
    }
    os << '"';
    for (double v : rows[r]) {
      std::snprintf(buf, sizeof buf, "%.9g", v);
      os << ',' << buf;
    }
    os << '\n';
  }
  if (!os) throw std::runtime_error("write failed: " + file.string());
}

std::string check_monotone(const Table& table, const MonotoneCheck& check) {
  const std::vector<double> knob = table.values(check.knob);
  const std::vector<double> value = table.values(check.value);
  std::vector<std::size_t> order(knob.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return knob[a] < knob[b]; });
  for (std::size_t i = 1; i < order.size(); ++i) {
    const double prev = value[order[i - 1]];
    const double cur = value[order[i]];
    if (!std::isfinite(prev) || !std::isfinite(cur)) {
      return table.name + ": " + check.value + " is not finite at '" + table.settings[order[i]] +
             "'";
    }
    const double slack = check.rel_tol * std::abs(prev) + check.abs_tol;
    const bool wrong =
        check.direction == Direction::decreasing ? cur > prev + slack : cur < prev - slack;
    if (wrong) {
      char buf[256];
      std::snprintf(buf, sizeof buf, "%s: %s goes %s from %.6g ('%s') to %.6g ('%s') as %s rises",
                    table.name.c_str(), check.value.c_str(),
                    check.direction == Direction::decreasing ? "up" : "down", prev,
                    table.settings[order[i - 1]].c_str(), cur, table.settings[order[i]].c_str(),
                    check.knob.c_str());
      return buf;
    }
  }
  return {};
}

}  // namespace serosa::bench
