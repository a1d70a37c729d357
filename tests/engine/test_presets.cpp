// Presets pick from the measured curves (engine/presets.h): the compiled-in curves equal the CSV
// files of the bench runs they were copied from, and the choice is the cheapest point within the
// target for every target.
#include "engine/presets.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace serosa {
namespace {

// Rows of a CSV file as string cells; '#' lines skipped, quotes stripped.
std::vector<std::vector<std::string>> read_csv(const std::string& path) {
  std::ifstream is(path);
  EXPECT_TRUE(is) << path;
  std::vector<std::vector<std::string>> rows;
  std::string line;
  while (std::getline(is, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> cells;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) {
      std::string clean;
      for (char c : cell)
        if (c != '"') clean.push_back(c);
      cells.push_back(clean);
    }
    rows.push_back(cells);
  }
  return rows;
}

std::string plots(const char* name) {
  return std::string(SEROSA_SOURCE_DIR) + "/docs/plots/" + name;
}

TEST(Presets, SolverCurveIsTheMeasuredOne) {
  // setting,family,ms_per_step,error_percent
  std::map<std::string, std::pair<double, double>> measured;
  for (const auto& row : read_csv(plots("fem_accuracy.csv"))) {
    ASSERT_EQ(row.size(), 4u);
    measured[row[0]] = {std::stod(row[2]), std::stod(row[3]) / 100.0};
  }
  ASSERT_EQ(measured.size(), solver_curve().size());
  for (const SolverCurvePoint& p : solver_curve()) {
    const auto it = measured.find(std::string(p.setting));
    ASSERT_NE(it, measured.end()) << p.setting;
    EXPECT_DOUBLE_EQ(p.ms_per_step, it->second.first) << p.setting;
    EXPECT_NEAR(p.rel_error, it->second.second, 1e-12 + 1e-9 * it->second.second) << p.setting;
  }
}

TEST(Presets, TessellationCurveIsTheMeasuredOne) {
  // The once-subdivided icosahedron: subdiv:1 rows of both render CSVs.
  std::map<int, double> distance, frame_ms;
  for (const auto& row : read_csv(plots("render_phong_accuracy.csv"))) {
    if (row[0].find("/subdiv:1") == std::string::npos) continue;
    distance[std::stoi(row[0].substr(row[0].find("level:") + 6))] = std::stod(row[12]);
  }
  for (const auto& row : read_csv(plots("render_frame_time.csv"))) {
    if (row[0].find("/subdiv:1/") == std::string::npos) continue;
    frame_ms[std::stoi(row[0].substr(row[0].find("level:") + 6))] = std::stod(row[2]);
  }
  ASSERT_EQ(distance.size(), tessellation_curve().size());
  for (const TessellationCurvePoint& p : tessellation_curve()) {
    EXPECT_DOUBLE_EQ(p.mean_rel_distance, distance.at(p.level)) << p.level;
    EXPECT_DOUBLE_EQ(p.frame_ms, frame_ms.at(p.level)) << p.level;
  }
}

TEST(Presets, ChoiceIsTheCheapestPointWithinTheTarget) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> log10_target(-11.0, 0.0);
  for (int i = 0; i < 5000; ++i) {
    const double target = std::pow(10.0, log10_target(rng));
    const PresetChoice c = choose_preset(target, std::nullopt);
    ASSERT_NE(c.solver, nullptr);
    EXPECT_EQ(c.tessellation, nullptr);
    bool any = false;
    for (const SolverCurvePoint& p : solver_curve()) {
      if (p.rel_error <= target) {
        any = true;
        EXPECT_GE(p.ms_per_step, c.solver->ms_per_step) << target << " " << p.setting;
      }
      if (!c.target_met) {
        EXPECT_GE(p.rel_error, c.solver->rel_error);
      }
    }
    EXPECT_EQ(any, c.target_met) << target;
    if (c.target_met) {
      EXPECT_LE(c.solver->rel_error, target);
    }
  }
}

TEST(Presets, TighterTargetsNeverCostLessOrDeliverLess) {
  double prev_ms = 0.0;
  for (double target = 1.0; target > 1e-12; target /= 1.5) {
    const PresetChoice c = choose_preset(target, std::nullopt);
    EXPECT_GE(c.solver->ms_per_step, prev_ms) << target;
    prev_ms = c.solver->ms_per_step;
  }
  const Quality order[] = {Quality::kFast, Quality::kBalanced, Quality::kAccurate};
  for (int i = 0; i + 1 < 3; ++i) {
    const PresetChoice a = choose_preset(quality_accuracy_target(order[i]), order[i]);
    const PresetChoice b = choose_preset(quality_accuracy_target(order[i + 1]), order[i + 1]);
    EXPECT_TRUE(a.target_met && b.target_met);
    EXPECT_LE(a.solver->ms_per_step, b.solver->ms_per_step);
    EXPECT_GE(a.solver->rel_error, b.solver->rel_error);
    ASSERT_NE(a.tessellation, nullptr);
    ASSERT_NE(b.tessellation, nullptr);
    EXPECT_GE(a.tessellation->mean_rel_distance, b.tessellation->mean_rel_distance);
  }
}

TEST(Presets, AppliedSettingsAreRunnable) {
  for (const Quality q : {Quality::kFast, Quality::kBalanced, Quality::kAccurate}) {
    const PresetChoice c = choose_preset(quality_accuracy_target(q), q);
    SolverSettings solver;
    RenderSettings render;
    apply_preset(c, solver, render);
    EXPECT_GT(solver.tolerance, 0.0);  // the loader's own range
    EXPECT_LT(solver.tolerance, 1.0);
    EXPECT_EQ(solver.max_iterations, c.solver->max_iterations);
    EXPECT_EQ(render.tessellation, c.tessellation->level);
  }
}

}  // namespace
}  // namespace serosa
