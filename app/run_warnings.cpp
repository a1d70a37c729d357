#include "app/run_warnings.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>

#include "engine/scene/tool_path.h"

namespace serosa::app {
namespace {

std::string figure(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

// Seconds to four figures: a path a step longer than the run still reads longer.
std::string seconds(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g s", v);
  return buf;
}

// When the last of the scene's tools that `path` plays stops moving in it, s (nullopt: it plays
// none of them).
std::optional<double> path_end_s(const Scene& scene, const ToolPath& path) {
  std::optional<double> end;
  for (const Tool& t : scene.tools) {
    const bool plays = t.device.kind == DeviceKind::kScript ||
                       (t.device.kind == DeviceKind::kRigEmulated && !t.device.script.empty());
    const std::optional<std::size_t> k = plays ? path.index_of(t.name) : std::nullopt;
    if (!k || path.samples[*k].empty()) continue;
    end = std::max(end.value_or(0.0), path.samples[*k].back().time_s);
  }
  return end;
}

std::string where(const fem::StepTrouble& t) {
  return "step " + std::to_string(t.step) + " at " + figure(t.time_s) + " s";
}

std::string of_steps(std::uint64_t n, std::uint64_t steps) {
  return std::to_string(n) + " of " + std::to_string(steps) + " steps";
}

}  // namespace

std::vector<RunWarning> selection_warnings(const Scene& scene, const AssembledScene& assembled) {
  std::vector<RunWarning> out;
  for (std::size_t k = 0; k < assembled.fixed.size() && k < scene.organs.size(); ++k) {
    const FixedCount& c = assembled.fixed[k];
    const std::string key = "organ[" + std::to_string(k) + "].fixed";
    if (c.box && *c.box == 0) {
      const Box& b = *scene.organs[k].fixed.box;
      out.push_back({"empty_selection",
                     scene.file.string() + ": " + key + ".box of organ '" + c.organ +
                         "' selects no node (box from (" + figure(b.min_m.x()) + ", " +
                         figure(b.min_m.y()) + ", " + figure(b.min_m.z()) + ") to (" +
                         figure(b.max_m.x()) + ", " + figure(b.max_m.y()) + ", " +
                         figure(b.max_m.z()) +
                         ") m, in the scene frame, after the organ's transform): nothing it "
                         "meant to hold is held"});
    }
    if (c.groups && *c.groups == 0)
      out.push_back({"empty_selection", scene.file.string() + ": " + key + ".groups of organ '" +
                                            c.organ + "' selects no node"});
  }
  return out;
}

std::vector<RunWarning> path_warnings(const Scene& scene, const std::filesystem::path& csv,
                                      std::int64_t steps) {
  const std::optional<double> end = path_end_s(scene, read_tool_path(csv));
  const double dt = scene.settings.dt_s;
  const double run_s = static_cast<double>(steps) * dt;
  if (!end || !(dt > 0.0) || *end <= run_s + 0.5 * dt) return {};
  const auto all = static_cast<long long>(std::ceil(*end / dt - 1e-9));
  std::string text("the scripted path ");
  text.append(csv.string())
      .append(" lasts ")
      .append(seconds(*end))
      .append(" but the run stops at ")
      .append(seconds(run_s))
      .append(" (")
      .append(std::to_string(steps))
      .append(" steps, the scene's [headless] steps): --steps ")
      .append(std::to_string(all))
      .append(" runs all of it");
  return {{"path_cut_short", std::move(text)}};
}

std::vector<RunWarning> solver_warnings(const SolverSettings& solver,
                                        const fem::FemStageStats& stats) {
  std::vector<RunWarning> out;
  if (const auto& t = stats.first_not_converged)
    out.push_back(
        {"not_converged",
         "the solver stopped above its tolerance on " + of_steps(stats.not_converged, stats.steps) +
             ", first on " + where(*t) + ": relative residual " + figure(t->residual) + " after " +
             std::to_string(t->iterations) + " iterations against a tolerance of " +
             figure(solver.tolerance) + " and a cap of " + std::to_string(solver.max_iterations) +
             " (raise [solver] max_iterations or tolerance, or use kind = "
             "\"pcg-lagged\")"});
  if (const auto& t = stats.first_energy_gain)
    out.push_back(
        {"energy_gain", "a solve stopped above its tolerance injected energy into the tissue on " +
                            of_steps(stats.energy_gains_after_capped_solve, stats.steps) +
                            ", first on " + where(*t) + " (" + figure(stats.energy_removed_j) +
                            " J taken back out over all " + std::to_string(stats.energy_gains) +
                            " steps that gained energy)"});
  if (const auto& t = stats.first_rejected)
    out.push_back({"rejected", "the solver's result was not applied on " +
                                   of_steps(stats.rejected, stats.steps) + ", first on " +
                                   where(*t) + " (non-finite or diverged solve)"});
  return out;
}

void print_warnings(const std::vector<RunWarning>& warnings) {
  for (const RunWarning& w : warnings) std::fprintf(stderr, "warning: %s\n", w.text.c_str());
}

nlohmann::json warnings_json(const std::vector<RunWarning>& warnings) {
  nlohmann::json out = nlohmann::json::array();
  for (const RunWarning& w : warnings) out.push_back({{"kind", w.kind}, {"text", w.text}});
  return out;
}

nlohmann::json fixed_json(const AssembledScene& assembled) {
  nlohmann::json organs = nlohmann::json::array();
  std::int64_t total = 0;
  for (const FixedCount& c : assembled.fixed) {
    nlohmann::json o{{"organ", c.organ}, {"total", c.total}};
    if (c.box) o["box"] = *c.box;
    if (c.groups) o["groups"] = *c.groups;
    if (c.nodes) o["nodes"] = *c.nodes;
    organs.push_back(std::move(o));
    total += c.total;
  }
  return {{"nodes", total}, {"organs", std::move(organs)}};
}

}  // namespace serosa::app
