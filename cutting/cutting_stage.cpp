#include "cutting/cutting_stage.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "cutting/clip_guard.h"
#include "cutting/cut_areas.h"
#include "cutting/cut_method.h"
#include "cutting/tet_bvh.h"
#include "cutting/validate.h"
#include "engine/hook.h"
#include "engine/instrument_hold.h"
#include "engine/sim_state.h"
#include "engine/tool_geometry.h"

namespace serosa::cutting {

CuttingStage::CuttingStage(const Scene& scene, CuttingStageOptions options) : m_options(options) {
  for (std::size_t i = 0; i < scene.tools.size(); ++i) {
    if (options.scissors && scene.tools[i].kind == ToolKind::kScissors) m_scissors.push_back(i);
    if (options.hooks && scene.tools[i].kind == ToolKind::kHook) m_hooks.push_back(i);
    if (options.staplers && scene.tools[i].kind == ToolKind::kStapler) m_staplers.push_back(i);
  }
  m_cut_options.classify_rel = scene.cutting.tolerance;
  m_swept_strokes = scene.cutting.strokes == StrokeSurfaceKind::kSwept;
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

namespace {

// What a stroke's report says before it is cut.
StrokeReport stroke_report(std::uint64_t first_step, std::uint64_t last_step, std::uint64_t steps,
                           const StrokePolygons& polygons) {
  StrokeReport r;
  r.first_step = first_step;
  r.last_step = last_step;
  r.steps = steps;
  r.polygons = polygons.polygons.size();
  r.deviation_m = polygons.fit.deviation_m;
  return r;
}

double hinge_distance(const ToolState& a, const ToolState& b) {
  return (tool_frame(a).hinge - tool_frame(b).hinge).norm();
}

}  // namespace

void CuttingStage::step(const StepContext& ctx, SimState& state) {
  state.events.cuts.clear();  // the FEM stage of this step has taken the last step's
  if (!m_scissors.empty() || !m_hooks.empty() || !m_staplers.empty() || !m_queued.empty())
    cutting::reserve_for_cuts(state.mesh);  // no realloc in the first cut
  cut_queued(ctx, state);
  CuttingBlock& b = state.blocks.cutting;
  if (b.scissors.size() != m_scissors.size()) b.scissors.resize(m_scissors.size());  // the first
  if (b.hooks.size() != m_hooks.size()) b.hooks.resize(m_hooks.size());              // step
  if (b.staplers.size() != m_staplers.size()) b.staplers.resize(m_staplers.size());
  for (std::size_t k = 0; k < m_scissors.size(); ++k) {
    const std::size_t tool = m_scissors[k];
    if (tool >= state.tools.size()) continue;
    Follow& s = b.scissors[k];
    const ToolState now = state.tools[tool];
    if (in_port(now)) {  // withdrawn: the blades left the tissue; what they closed on stays whole
      s = Follow{};
      continue;
    }
    const std::optional<ToolState> before = s.before;
    s.before = now;
    if (before) follow(ctx, state, tool, s, *before, now);
  }
  for (std::size_t k = 0; k < m_staplers.size(); ++k) {
    const std::size_t tool = m_staplers[k];
    if (tool >= state.tools.size()) continue;
    const ToolState now = state.tools[tool];
    if (const std::optional<double> fired = b.staplers[k].update(now.jaw_rad))
      fire(ctx, state, tool, now, *fired);
  }
  if (m_hooks.empty()) return;
  b.coagulated.resize(static_cast<std::size_t>(state.mesh.num_nodes()), 0);
  for (std::size_t k = 0; k < m_hooks.size(); ++k) {
    const std::size_t tool = m_hooks[k];
    if (tool < state.tools.size())
      follow_hook(ctx, state, tool, b.hooks[k], live_hook(b.hooks[k], state.tools[tool]));
  }
  inherit_coagulation(state, 0);
}

void CuttingStage::cut_queued(const StepContext& ctx, SimState& state) {
  m_queued_reports.clear();
  for (const cutting::ConvexPolygon& polygon : m_queued) {
    StrokeReport report;
    report.first_step = report.last_step = ctx.step;
    report.steps = report.polygons = 1;
    cut(ctx, state, kNoTool, 0, polygon, nullptr, report);
    m_queued_reports.push_back(report);
  }
  m_queued.clear();
}

// A hook withdrawn into its port: the current goes off where it left the tissue (what it burnt
// through opens), and it burns nothing out there.
ToolState CuttingStage::live_hook(const Follow& h, const ToolState& now) {
  if (!in_port(now)) return now;
  ToolState off = h.before && !in_port(*h.before) ? *h.before : now;
  off.buttons &= ~kPedalButton;
  set_in_port(off, true);
  return off;
}

void CuttingStage::follow_hook(const StepContext& ctx, SimState& state, std::size_t tool, Follow& h,
                               const ToolState& now) {
  const std::optional<ToolState> before = h.before;
  h.before = now;
  if (!pedal_down(now)) {  // the current is off: the path it burnt through opens
    if (!h.stroke) return;
    ToolState end = now;
    end.jaw_rad = 0.0;  // one region over every sample
    const std::uint64_t steps = h.stroke->steps;
    const StrokePolygons polys = ScissorsStroke(std::move(*h.stroke), std::move(m_scratch))
                                     .polygons(state.mesh, end, kStrokeClosedRad);
    StrokeReport report = stroke_report(h.first_step, ctx.step, steps, polys);
    h.stroke.reset();
    ++m_stats.strokes;
    ++m_stats.hook_strokes;
    if (polys.polygons.empty()) ++m_stats.degenerate_sweeps;
    const std::size_t first_cut = state.events.cuts.size();
    cut_stroke(ctx, state, tool, polys, report);
    coagulate_cut(state, first_cut);  // what the current divided it also dried
    return;
  }
  const HookSegment seg = hook_segment(now);
  coagulate(ctx, state, seg.a, seg.b);
  if (!before || !pedal_down(*before)) return;  // the stroke starts with the next step
  refresh_bvh(ctx, state.mesh);
  ScissorsStroke stroke = h.stroke ? ScissorsStroke(std::move(*h.stroke), std::move(m_scratch))
                                   : ScissorsStroke(*before, state.mesh.topology_version);
  if (!h.stroke) {
    h.first_step = ctx.step;
    const HookSegment s0 = hook_segment(*before);
    stroke.add_segment(s0.a, s0.b, state.mesh, *m_bvh);
  }
  // Samples along the way, close enough that their hull is the path the crook swept.
  const HookSegment s0 = hook_segment(*before);
  const double travel = std::max((seg.a - s0.a).norm(), (seg.b - s0.b).norm());
  const double steps = std::ceil(travel / kHookSampleStep);
  const int n = std::isfinite(steps) ? std::clamp(static_cast<int>(steps), 1, 64) : 1;
  for (int j = 1; j <= n; ++j) {
    const HookSegment sj =
        hook_segment(interpolate(*before, now, static_cast<double>(j) / static_cast<double>(n)));
    stroke.add_segment(sj.a, sj.b, state.mesh, *m_bvh);
  }
  stroke.count_step();
  h.stroke = stroke.release();
  m_scratch = stroke.release_scratch();
}

void CuttingStage::coagulate(const StepContext& ctx, SimState& state, const Vec3& a,
                             const Vec3& b) {
  refresh_bvh(ctx, state.mesh);
  const Vec3 r = Vec3::Constant(kCoagulationRadius);
  m_near.clear();
  m_bvh->query(a.cwiseMin(b) - r, a.cwiseMax(b) + r, m_near);
  std::vector<std::uint8_t>& marks = state.blocks.cutting.coagulated;
  marks.resize(static_cast<std::size_t>(state.mesh.num_nodes()), 0);  // after a cut this step
  bool added = false;
  for (std::int32_t t : m_near)
    for (std::int32_t n : state.mesh.tets[static_cast<std::size_t>(t)]) {
      const auto un = static_cast<std::size_t>(n);
      if (marks[un] != 0 || distance_to_segment(state.mesh.x[un], a, b) > kCoagulationRadius)
        continue;
      marks[un] = 1;
      ++m_stats.coagulated_nodes;
      added = true;
    }
  if (added) ++state.blocks.cutting.coagulated_version;
}

void CuttingStage::coagulate_cut(SimState& state, std::size_t first_cut) {
  std::vector<std::uint8_t>& marks = state.blocks.cutting.coagulated;
  marks.resize(static_cast<std::size_t>(state.mesh.num_nodes()), 0);
  std::size_t added = 0;
  for (std::size_t c = first_cut; c < state.events.cuts.size(); ++c)
    added += state.events.cuts[c].delta.added_nodes.size();
  for (std::size_t n = marks.size() - added; n < marks.size(); ++n)
    if (marks[n] == 0) {
      marks[n] = 1;
      ++m_stats.coagulated_nodes;
    }
  if (added > 0) ++state.blocks.cutting.coagulated_version;
}

// New nodes are numbered after the old ones, cut by cut: each takes a mark if a parent has one.
void CuttingStage::inherit_coagulation(SimState& state, std::size_t first_cut) {
  std::vector<std::uint8_t>& marks = state.blocks.cutting.coagulated;
  marks.resize(static_cast<std::size_t>(state.mesh.num_nodes()), 0);
  std::size_t added = 0;
  for (std::size_t c = first_cut; c < state.events.cuts.size(); ++c)
    added += state.events.cuts[c].delta.added_nodes.size();
  std::size_t next = marks.size() - added;
  bool changed = false;
  for (std::size_t c = first_cut; c < state.events.cuts.size(); ++c)
    for (const NodeParent& p : state.events.cuts[c].delta.added_nodes) {
      for (int k = 0; k < p.count && marks[next] == 0; ++k)
        if (marks[static_cast<std::size_t>(p.nodes[static_cast<std::size_t>(k)])] != 0) {
          marks[next] = 1;
          ++m_stats.coagulated_nodes;
          changed = true;
          break;
        }
      ++next;
    }
  if (changed) ++state.blocks.cutting.coagulated_version;
}

void CuttingStage::follow(const StepContext& ctx, SimState& state, std::size_t tool, Follow& s,
                          const ToolState& before, const ToolState& now) {
  // Only closing jaws cut: the blades slide past each other over the tissue between them.
  const bool closing = now.jaw_rad < before.jaw_rad;
  if (s.stroke && s.paused && !closing) {
    // Jaws that only held still (a device sample that did not come in time for this step, a
    // hand that hesitates) have not reopened, however little they had closed.
    const bool reopened = now.jaw_rad > s.paused->jaw_rad &&
                          now.jaw_rad >= s.stroke->start.jaw_rad - kStrokeReopenTol;
    const bool drawn_away = hinge_distance(now, *s.paused) > kStrokeDriftTol;
    if (reopened || drawn_away) {  // cut what it swept, up to where the jaws were most closed
      end_stroke(ctx, state, tool, s, *s.paused);
      return;
    }
  }
  if (!closing || before.jaw_rad <= kStrokeClosedRad) return;  // (closed already: nothing between)
  extend(ctx, state, s, before, now);
  if (now.jaw_rad <= kStrokeClosedRad) end_stroke(ctx, state, tool, s, now);  // the blades met
}

void CuttingStage::extend(const StepContext& ctx, const SimState& state, Follow& s,
                          const ToolState& before, const ToolState& now) {
  const TetMesh& mesh = state.mesh;
  refresh_bvh(ctx, mesh);
  if (!s.stroke) s.first_step = ctx.step;
  ScissorsStroke stroke = s.stroke ? ScissorsStroke(std::move(*s.stroke), std::move(m_scratch))
                                   : ScissorsStroke(before, mesh.topology_version);
  stroke.sweep(before, now, mesh, *m_bvh);
  s.stroke = stroke.release();
  m_scratch = stroke.release_scratch();
  if (!s.paused || now.jaw_rad <= s.paused->jaw_rad) s.paused = now;
}

void CuttingStage::end_stroke(const StepContext& ctx, SimState& state, std::size_t tool, Follow& s,
                              ToolState end) {
  if (!s.stroke) return;
  const std::uint64_t steps = s.stroke->steps;
  const StrokePolygons cut_with_these = ScissorsStroke(std::move(*s.stroke), std::move(m_scratch))
                                            .polygons(state.mesh, end, kStrokeClosedRad);
  StrokeReport report = stroke_report(s.first_step, ctx.step, steps, cut_with_these);
  s.stroke.reset();
  s.paused.reset();
  ++m_stats.strokes;
  if (cut_with_these.polygons.empty()) ++m_stats.degenerate_sweeps;
  cut_stroke(ctx, state, tool, cut_with_these, report);
}

void CuttingStage::fire(const StepContext& ctx, SimState& state, std::size_t tool,
                        const ToolState& ts, double opening_rad) {
  const bool laid =
      std::any_of(state.shared.clips.begin(), state.shared.clips.end(), [&](const Clip& c) {
        return c.kind == Clip::Kind::kStaple && c.tool == tool && c.placed_s == ctx.time_s;
      });
  if (!laid) {
    ++m_stats.stapler_fires_held;
    return;
  }
  const std::array<Vec3, 4> corners = knife_polygon(stapler_jaws(ts, opening_rad));
  const std::optional<ConvexPolygon> knife =
      ConvexPolygon::make(std::vector<Vec3>(corners.begin(), corners.end()));
  if (!knife) {  // a non-finite pose: nothing to cut along
    ++m_stats.degenerate_sweeps;
    return;
  }
  StrokeReport report;
  report.first_step = ctx.step;
  report.last_step = ctx.step;
  report.steps = 1;
  report.polygons = 1;
  ++m_stats.strokes;
  ++m_stats.stapler_fires;
  ++m_stats.sweeps;
  cut(ctx, state, tool, 0, *knife, nullptr, report);
  if (m_stats.stroke_reports.size() < kMaxStrokeReports) m_stats.stroke_reports.push_back(report);
}

void CuttingStage::cut_stroke(const StepContext& ctx, SimState& state, std::size_t tool,
                              const StrokePolygons& polygons, StrokeReport& report) {
  // Blades that closed on a clip met titanium: the tissue they hold is not divided.
  report.on_clip = std::any_of(
      polygons.polygons.begin(), polygons.polygons.end(),
      [&](const ConvexPolygon& p) { return polygon_meets_clips(p, state.shared.clips); });
  if (report.on_clip) {
    ++m_stats.strokes_on_clip;
  } else {
    std::optional<FlattenedPositions> flat = flattening(ctx, state, polygons, report);
    for (std::size_t k = 0; k < polygons.polygons.size(); ++k) {
      ++m_stats.sweeps;
      cut(ctx, state, tool, polygons.blades[k], polygons.polygons[k], flat ? &*flat : nullptr,
          report);
    }
  }
  if (m_stats.stroke_reports.size() < kMaxStrokeReports) m_stats.stroke_reports.push_back(report);
}

std::optional<FlattenedPositions> CuttingStage::flattening(const StepContext& ctx, SimState& state,
                                                           const StrokePolygons& polygons,
                                                           StrokeReport& report) {
  refresh_bvh(ctx, state.mesh);
  const std::span<const Vec3> points = polygons.surface_points_m;
  report.crack_deviation_m = crack_deviation(state.mesh, *m_bvh, points, polygons.fit, nullptr);
  // Only the paper's pattern cut classifies against a plane that flattening can bend.
  if (!polygons.surface || m_method != CutMethod::kPattern || !m_swept_strokes) return std::nullopt;
  std::optional<FlattenedPositions> flat(std::in_place, *polygons.surface);
  if (!flattening_keeps_tets(state.mesh, *flat, polygons.polygons, *m_bvh)) return std::nullopt;
  // A surface that folds over its plane interpolates between its sheets: the plane may then be
  // nearer the blades' path in the tissue than the bent crack.
  const double bent = crack_deviation(state.mesh, *m_bvh, points, polygons.fit, &*flat);
  if (!(bent < report.crack_deviation_m)) return std::nullopt;
  report.crack_deviation_m = bent;
  report.bent = true;
  return flat;
}

void CuttingStage::refresh_bvh(const StepContext& ctx, const TetMesh& mesh) {
  // A BVH over current positions, built once, updated locally after each of our cuts (cost
  // follows the tets touched), refitted once a step; rebuilt only when the topology changed
  // behind our back.
  if (!m_bvh || m_bvh_version != mesh.topology_version) {
    m_bvh = std::make_unique<cutting::TetBvh>(mesh);
    m_bvh_version = mesh.topology_version;
    m_bvh_step = ctx.step;
  } else if (m_bvh_step != ctx.step) {
    m_bvh->refit(mesh);
    m_bvh_step = ctx.step;
  }
}

void CuttingStage::cut(const StepContext& ctx, SimState& state, std::size_t tool, int blade,
                       const cutting::ConvexPolygon& polygon, FlattenedPositions* flat,
                       StrokeReport& report) {
  TetMesh& mesh = state.mesh;
  refresh_bvh(ctx, mesh);
  cutting::CutResult result;
  if (flat) {
    FlatCutResult r = cut_flattened(mesh, *flat, polygon, m_cut_options, *m_bvh);
    result = std::move(r.cut);
    report.swept_area_m2 += r.swept_area_m2;
  } else {
    result = cut_with(m_method, mesh, polygon, m_cut_options, m_bvh->as_query());
    if (!result.delta.empty())
      report.swept_area_m2 += swept_area(mesh, result.delta.removed_tets, polygon);
  }
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
    applied.removed_groups.push_back(mesh.group[static_cast<std::size_t>(t)]);
  }
  std::optional<TetMesh> before;
  // The invariants hold for the paper's method; removal loses volume and snapping moves nodes.
  // A bent stroke's cut is checked as what it is: the flattened mesh cut by the polygon.
  if (m_options.validate && m_method == CutMethod::kPattern)
    before = flat ? flattened_copy(mesh, *flat) : mesh;

  apply(mesh, result.delta);
  m_bvh->update(mesh, result.delta);
  m_bvh_version = mesh.topology_version;
  if (flat) flat->added(mesh, result.delta);

  ++report.cuts;
  report.tets_crossed += static_cast<std::int64_t>(result.delta.removed_tets.size());
  report.tets_created += static_cast<std::int64_t>(result.delta.added_tets.size());
  report.pinned += result.stats.tets_pinned;
  const double crack_tol = 2.0 * result.stats.tolerance_m + 1e-12;
  report.crack_area_m2 += flat ? flattened_crack_area(mesh, *flat, result.delta, polygon, crack_tol)
                               : crack_area(mesh, result.delta, polygon, crack_tol);
  report.min_quality = std::min(report.min_quality, min_added_quality(mesh, result.delta));

  ++m_stats.cuts;
  m_stats.tets_removed += static_cast<std::int64_t>(result.delta.removed_tets.size());
  m_stats.tets_added += static_cast<std::int64_t>(result.delta.added_tets.size());
  m_stats.nodes_added += static_cast<std::int64_t>(result.delta.added_nodes.size());
  m_stats.degenerate_tets += result.stats.degenerate_tets;
  if (before) {
    // Nodes within the cut's classification tolerance of the plane count as on it.
    cutting::CutCheckOptions co;
    co.geometry_tol_m = 4.0 * result.stats.tolerance_m + 1e-12;
    co.plane_tol_m = result.stats.tolerance_m;
    const cutting::CutCheckReport r =
        flat ? cutting::check_cut(*before, flattened_copy(mesh, *flat), polygon, co)
             : cutting::check_cut(*before, mesh, polygon, co);
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
  state.events.cuts.push_back(std::move(applied));
}

void CuttingStage::adopt(SimState& state) {
  const CuttingBlock& b = state.blocks.cutting;
  const auto fits = [&](std::size_t size, std::size_t scene, const char* what) {
    if ((state.step > 0 || size != 0) && size != scene)  // (the first step shapes them)
      throw BlockMismatch(std::string("strokes of ") + std::to_string(size) + " " + what +
                          ", the scene has " + std::to_string(scene));
  };
  fits(b.scissors.size(), m_scissors.size(), "scissors");
  fits(b.hooks.size(), m_hooks.size(), "hooks");
  fits(b.staplers.size(), m_staplers.size(), "staplers");
  if (b.coagulated.size() > static_cast<std::size_t>(state.mesh.num_nodes()))
    throw BlockMismatch("coagulation marks for more nodes than the mesh has");
  m_bvh.reset();  // candidates are sorted: a fresh tree finds the same ones
}

}  // namespace serosa::cutting
