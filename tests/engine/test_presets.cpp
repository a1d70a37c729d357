// Presets pick from the measured curves (engine/scene/presets.h): the compiled-in curves equal the
// CSV files of the bench runs they were copied from, and the choice is the cheapest point within
// the target for every target.
#include "engine/scene/presets.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>
#include "support/test_paths.h"

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
  return std::string(::serosa::test_paths::source_dir()) + "/docs/plots/" + name;
}

// One `serosa bench` CSV as maps column name -> cell, one per row.
std::vector<std::map<std::string, std::string>> read_table(const char* name) {
  const auto rows = read_csv(plots(name));
  std::vector<std::map<std::string, std::string>> out;
  for (std::size_t r = 1; r < rows.size(); ++r) {
    std::map<std::string, std::string> m;
    for (std::size_t c = 0; c < rows[0].size() && c < rows[r].size(); ++c)
      m[rows[0][c]] = rows[r][c];
    out.push_back(m);
  }
  return out;
}

TEST(Presets, SolverCurveIsTheMeasuredOne) {
  struct Source {
    const char* file;
    const char* prefix;  // the curve's label = prefix + the CSV's setting
    SolverKind kind;
  };
  const Source sources[] = {
      {"bench_fem_cg_cap.csv", "", SolverKind::kPcg},
      {"bench_fem_cg_tolerance.csv", "", SolverKind::kPcg},
      {"bench_fem_cholmod_pcg_cap.csv", "pcg-cholmod ", SolverKind::kPcgCholmod}};
  std::size_t rows = 0;
  for (const Source& src : sources) {
    for (const auto& row : read_table(src.file)) {
      ++rows;
      const std::string label = src.prefix + row.at("setting");
      const SolverCurvePoint* p = nullptr;
      for (const SolverCurvePoint& q : solver_curve())
        if (q.setting == label) p = &q;
      ASSERT_NE(p, nullptr) << src.file << ": " << label << " is not in engine/scene/presets.cpp";
      EXPECT_EQ(p->kind, src.kind) << label;
      EXPECT_NEAR(p->ms_per_step, std::stod(row.at("ms_per_step")), 1e-6) << label;
      const double e = std::stod(row.at("rel_error"));
      EXPECT_NEAR(p->rel_error, e, 1e-8 * e + 1e-15) << label;
      if (row.count("max_iterations")) {
        EXPECT_EQ(p->max_iterations, std::stoi(row.at("max_iterations"))) << label;
      }
      if (row.count("tolerance")) {
        EXPECT_NEAR(p->tolerance, std::stod(row.at("tolerance")), 1e-12) << label;
      }
    }
  }
  const auto cholmod = read_table("bench_fem_cholmod.csv");
  ASSERT_EQ(cholmod.size(), 1u);
  const SolverCurvePoint& last = solver_curve().back();
  EXPECT_EQ(last.kind, SolverKind::kCholmod);
  EXPECT_NEAR(last.ms_per_step, std::stod(cholmod[0].at("ms_per_step")), 1e-6);
  EXPECT_EQ(rows + 1, solver_curve().size());  // nothing in the curve that was not measured
}

TEST(Presets, TessellationCurveIsTheMeasuredOne) {
  const auto rows = read_table("bench_tessellation_sphere.csv");
  ASSERT_EQ(rows.size(), tessellation_curve().size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const TessellationCurvePoint& p = tessellation_curve()[i];
    EXPECT_EQ(p.level, std::stoi(rows[i].at("level")));
    EXPECT_NEAR(p.mean_rel_distance, std::stod(rows[i].at("mean_dist_rel")), 1e-9) << p.level;
    EXPECT_NEAR(p.frame_ms, std::stod(rows[i].at("ms_per_frame")), 1e-6) << p.level;
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
