#include "app/cutting_stage.h"

#include <algorithm>

#include "app/tool_geometry.h"
#include "cutting/tet_bvh.h"
#include "cutting/validate.h"
#include "engine/sim_state.h"

namespace serosa::app {

CuttingStage::CuttingStage(const Scene& scene, CuttingStageOptions options) : m_options(options) {
  for (std::size_t i = 0; i < scene.tools.size(); ++i)
    if (scene.tools[i].kind == ToolKind::kScissors) m_scissors.push_back({i, std::nullopt});
  m_cut_options.classify_rel = scene.cutting.tolerance;
}

CuttingStage::~CuttingStage() = default;

void CuttingStage::step(const StepContext& ctx, SimState& state) {
  for (Scissors& s : m_scissors) {
    if (s.tool >= state.tools.size()) continue;
    const ToolState now = state.tools[s.tool];
    const std::optional<ToolState> before = s.before;
    s.before = now;
    // Only closing jaws cut: the blades slide past each other over the tissue between them.
    if (!before || !(now.jaw_rad < before->jaw_rad)) continue;
    const ToolFrame f0 = tool_frame(*before);
    const ToolFrame f1 = tool_frame(now);
    for (int blade = 0; blade < 2; ++blade) {
      const cutting::BladeEdge e0{f0.hinge, jaw_tip(f0, before->jaw_rad, blade)};
      const cutting::BladeEdge e1{f1.hinge, jaw_tip(f1, now.jaw_rad, blade)};
      ++m_stats.sweeps;
      const auto polygon = cutting::sweep_polygon(e0, e1, m_sweep_warnings);
      if (!polygon) {
        ++m_stats.degenerate_sweeps;
        continue;
      }
      cut(ctx, state, s.tool, blade, *polygon);
    }
  }
}

void CuttingStage::cut(const StepContext& ctx, SimState& state, std::size_t tool, int blade,
                       const cutting::ConvexPolygon& polygon) {
  TetMesh& mesh = state.mesh;
  // Candidate search: a BVH over current positions, rebuilt after a cut, refitted once a step.
  if (!m_bvh || m_bvh_version != mesh.topology_version) {
    m_bvh = std::make_unique<cutting::TetBvh>(mesh);
    m_bvh_version = mesh.topology_version;
    m_bvh_step = ctx.step;
  } else if (m_bvh_step != ctx.step) {
    m_bvh->refit(mesh);
    m_bvh_step = ctx.step;
  }
  cutting::CutResult result = cutting::cut_mesh(mesh, polygon, m_cut_options, m_bvh->as_query());
  if (result.delta.empty()) return;

  CutApplied applied;
  applied.step = ctx.step;
  applied.tool = tool;
  applied.blade = blade;
  applied.polygon = &polygon;
  applied.stats = &result.stats;
  for (std::int32_t t : result.delta.removed_tets) {
    const Tet& tet = mesh.tets[static_cast<std::size_t>(t)];
    Vec3 c = Vec3::Zero();
    for (std::int32_t n : tet) c += mesh.x[static_cast<std::size_t>(n)];
    applied.removed_centroids_m.push_back(0.25 * c);
    applied.removed_volumes_m3.push_back(mesh.rest_volume(t));
  }
  std::optional<TetMesh> before;
  if (m_options.validate) before = mesh;

  apply(mesh, result.delta);
  applied.delta = &result.delta;

  ++m_stats.cuts;
  m_stats.tets_removed += static_cast<std::int64_t>(result.delta.removed_tets.size());
  m_stats.tets_added += static_cast<std::int64_t>(result.delta.added_tets.size());
  m_stats.nodes_added += static_cast<std::int64_t>(result.delta.added_nodes.size());
  m_stats.degenerate_tets += result.stats.degenerate_tets;
  if (before) {
    const cutting::CutCheckReport r = cutting::check_cut(*before, mesh, polygon);
    ++m_stats.validated;
    if (!r.ok) {
      ++m_stats.invalid;
      for (const std::string& p : r.problems)
        if (m_stats.problems.size() < 20) {
          std::string line = "step ";
          line.append(std::to_string(ctx.step)).append(": ").append(p);
          m_stats.problems.push_back(std::move(line));
        }
    }
  }
  for (const CutListener& l : m_listeners) l(state, applied);
}

}  // namespace serosa::app
