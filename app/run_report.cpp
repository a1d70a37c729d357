#include "app/run_report.h"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <numeric>
#include <sstream>

#include "app/compose.h"
#include "app/version.h"
#include "cutting/cutting_stage.h"

namespace serosa::app {
namespace {

using Json = nlohmann::json;

std::string read_text(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

Json close_recording(recording::RecordingWriter& writer, const Scene& scene, std::uint64_t steps) {
  writer.close(steps);
  const auto ws = writer.stats();
  return {{"file", writer.path().string()},
          {"steps", ws.steps},
          {"chunks", ws.chunks},
          {"bytes", ws.bytes},
          {"hash_every", scene.record.hash_every},
          {"snapshots", ws.snapshots}};
}

recording::Header recording_header(const Scene& scene, std::int64_t steps) {
  recording::Header h;
  h.set("serosa", std::string(version_string()));
  h.set("scene_path", std::filesystem::absolute(scene.file).lexically_normal().string());
  h.set("scene_text", read_text(scene.file));
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", scene.settings.dt_s);
  h.set("dt_s", buf);
  h.set("hash_every", std::to_string(scene.record.hash_every));
  std::string names;
  for (const Tool& t : scene.tools) {
    if (!names.empty()) names.push_back(',');
    names.append(t.name);
  }
  h.set("tools", names);
  h.set("steps_planned", std::to_string(steps));
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &utc);
  h.set("created_utc", buf);
  return h;
}

Json cutting_json(const Composition& comp) {
  Json j = Json::object();
  if (comp.cutting) {
    const CuttingStageStats& c = comp.cutting->stats();
    j = {{"strokes", c.strokes},
         {"sweeps", c.sweeps},
         {"cuts", c.cuts},
         {"tets_removed", c.tets_removed},
         {"tets_added", c.tets_added},
         {"nodes_added", c.nodes_added},
         {"degenerate_tets", c.degenerate_tets},
         {"strokes_on_clip", c.strokes_on_clip},
         {"hook_strokes", c.hook_strokes},
         {"coagulated_nodes", c.coagulated_nodes}};
    if (comp.cutting->num_staplers() > 0) {
      j["stapler_fires"] = c.stapler_fires;
      j["stapler_fires_held"] = c.stapler_fires_held;
    }
    Json strokes = Json::array();
    for (const cutting::StrokeReport& r : c.stroke_reports)
      strokes.push_back({{"first_step", r.first_step},
                         {"last_step", r.last_step},
                         {"steps", r.steps},
                         {"polygons", r.polygons},
                         {"cuts", r.cuts},
                         {"tets_crossed", r.tets_crossed},
                         {"tets_created", r.tets_created},
                         {"pinned", r.pinned},
                         {"swept_area_m2", r.swept_area_m2},
                         {"crack_area_m2", r.crack_area_m2},
                         {"deviation_m", r.deviation_m},
                         {"bent", r.bent},
                         {"crack_deviation_m", r.crack_deviation_m},
                         {"min_quality", r.min_quality},
                         {"on_clip", r.on_clip}});
    j["per_stroke"] = std::move(strokes);
    if (c.validated > 0) {
      j["validated"] = c.validated;
      j["invalid"] = c.invalid;
      j["problems"] = c.problems;
    }
  }
  return j;
}

Json step_time_json(const std::vector<double>& ms, const std::vector<StepDetail>& details) {
  if (ms.empty()) return {{"p50", 0.0}, {"p99", 0.0}, {"max", 0.0}, {"slowest", Json::array()}};
  std::vector<std::size_t> order(ms.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  // Slowest first; equal times by step, so the report does not depend on the sort.
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return ms[a] != ms[b] ? ms[a] > ms[b] : a < b; });
  const auto at = [&](double q) {  // the q-quantile counted from the fastest step
    const auto k =
        std::min(ms.size() - 1, static_cast<std::size_t>(q * static_cast<double>(ms.size())));
    return ms[order[ms.size() - 1 - k]];
  };
  Json slowest = Json::array();
  for (std::size_t i = 0; i < std::min<std::size_t>(8, order.size()); ++i) {
    Json s = {{"step", order[i]}, {"ms", ms[order[i]]}};
    if (order[i] < details.size()) {
      const StepDetail& d = details[order[i]];
      s["fem_ms"] = d.fem_ms;
      s["cg_iterations"] = d.cg_iterations;
      s["factor_refresh"] = d.factor_refresh;
      s["factor_patch"] = d.factor_patch;
      s["factor_wait_ms"] = d.factor_wait_ms;
    }
    slowest.push_back(std::move(s));
  }
  return {{"p50", at(0.5)}, {"p99", at(0.99)}, {"max", ms[order[0]]}, {"slowest", slowest}};
}

std::string hash_hex(std::uint64_t hash) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(hash));
  return buf;
}

}  // namespace serosa::app
