#include "cutting/cutting_stage.h"

#include <algorithm>
#include <cmath>

#include "cutting/cut_method.h"
#include "cutting/tet_bvh.h"
#include "cutting/validate.h"
#include "engine/sim_state.h"
#include "engine/state_codec.h"
#include "engine/tool_geometry.h"

namespace serosa::cutting {

CuttingStage::CuttingStage(const Scene& scene, CuttingStageOptions options) : m_options(options) {
  for (std::size_t i = 0; i < scene.tools.size(); ++i)
    if (scene.tools[i].kind == ToolKind::kScissors)
      m_scissors.push_back({i, std::nullopt, std::nullopt});
  m_cut_options.classify_rel = scene.cutting.tolerance;
  switch (scene.cutting.method) {
    case serosa::CutMethod::kPattern:
      m_method = CutMethod::kPattern;
      break;
    case serosa::CutMethod::kRemove:
      m_method = CutMethod::kRemove;
      break;
    case serosa::CutMethod::kSnap:
      m_method = CutMethod::kSnap;
      break;
  }
}

CuttingStage::~CuttingStage() = default;

std::optional<cutting::ConvexPolygon> sector_polygon(const ToolFrame& frame, double a0, double a1,
                                                     double length_m) {
  if (a1 < a0) std::swap(a0, a1);
  const double span = a1 - a0;
  if (!(span > 1e-9) || !(length_m > 0.0)) return std::nullopt;
  const int segments = std::max(1, static_cast<int>(std::ceil(span / kStrokeArcStep)));
  std::vector<Vec3> points{frame.hinge};
  // Counter-clockwise seen from +pin: from the side (+a) towards the other side.
  for (int k = 0; k <= segments; ++k) {
    const double a = a1 - span * static_cast<double>(k) / static_cast<double>(segments);
    points.push_back(frame.hinge +
                     length_m * (std::cos(a) * frame.forward + std::sin(a) * frame.side));
  }
  return cutting::ConvexPolygon::make(std::move(points));
}

namespace {

// Whether two poses hold the blades in the same place, within the stroke tolerances.
bool same_place(const ToolState& a, const ToolState& b) {
  const ToolFrame fa = tool_frame(a), fb = tool_frame(b);
  if (!((fa.hinge - fb.hinge).norm() <= kStrokeHingeTol)) return false;
  const double turn =
      std::max((fa.forward - fb.forward).norm(), (fa.side - fb.side).norm());  // ~ angle, rad
  return turn <= kStrokeAngleTol;
}

}  // namespace

void CuttingStage::step(const StepContext& ctx, SimState& state) {
  state.handoff.cuts.clear();  // the FEM stage of this step has taken the last step's
  if (!m_scissors.empty()) cutting::reserve_for_cuts(state.mesh);  // no realloc in the first cut
  for (Scissors& s : m_scissors) {
    if (s.tool >= state.tools.size()) continue;
    const ToolState now = state.tools[s.tool];
    const std::optional<ToolState> before = s.before;
    s.before = now;
    if (!before) continue;
    const bool closing = now.jaw_rad < before->jaw_rad;
    // A stationary stroke goes on while the jaws close or pause and the scissors stay in its
    // place.
    if (s.stroke) {
      const bool opening = now.jaw_rad > before->jaw_rad;
      if (!opening && same_place(*s.stroke, now)) {
        if (closing && now.jaw_rad <= 0.0) {  // closed: nothing more to sweep
          const ToolState start = *s.stroke;
          s.stroke.reset();
          flush_stroke(ctx, state, s.tool, start, 0.0);
        }
        continue;
      }
      // Opened again or moved: cut what the stroke swept up to the previous pose.
      const ToolState start = *s.stroke;
      s.stroke.reset();
      flush_stroke(ctx, state, s.tool, start, before->jaw_rad);
      if (!closing) continue;
    } else if (!closing) {
      continue;
    }
    // Only closing jaws cut: the blades slide past each other over the tissue between them.
    if (same_place(*before, now)) {
      s.stroke = *before;  // a stationary stroke begins: cut it as a whole later
      if (now.jaw_rad <= 0.0) {
        s.stroke.reset();
        flush_stroke(ctx, state, s.tool, *before, 0.0);
      }
      continue;
    }
    // Moving while closing: each blade sweeps the quad between its two poses.
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

void CuttingStage::flush_stroke(const StepContext& ctx, SimState& state, std::size_t tool,
                                const ToolState& start, double end_jaw_rad) {
  const ToolFrame f = tool_frame(start);
  const double a0 = 0.5 * start.jaw_rad, a1 = 0.5 * std::max(end_jaw_rad, 0.0);
  if (!(a0 > a1)) return;
  ++m_stats.strokes;
  if (a1 <= 0.0) {
    // Fully closed: the two blades swept one sector across the shaft axis.
    ++m_stats.sweeps;
    if (auto p = sector_polygon(f, -a0, a0, kJawLength)) {
      cut(ctx, state, tool, 0, *p);
    } else {
      ++m_stats.degenerate_sweeps;
    }
    return;
  }
  for (int blade = 0; blade < 2; ++blade) {
    const double sign = blade == 0 ? 1.0 : -1.0;
    ++m_stats.sweeps;
    if (auto p = sector_polygon(f, sign * a1, sign * a0, kJawLength)) {
      cut(ctx, state, tool, blade, *p);
    } else {
      ++m_stats.degenerate_sweeps;
    }
  }
}

void CuttingStage::cut(const StepContext& ctx, SimState& state, std::size_t tool, int blade,
                       const cutting::ConvexPolygon& polygon) {
  TetMesh& mesh = state.mesh;
  // Candidate search: a BVH over current positions, built once, updated locally after each of our
  // cuts (cost follows the tets touched), refitted once a step; rebuilt only when the topology
  // changed behind our back.
  if (!m_bvh || m_bvh_version != mesh.topology_version) {
    m_bvh = std::make_unique<cutting::TetBvh>(mesh);
    m_bvh_version = mesh.topology_version;
    m_bvh_step = ctx.step;
  } else if (m_bvh_step != ctx.step) {
    m_bvh->refit(mesh);
    m_bvh_step = ctx.step;
  }
  cutting::CutResult result = cut_with(m_method, mesh, polygon, m_cut_options, m_bvh->as_query());
  if (result.delta.empty()) return;

  CutEvent applied;
  applied.step = ctx.step;
  applied.tool = tool;
  applied.blade = blade;
  applied.polygon_m = polygon.points();
  for (std::int32_t t : result.delta.removed_tets) {
    const Tet& tet = mesh.tets[static_cast<std::size_t>(t)];
    Vec3 c = Vec3::Zero();
    for (std::int32_t n : tet) c += mesh.x[static_cast<std::size_t>(n)];
    applied.removed_centroids_m.push_back(0.25 * c);
    applied.removed_volumes_m3.push_back(mesh.rest_volume(t));
  }
  std::optional<TetMesh> before;
  // The invariants hold for the paper's method; removal loses volume and snapping moves nodes.
  if (m_options.validate && m_method == CutMethod::kPattern) before = mesh;

  apply(mesh, result.delta);
  m_bvh->update(mesh, result.delta);
  m_bvh_version = mesh.topology_version;

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
  applied.delta = std::move(result.delta);
  state.handoff.cuts.push_back(std::move(applied));
}

namespace {

void write_pose(StateWriter& out, const std::optional<ToolState>& t) {
  out.u8(t ? 1 : 0);
  if (t) out.tool_state(*t);
}

std::optional<ToolState> read_pose(StateReader& in) {
  if (in.u8() == 0) return std::nullopt;
  return in.tool_state();
}

}  // namespace

void CuttingStage::save(StateWriter& out) const {
  out.u32(static_cast<std::uint32_t>(m_scissors.size()));
  for (const Scissors& s : m_scissors) {
    write_pose(out, s.before);
    write_pose(out, s.stroke);
  }
}

void CuttingStage::restore(StateReader& in, SimState& /*state*/) {
  if (in.u32() != m_scissors.size()) in.fail("another number of scissors than the scene's");
  for (Scissors& s : m_scissors) {
    s.before = read_pose(in);
    s.stroke = read_pose(in);
  }
  m_bvh.reset();  // candidates are sorted: a fresh tree finds the same ones
}

}  // namespace serosa::cutting
